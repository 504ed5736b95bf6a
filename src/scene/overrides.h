#pragma once
// Overrides of scene values from the command line (--set): "json/path=value" or
// "json.path=value", the value parsed as JSON, else taken as a string.
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace sluice::scene_detail {

// Applies one override to `root` (an object); appends to `replaced` the JSON pointer of
// the value it set. Throws SceneError "--set <text>: <problem>" for a bad path.
void apply_override(nlohmann::json& root, const std::string& text, std::vector<std::string>& replaced);

}  // namespace sluice::scene_detail
