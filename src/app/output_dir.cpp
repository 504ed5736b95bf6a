#include "app/output_dir.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "app/run.h"
#include "io/export.h"
#include "io/output.h"
#include "render/video.h"

namespace sluice::app {

namespace fs = std::filesystem;

namespace {

// Folders of per-frame files (frames/, particles/) count as a previous run only when
// something is in them: an empty frames/ left by a run that failed before its first
// frame (e.g. no EGL display) must not block the retry.
bool holds_run_output(const fs::path& entry) {
  std::error_code ec;
  const fs::file_status st = fs::symlink_status(entry, ec);
  if (ec || !fs::exists(st)) return false;
  if (!fs::is_directory(st)) return true;
  return !fs::is_empty(entry, ec) && !ec;
}

bool has_digit(const std::string& name) {
  return std::any_of(name.begin(), name.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// What a run writes inside `folder` (frames/ or particles/), with the temporary names:
// in frames/ a PNG whose name holds a frame number (whatever --frame-pattern named it),
// in particles/ frame_NNNNN.csv, .vtp (.vtk of older versions) and the collection.
// Nothing else there is removed.
bool is_frame_file(const std::string& folder, std::string name) {
  if (name.ends_with(".tmp")) name.resize(name.size() - 4);
  if (folder == "frames") return name.ends_with(".png") && has_digit(name);
  if (folder != "particles") return false;  // checkpoints/: the Checkpointer clears its own
  return name == kCollectionFile ||
         (name.starts_with("frame_") && (name.ends_with(".csv") || name.ends_with(".vtp") || name.ends_with(".vtk")));
}

void remove_entry(const fs::path& p) {
  std::error_code ec;
  fs::remove(p, ec);
  if (ec) throw OutputError(p.string() + ": cannot remove the previous run's file: " + ec.message());
}

// Removes one previous-run entry: a file, or a folder's frame files and then the folder
// when that left it empty.
void remove_previous(const fs::path& entry) {
  std::error_code ec;
  if (!fs::is_directory(fs::symlink_status(entry, ec))) {
    remove_entry(entry);
    return;
  }
  const std::string folder = entry.filename().string();
  for (const fs::directory_entry& e : fs::directory_iterator(entry, ec))
    if (is_frame_file(folder, e.path().filename().string())) remove_entry(e.path());
  if (ec) throw OutputError(entry.string() + ": cannot list the previous run's files: " + ec.message());
  if (fs::is_empty(entry, ec)) fs::remove(entry, ec);
}

// --overwrite must not delete the file the run reads: a scene saved as DIR/summary.json
// or among DIR/frames/ would be gone before it was used.
void refuse_removing_input(const fs::path& entry, const std::string& input) {
  if (input.empty()) return;
  std::error_code ec;
  const fs::path in = fs::weakly_canonical(input, ec);
  if (ec) return;
  const fs::path e = fs::weakly_canonical(entry, ec);
  if (ec) return;
  const bool inside = fs::is_directory(fs::symlink_status(entry, ec)) && in.parent_path() == e &&
                      is_frame_file(entry.filename().string(), in.filename().string());
  if (in == e || inside)
    throw OutputError(
        entry.string() + ": --overwrite would delete the scene file " + input +
        " (it is a previous run's file there); move the scene out of the output directory or choose another -o");
}

void check_writable(const fs::path& dir) {
  // access() also answers EROFS for a read-only file system; root passes the permission
  // bits, so a later write can still fail (and is reported then).
  if (access(dir.c_str(), W_OK | X_OK) != 0)
    throw OutputError(dir.string() + ": output directory is not writable: " + std::strerror(errno));
}

}  // namespace

std::vector<std::string> previous_run_files(const std::string& scene_name) {
  std::vector<std::string> names = {"stats.csv",   "stats.csv.tmp",  "summary.json", "summary.json.tmp",
                                    "frames",      "particles",      "ffmpeg.log",   "checkpoints",
                                    "timing.json", "timing.json.tmp"};
  for (const render::VideoFormat f : {render::VideoFormat::mp4, render::VideoFormat::webm, render::VideoFormat::gif}) {
    render::VideoJob video;
    video.format = f;
    video.output = scene_name + "." + render::extension(f);
    names.push_back(video.output);
    names.push_back(render::temporary_output(video));
  }
  return names;
}

void prepare_output_directory(const fs::path& dir, bool overwrite, const std::string& scene_name,
                              const std::string& input) {
  std::error_code ec;
  if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
    throw OutputError(dir.string() + ": output directory exists and is not a directory");
  make_directory(dir);
  check_writable(dir);

  std::vector<std::string> found;
  for (const std::string& name : previous_run_files(scene_name))
    if (holds_run_output(dir / name)) found.push_back(name);
  if (found.empty()) return;
  if (!overwrite) {
    std::string list;
    for (const std::string& name : found)
      list += (list.empty() ? "" : ", ") + name + (fs::is_directory(dir / name, ec) ? "/" : "");
    throw OutputError(dir.string() + ": output directory holds a previous run (" + list +
                      "); pass --overwrite to replace it, or choose another directory with -o");
  }
  for (const std::string& name : found) refuse_removing_input(dir / name, input);
  for (const std::string& name : found) remove_previous(dir / name);
}

void refuse_previous_files(const fs::path& dir, const std::vector<std::string>& names, bool overwrite) {
  std::vector<std::string> found;
  std::error_code ec;
  for (const std::string& name : names)
    if (fs::exists(fs::symlink_status(dir / name, ec))) found.push_back(name);
  if (found.empty()) return;
  if (!overwrite) {
    std::string list;
    for (const std::string& name : found) list += (list.empty() ? "" : ", ") + name;
    throw OutputError(dir.string() + ": output directory holds a previous run (" + list +
                      "); pass --overwrite to replace it, or choose another directory with -o");
  }
  for (const std::string& name : found) remove_entry(dir / name);
}

}  // namespace sluice::app
