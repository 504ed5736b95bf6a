// Overrides of scene values (overrides.h), applied through nlohmann's JSON pointers.
#include "scene/overrides.h"

#include <algorithm>
#include <set>
#include <sstream>

#include "scene/json_reader.h"
#include "scene/scene.h"

namespace sluice::scene_detail {

namespace {

// A path "/a/b" as a JSON pointer; a '~' that escapes nothing ("~2", a '~' at the end)
// stands for itself, where json_pointer would refuse it.
json::json_pointer slash_path(const std::string& path) {
  std::string escaped;
  for (std::size_t i = 0; i < path.size(); ++i)
    escaped += path[i] == '~' && !(i + 1 < path.size() && (path[i + 1] == '0' || path[i + 1] == '1'))
                   ? "~0"
                   : std::string(1, path[i]);
  return json::json_pointer(escaped);
}

// A path "a.b" as a JSON pointer: one key per dot-separated part, an empty one after a
// trailing dot.
json::json_pointer dotted_path(const std::string& path) {
  json::json_pointer p;
  std::stringstream ss(path);
  for (std::string part; std::getline(ss, part, '.');) p /= part;
  if (path.back() == '.') p /= std::string();
  return p;
}

std::vector<std::string> tokens_of(json::json_pointer p) {
  std::vector<std::string> tokens;
  for (; !p.empty(); p.pop_back()) tokens.push_back(p.back());
  std::reverse(tokens.begin(), tokens.end());
  return tokens;
}

}  // namespace

void apply_override(json& root, const std::string& text, std::vector<std::string>& replaced) {
  auto fail = [&](const std::string& problem) -> void { throw SceneError("--set " + text + ": " + problem); };
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) fail("expected path=value, e.g. solver.tolerance=0.05 or /solver/type=wcsph");
  const std::string path = text.substr(0, eq), value_text = text.substr(eq + 1);

  if (path.empty() || path == "/") fail("empty path; expected e.g. solver.tolerance or /solver/tolerance");
  const std::vector<std::string> parts = tokens_of(path[0] == '/' ? slash_path(path) : dotted_path(path));
  for (const auto& p : parts)
    if (p.empty()) fail("empty path component; expected e.g. solver.tolerance or /solver/tolerance");

  // nlohmann keeps the last of duplicate keys; a scene file refuses them (parse_json), and
  // so does an override: {"type":"iisph","type":"wcsph"} must not run WCSPH quietly.
  std::vector<std::set<std::string>> open;  // the keys of each open object (arrays: none)
  std::string duplicate;
  auto track = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) open.emplace_back();
    if ((event == json::parse_event_t::object_end || event == json::parse_event_t::array_end) && !open.empty())
      open.pop_back();
    if (event == json::parse_event_t::key && !open.empty() && !open.back().insert(parsed.get<std::string>()).second &&
        duplicate.empty())
      duplicate = parsed.get<std::string>();
    return true;
  };
  json value = json::parse(value_text, track, /*allow_exceptions=*/false);
  if (value.is_discarded())
    value = value_text;  // not JSON: a plain string such as wcsph
  else if (!duplicate.empty())
    fail("duplicate key \"" + duplicate + "\" in the value; each key may appear only once");

  // Walk the path first: json_pointer would make a null into an array for a numeric key,
  // resize an array for any index and throw its own messages; here a null becomes an
  // object, an array takes an index up to its size (which appends), anything else stops.
  json::json_pointer walked;
  std::string shown;  // the path walked as given, for messages
  for (const auto& part : parts) {
    json& cur = root[walked];
    if (cur.is_null()) cur = json::object();
    if (cur.is_object()) {
      walked /= part;
    } else if (cur.is_array()) {
      const bool digits = std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
      if (!digits || part.size() > 9 || std::stoul(part) > cur.size())
        fail("\"" + part + "\" is not an index of the array at " + (shown.empty() ? "/" : shown) + " (size " +
             std::to_string(cur.size()) + "; the index equal to the size appends)");
      walked /= static_cast<std::size_t>(std::stoul(part));  // index == size appends a null, replaced below
    } else {
      fail("the path goes through " + (shown.empty() ? "/" : shown) + ", which is " + show(cur) +
           ", not an object or array");
    }
    shown.append("/").append(escape_key(part));
  }
  root[walked] = std::move(value);
  replaced.push_back(walked.to_string());
}

}  // namespace sluice::scene_detail
