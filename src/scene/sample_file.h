#pragma once
// Boundary samples from a text file: one point per line, "x,y" or "x y".
#include <filesystem>
#include <string>
#include <vector>

#include "core/types.h"
#include "scene/json_reader.h"

namespace sluice::scene_detail {

// Empty lines, lines starting with '#' and a header "x,y" before the first sample are
// skipped. Errors name the scene's `json_path` and the file's line.
std::vector<Vec2> read_sample_file(const std::filesystem::path& path, const std::string& json_path, const Context& ctx);

}  // namespace sluice::scene_detail
