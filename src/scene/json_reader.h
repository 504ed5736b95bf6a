#pragma once
// The validation framework of scene files: allowed ranges, the checks of single JSON
// values with path-precise messages (Context), the Reader of one JSON object's keys, and
// the parsing of the text (line:column of syntax errors, duplicate keys, nesting depth).
// A value error names the line:column of the value when it is in the file as written.
#include <limits>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "core/types.h"

namespace sluice::scene_detail {

using nlohmann::json;

inline constexpr double kInf = std::numeric_limits<double>::infinity();
inline constexpr double kMaxParticles = 2e7;  // guard against a typo in the spacing eating all memory

std::string num(double v);        // %.15g
std::string show(const json& v);  // compact, at most 60 characters
std::string join(const std::vector<std::string>& items);
std::string escape_key(const std::string& key);  // JSON pointer escaping of one key (RFC 6901)

// An allowed interval of a number, with its description for messages.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  std::string unit;

  static Range any(std::string unit = "") { return {-kInf, kInf, false, false, std::move(unit)}; }
  static Range positive(std::string unit = "") { return {0, kInf, true, false, std::move(unit)}; }
  static Range at_least(double lo, std::string unit = "") { return {lo, kInf, false, false, std::move(unit)}; }
  static Range open_closed(double lo, double hi, std::string unit = "") {
    return {lo, hi, true, false, std::move(unit)};
  }
  static Range closed(double lo, double hi, std::string unit = "") { return {lo, hi, false, false, std::move(unit)}; }
  static Range closed_open(double lo, double hi, std::string unit = "") {
    return {lo, hi, false, true, std::move(unit)};
  }

  bool contains(double v) const;
  std::string describe() const;
};

// The file name for messages and the checks of single JSON values. With the text, a
// failure names "file:line:column: /path: problem" where the value at /path is in the
// file as written (not set nor changed by an override), else "file: /path: problem".
struct Context {
  std::string file;
  const std::string* text = nullptr;    // the scene's JSON text; must outlive the Context
  std::vector<std::string> overridden;  // JSON pointers whose values an override set

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const;

  double number(const json& v, const std::string& path, const Range& r) const;
  int integer(const json& v, const std::string& path, int lo, int hi) const;
  bool boolean(const json& v, const std::string& path) const;
  std::string string(const json& v, const std::string& path) const;
  std::string choice(const json& v, const std::string& path, const std::vector<std::string>& allowed) const;
  Vec2 vec2(const json& v, const std::string& path) const;
  std::vector<Vec2> points(const json& v, const std::string& path, std::size_t min_count) const;
};

// Reads the keys of one JSON object: every read names an allowed key and records the
// value (or its default) in resolved(); finish() rejects the keys nobody asked for.
class Reader {
 public:
  Reader(const Context& ctx, const json* j, std::string path);

  std::string at(const std::string& key) const { return path_ + "/" + escape_key(key); }
  const std::string& path() const { return path_; }
  json& resolved() { return out_; }

  const json* find(const std::string& key);
  const json& require(const std::string& key, const std::string& what);

  double number(const std::string& key, double def, const Range& r);
  double number(const std::string& key, const Range& r);
  int integer(const std::string& key, int def, int lo, int hi);
  bool boolean(const std::string& key, bool def);
  std::string string(const std::string& key, const std::string& def);
  Vec2 vec2(const std::string& key, const Vec2& def);
  Vec2 vec2(const std::string& key);
  std::vector<Vec2> points(const std::string& key, std::size_t min_count);
  // A string from a fixed list; def == nullptr makes the key required.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const char* def);
  template <class E>
  E enumeration(const std::string& key, E def, const std::vector<std::pair<std::string, E>>& table) {
    std::vector<std::string> names;
    std::string def_name;
    for (const auto& [name, e] : table) {
      names.push_back(name);
      if (e == def) def_name = name;
    }
    const std::string x = choice(key, names, def_name.c_str());
    for (const auto& [name, e] : table)
      if (name == x) return e;
    return def;
  }

  void finish() const;

 private:
  const Context& ctx_;
  json j_ = json::object();
  std::string path_;
  std::vector<std::string> allowed_;
  json out_ = json::object();
};

// The scene's JSON text parsed; a syntax error, a NUL byte, a duplicate key or nesting
// deeper than 100 levels throws SceneError with the line:column.
json parse_json(const std::string& text, const Context& ctx);

}  // namespace sluice::scene_detail
