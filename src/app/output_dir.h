#pragma once
// The output directory of `simulate` and `render`: created, checked for writability, and
// refused when it holds a previous run unless --overwrite is given. A new run into an
// old directory would otherwise mix its files with the old ones: stale frames after the
// new last frame would end up in the video, and an old summary.json would describe a
// run that is no longer there.
#include <filesystem>
#include <string>
#include <vector>

namespace sluice::app {

// The entries a run leaves in its directory (files and folders, relative to it),
// including the temporary names of an interrupted run. `scene_name` names the video.
std::vector<std::string> previous_run_files(const std::string& scene_name);

// Creates `dir` (and its parents) and checks that files can be made in it. When it
// holds any of previous_run_files(): throws OutputError naming the directory, the
// entries and --overwrite, or with `overwrite` removes those entries (only those: a
// directory shared with other files keeps them), unless one of them is `input` (the scene
// file: refused). Throws OutputError.
void prepare_output_directory(const std::filesystem::path& dir, bool overwrite, const std::string& scene_name,
                              const std::string& input = "");

// The files a command other than simulate/render (bench) writes straight into `dir`: when
// any of `names` exists there, throws OutputError naming the directory, the files and
// --overwrite, or with `overwrite` removes them (a stale bench.png must not outlive its
// table). Throws OutputError.
void refuse_previous_files(const std::filesystem::path& dir, const std::vector<std::string>& names, bool overwrite);

}  // namespace sluice::app
