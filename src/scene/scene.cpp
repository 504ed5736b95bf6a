// Scene files: JSON reading, overrides, validation with path-precise messages, and the
// assembly of particles from the shapes (shapes.cpp). The format is documented in
// docs/scene_format.md; keep the two in sync.
#include "scene/scene.h"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <utility>

#include "core/shapes.h"

namespace sluice {

namespace {

using nlohmann::json;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kMaxParticles = 2e7;  // guard against a typo in the spacing eating all memory
// Frames of a run (duration x fps): frame numbers are 32-bit, and every frame is a file.
constexpr double kMaxFrames = 1e7;
// Steps of a run: the fewest it can take (duration / dt, or / dt_max when adaptive). A
// typo in dt would otherwise run for days and fill the disk with stats.csv rows.
constexpr double kMaxSteps = 1e7;
// Nesting of JSON arrays and objects: a scene needs 7 levels; a hostile file of a
// million '[' would overflow the stack where values are copied or printed.
constexpr std::size_t kMaxDepth = 100;

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.15g", v);
  return buf;
}

std::string show(const json& v) {
  // replace: an override's string value need not be UTF-8 (the parser's are)
  std::string s = v.dump(-1, ' ', false, json::error_handler_t::replace);
  return s.size() > 60 ? s.substr(0, 57) + "..." : s;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const auto& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// JSON pointer escaping of one key (RFC 6901).
std::string escape_key(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// An allowed interval of a number, with its description for messages.
struct Range {
  double lo = -kInf, hi = kInf;
  bool lo_open = false, hi_open = false;
  std::string unit;

  static Range any(std::string unit = "") { return {-kInf, kInf, false, false, std::move(unit)}; }
  static Range positive(std::string unit = "") { return {0, kInf, true, false, std::move(unit)}; }
  static Range at_least(double lo, std::string unit = "") { return {lo, kInf, false, false, std::move(unit)}; }
  static Range open_closed(double lo, double hi, std::string unit = "") { return {lo, hi, true, false, std::move(unit)}; }

  bool contains(double v) const {
    return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
  }
  std::string describe() const {
    std::string s;
    if (hi == kInf && lo == -kInf) s = "must be a finite number";
    else if (hi == kInf) s = std::string("must be ") + (lo_open ? "> " : ">= ") + num(lo);
    else s = "must be in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
    return unit.empty() ? s : s + " " + unit;
  }
};

// The file name for messages and the checks of single JSON values.
struct Context {
  std::string file;

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw SceneError(file + ": " + (path.empty() ? "/" : path) + ": " + problem);
  }

  double number(const json& v, const std::string& path, const Range& r) const {
    if (!v.is_number()) fail(path, "expected a number, got " + show(v));
    const double x = v.get<double>();
    if (!r.contains(x)) fail(path, "value " + show(v) + " is out of range; " + r.describe());
    return x;
  }
  int integer(const json& v, const std::string& path, int lo, int hi) const {
    if (!v.is_number_integer()) fail(path, "expected an integer, got " + show(v));
    const long double x = v.is_number_unsigned() ? static_cast<long double>(v.get<unsigned long long>())
                                                 : static_cast<long double>(v.get<long long>());
    if (x < lo || x > hi)
      fail(path, "value " + show(v) + " is out of range; must be an integer in [" + std::to_string(lo) + ", " +
                     std::to_string(hi) + "]");
    return static_cast<int>(x);
  }
  bool boolean(const json& v, const std::string& path) const {
    if (!v.is_boolean()) fail(path, "expected true or false, got " + show(v));
    return v.get<bool>();
  }
  std::string string(const json& v, const std::string& path) const {
    if (!v.is_string() || v.get<std::string>().empty()) fail(path, "expected a non-empty string, got " + show(v));
    return v.get<std::string>();
  }
  std::string choice(const json& v, const std::string& path, const std::vector<std::string>& allowed) const {
    if (!v.is_string() || std::find(allowed.begin(), allowed.end(), v.get<std::string>()) == allowed.end())
      fail(path, "invalid value " + show(v) + "; must be one of: " + join(allowed));
    return v.get<std::string>();
  }
  Vec2 vec2(const json& v, const std::string& path) const {
    if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() ||
        !std::isfinite(v[0].get<double>()) || !std::isfinite(v[1].get<double>()))
      fail(path, "expected an array of 2 numbers, got " + show(v));
    return {v[0].get<double>(), v[1].get<double>()};
  }
  std::vector<Vec2> points(const json& v, const std::string& path, std::size_t min_count) const {
    if (!v.is_array() || v.size() < min_count)
      fail(path, "expected an array of at least " + std::to_string(min_count) + " points [x, y], got " + show(v));
    std::vector<Vec2> out;
    for (std::size_t i = 0; i < v.size(); ++i) out.push_back(vec2(v[i], path + "/" + std::to_string(i)));
    return out;
  }
};

// Reads the keys of one JSON object: every read names an allowed key and records the
// value (or its default) in resolved(); finish() rejects the keys nobody asked for.
class Reader {
 public:
  Reader(const Context& ctx, const json* j, std::string path) : ctx_(ctx), path_(std::move(path)) {
    if (j && !j->is_object()) ctx.fail(path_, "expected an object, got " + show(*j));
    if (j) j_ = *j;
  }

  std::string at(const std::string& key) const { return path_ + "/" + escape_key(key); }
  const std::string& path() const { return path_; }
  json& resolved() { return out_; }

  const json* find(const std::string& key) {
    allowed_.push_back(key);
    const auto it = j_.find(key);
    return it == j_.end() ? nullptr : &*it;
  }
  const json& require(const std::string& key, const std::string& what) {
    if (const json* v = find(key)) return *v;
    ctx_.fail(at(key), "missing required key; " + what);
  }

  double number(const std::string& key, double def, const Range& r) {
    const json* v = find(key);
    const double x = v ? ctx_.number(*v, at(key), r) : def;
    out_[key] = x;
    return x;
  }
  double number(const std::string& key, const Range& r) {
    const double x = ctx_.number(require(key, "a number that " + r.describe()), at(key), r);
    out_[key] = x;
    return x;
  }
  int integer(const std::string& key, int def, int lo, int hi) {
    const json* v = find(key);
    const int x = v ? ctx_.integer(*v, at(key), lo, hi) : def;
    out_[key] = x;
    return x;
  }
  bool boolean(const std::string& key, bool def) {
    const json* v = find(key);
    const bool x = v ? ctx_.boolean(*v, at(key)) : def;
    out_[key] = x;
    return x;
  }
  std::string string(const std::string& key, const std::string& def) {
    const json* v = find(key);
    std::string x = v ? ctx_.string(*v, at(key)) : def;
    out_[key] = x;
    return x;
  }
  Vec2 vec2(const std::string& key, const Vec2& def) {
    const json* v = find(key);
    const Vec2 x = v ? ctx_.vec2(*v, at(key)) : def;
    out_[key] = {x.x(), x.y()};
    return x;
  }
  Vec2 vec2(const std::string& key) {
    const Vec2 x = ctx_.vec2(require(key, "an array of 2 numbers [x, y]"), at(key));
    out_[key] = {x.x(), x.y()};
    return x;
  }
  std::vector<Vec2> points(const std::string& key, std::size_t min_count) {
    const json& v = require(key, "an array of at least " + std::to_string(min_count) + " points [x, y]");
    auto pts = ctx_.points(v, at(key), min_count);
    out_[key] = v;
    return pts;
  }
  // A string from a fixed list; def == nullptr makes the key required.
  std::string choice(const std::string& key, const std::vector<std::string>& allowed, const char* def) {
    const json* v = def ? find(key) : &require(key, "must be one of: " + join(allowed));
    std::string x = v ? ctx_.choice(*v, at(key), allowed) : def;
    out_[key] = x;
    return x;
  }
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

  void finish() const {
    for (const auto& item : j_.items())
      if (std::find(allowed_.begin(), allowed_.end(), item.key()) == allowed_.end())
        ctx_.fail(at(item.key()), "unknown key; allowed keys: " + join(allowed_));
  }

 private:
  const Context& ctx_;
  json j_ = json::object();
  std::string path_;
  std::vector<std::string> allowed_;
  json out_ = json::object();
};

// --- parsing the text -----------------------------------------------------------------------

// "line:column" (1-based) of byte `pos` of `text`.
std::string line_column(const std::string& text, std::size_t pos) {
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
  const std::size_t nl = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
  return std::to_string(line) + ":" + std::to_string(nl == std::string::npos ? pos + 1 : pos - nl);
}

json parse_json(const std::string& text, const Context& ctx) {
  // nlohmann keeps the last of duplicate keys; the callback turns that into an error.
  struct Frame {
    bool array = false;
    long index = 0;
    std::string path, key;
    std::set<std::string> keys;
  };
  std::vector<Frame> frames;
  std::string duplicate;
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    auto child_path = [&]() {
      if (frames.empty()) return std::string();
      const Frame& f = frames.back();
      return f.path + "/" + (f.array ? std::to_string(f.index) : escape_key(f.key));
    };
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (frames.size() >= kMaxDepth)
          ctx.fail(child_path(), "arrays and objects are nested more than " + std::to_string(kMaxDepth) +
                                     " levels deep; a scene needs fewer than 10");
        frames.push_back({event == json::parse_event_t::array_start, 0, child_path(), "", {}});
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames.pop_back();
        if (!frames.empty() && frames.back().array) ++frames.back().index;
        break;
      case json::parse_event_t::key:
        frames.back().key = parsed.get<std::string>();
        if (!frames.back().keys.insert(frames.back().key).second && duplicate.empty()) duplicate = child_path();
        break;
      case json::parse_event_t::value:
        if (!frames.empty() && frames.back().array) ++frames.back().index;
        break;
    }
    return true;
  };
  // A NUL ends what some readers see of the file; nothing may hide after one.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw SceneError(ctx.file + ":" + line_column(text, nul) + ": a NUL byte; a scene file is JSON text");
  json j;
  try {
    j = json::parse(text, callback);
  } catch (const json::parse_error& e) {
    // e.byte counts the characters read; the last one read is where the error is.
    std::size_t pos = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    // An unexpected string is reported at its closing quote; point at its opening quote.
    if (pos < text.size() && text[pos] == '"' && std::string(e.what()).find("unexpected string literal") != std::string::npos)
      for (std::size_t q = pos; q-- > 0;)
        if (text[q] == '"') {
          std::size_t slashes = 0;
          while (q > slashes && text[q - 1 - slashes] == '\\') ++slashes;
          if (slashes % 2 == 0) {
            pos = q;
            break;
          }
        }
    const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
    const std::size_t nl = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
    const std::size_t column = nl == std::string::npos ? pos + 1 : pos - nl;
    std::string detail = e.what();
    std::size_t p = detail.find("column ");
    p = p == std::string::npos ? detail.find("] ") : detail.find(": ", p);
    if (p != std::string::npos) detail = detail.substr(p + 2);
    throw SceneError(ctx.file + ":" + std::to_string(line) + ":" + std::to_string(column) + ": JSON parse error: " + detail);
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e999'" carries no position: find the number in the text.
    const std::string what = e.what();
    const std::size_t q1 = what.find('\''), q2 = what.rfind('\'');
    const std::size_t at = q1 != std::string::npos && q2 > q1 ? text.find(what.substr(q1 + 1, q2 - q1 - 1)) : std::string::npos;
    const std::string detail = what.substr(what.find("] ") == std::string::npos ? 0 : what.find("] ") + 2);
    throw SceneError(ctx.file + (at == std::string::npos ? "" : ":" + line_column(text, at)) + ": JSON parse error: " +
                     detail + " (numbers must be within the range of double, about 1.8e308)");
  } catch (const json::exception& e) {
    throw SceneError(ctx.file + ": JSON parse error: " + e.what());
  }
  if (!duplicate.empty()) ctx.fail(duplicate, "duplicate key; each key may appear only once");
  return j;
}

// --- overrides ----------------------------------------------------------------------------

void apply_override(json& root, const std::string& text) {
  auto fail = [&](const std::string& problem) -> void { throw SceneError("--set " + text + ": " + problem); };
  const std::size_t eq = text.find('=');
  if (eq == std::string::npos) fail("expected path=value, e.g. solver.tolerance=0.05 or /solver/type=wcsph");
  const std::string path = text.substr(0, eq), value_text = text.substr(eq + 1);

  std::vector<std::string> parts;
  if (path.empty() || path == "/") fail("empty path; expected e.g. solver.tolerance or /solver/tolerance");
  if (path[0] == '/') {
    std::stringstream ss(path.substr(1));
    for (std::string part; std::getline(ss, part, '/');) {
      std::string key;
      for (std::size_t i = 0; i < part.size(); ++i)
        if (part[i] == '~' && i + 1 < part.size() && (part[i + 1] == '0' || part[i + 1] == '1')) key += part[++i] == '0' ? '~' : '/';
        else key += part[i];
      parts.push_back(key);
    }
    if (path.back() == '/') parts.push_back("");
  } else {
    std::stringstream ss(path);
    for (std::string part; std::getline(ss, part, '.');) parts.push_back(part);
    if (path.back() == '.') parts.push_back("");
  }
  for (const auto& p : parts)
    if (p.empty()) fail("empty path component; expected e.g. solver.tolerance or /solver/tolerance");

  json value = json::parse(value_text, nullptr, /*allow_exceptions=*/false);
  if (value.is_discarded()) value = value_text;  // not JSON: a plain string such as wcsph

  json* cur = &root;
  std::string walked;
  for (const auto& part : parts) {
    if (cur->is_null()) *cur = json::object();
    if (cur->is_object()) {
      cur = &(*cur)[part];
    } else if (cur->is_array()) {
      const bool digits = std::all_of(part.begin(), part.end(), [](char c) { return c >= '0' && c <= '9'; });
      if (!digits || part.size() > 9 || std::stoul(part) > cur->size())
        fail("\"" + part + "\" is not an index of the array at " + (walked.empty() ? "/" : walked) + " (size " +
             std::to_string(cur->size()) + "; the index equal to the size appends)");
      cur = &(*cur)[std::stoul(part)];  // index == size appends a null, replaced below
    } else {
      fail("the path goes through " + (walked.empty() ? "/" : walked) + ", which is " + show(*cur) +
           ", not an object or array");
    }
    walked += "/" + escape_key(part);
  }
  *cur = std::move(value);
}

// --- sections -----------------------------------------------------------------------------

SolverSettings read_solver(Reader& r, const Context& ctx) {
  SolverSettings s;
  s.type = r.enumeration("type", s.type, {{"iisph", SolverType::IISPH}, {"wcsph", SolverType::WCSPH}});
  s.rest_density = r.number("rest_density", s.rest_density, Range::positive("[kg/m^2]"));
  s.gravity = r.vec2("gravity", s.gravity);
  s.viscosity = r.number("viscosity", s.viscosity, Range::at_least(0, "[m^2/s]"));
  s.artificial_viscosity = r.number("artificial_viscosity", s.artificial_viscosity, Range::at_least(0, "(alpha)"));
  s.sound_speed = r.number("sound_speed", s.sound_speed, Range::at_least(0, "[m/s]"));
  s.gradient_correction = r.boolean("gradient_correction", s.gradient_correction);
  s.tolerance_percent = r.number("tolerance", s.tolerance_percent, Range::positive("(percent)"));
  s.omega = r.number("omega", s.omega, Range::open_closed(0, 1));
  s.min_iterations = r.integer("min_iterations", s.min_iterations, 1, 10000);
  s.max_iterations = r.integer("max_iterations", s.max_iterations, 1, 10000);
  if (s.min_iterations > s.max_iterations)
    ctx.fail(r.at("min_iterations"), "min_iterations " + std::to_string(s.min_iterations) + " is larger than max_iterations " +
                                         std::to_string(s.max_iterations) + "; need 1 <= min_iterations <= max_iterations <= 10000");
  s.pressure_init = r.enumeration("pressure_init", s.pressure_init,
                                  {{"warm", PressureInit::WarmStart}, {"thesis", PressureInit::Thesis}});
  s.stiffness = r.number("stiffness", s.stiffness, Range::positive("[Pa*m]"));
  s.boundary_pressure = r.enumeration("boundary_pressure", s.boundary_pressure,
                                      {{"solved", BoundaryPressure::Solved},
                                       {"extrapolation", BoundaryPressure::Extrapolation},
                                       {"mirroring", BoundaryPressure::Mirroring},
                                       {"zero", BoundaryPressure::Zero}});
  s.gamma1 = r.number("gamma1", s.gamma1, Range::positive());
  s.gamma2 = r.number("gamma2", s.gamma2, Range::at_least(0));
  s.gamma3 = r.number("gamma3", s.gamma3, Range::at_least(0));
  s.boundary_diagonal = r.boolean("boundary_diagonal", s.boundary_diagonal);
  r.finish();
  return s;
}

// The run must end within kMaxSteps steps, and its smallest step must move the clock:
// t + dt == t in double precision would repeat the same time forever.
void check_step_count(Reader& r, const Context& ctx, const TimeSettings& t, bool fixed) {
  const double step = fixed ? t.dt : t.dt_max;
  const std::string key = fixed ? "dt" : "dt_max";
  const double steps = (t.settle + t.duration) / step;
  if (!(steps <= kMaxSteps))
    ctx.fail(r.at(key), key + " " + num(step) + " s for " + num(t.settle + t.duration) + " s (settle + duration) makes at least " +
                            num(std::ceil(steps)) + " steps; the limit is " + num(kMaxSteps) + " (raise " + key +
                            " or shorten the run)");
  const double smallest = fixed ? t.dt : t.dt_min;
  const double end = t.settle + t.duration;
  if (!(end + smallest > end))
    ctx.fail(r.at(fixed ? "dt" : "dt_min"), "value " + num(smallest) + " s does not advance the time at t = " + num(end) +
                                              " s in double precision; must be > " + num(end * 0x1p-52) + " [s]");
}

TimeSettings read_time(Reader& r, const Context& ctx) {
  TimeSettings t;
  t.duration = r.number("duration", t.duration, Range::positive("[s]"));
  t.fps = r.number("fps", t.fps, Range::positive("[frames/s]"));
  if (!(t.duration * t.fps <= kMaxFrames))
    ctx.fail(r.path(), "duration " + num(t.duration) + " s at fps " + num(t.fps) + " makes " + num(std::ceil(t.duration * t.fps)) +
                           " frames; the limit is " + num(kMaxFrames) + " (shorten duration or lower fps)");
  const json* dt = r.find("dt");
  const json* cfl = r.find("cfl");
  const bool fixed = dt && !dt->is_null(), has_cfl = cfl && !cfl->is_null();
  if (fixed && has_cfl)
    ctx.fail(r.path(), "both dt and cfl are given; remove \"cfl\" for a fixed time step, or \"dt\" for the adaptive CFL step (an override can remove a key with null, e.g. time.dt=null)");
  if (fixed) t.dt = ctx.number(*dt, r.at("dt"), Range::positive("[s]"));
  if (has_cfl) t.cfl = ctx.number(*cfl, r.at("cfl"), Range::open_closed(0, 2));
  r.resolved()["dt"] = fixed ? json(t.dt) : json(nullptr);
  r.resolved()["cfl"] = fixed ? json(nullptr) : json(t.cfl);
  t.dt_max = r.number("dt_max", t.dt_max, Range::positive("[s]"));
  t.dt_min = r.number("dt_min", t.dt_min, Range::positive("[s]"));
  t.settle = r.number("settle", t.settle, Range::at_least(0, "[s]"));
  if (t.dt_min > t.dt_max)
    ctx.fail(r.at("dt_min"), "dt_min " + num(t.dt_min) + " is larger than dt_max " + num(t.dt_max) + "; need 0 < dt_min <= dt_max");
  if (t.duration < kMinDuration)
    ctx.fail(r.at("duration"), "value " + num(t.duration) + " is out of range; must be >= " + num(kMinDuration) +
                                   " [s] (shorter runs are below the resolution of the time steps)");
  check_step_count(r, ctx, t, fixed);
  r.finish();
  return t;
}

StabilityLimits read_stability(Reader& r) {
  StabilityLimits s;
  s.max_error_percent = r.number("max_error_percent", s.max_error_percent, Range::positive("(percent)"));
  s.bounds_margin = r.number("bounds_margin", s.bounds_margin, Range::positive("(scene sizes)"));
  s.max_leaked_percent = r.number("max_leaked_percent", s.max_leaked_percent, Range{0, 100, false, false, "(percent of the fluid particles)"});
  r.finish();
  return s;
}

OutputSettings read_output(Reader& r, const Context& ctx, const std::string& name) {
  OutputSettings o;
  o.directory = r.string("directory", "renders/" + name);
  if (const json* e = r.find("export")) {
    if (!e->is_array()) ctx.fail(r.at("export"), "expected an array of formats, got " + show(*e) + "; allowed formats: csv, vtk");
    for (std::size_t i = 0; i < e->size(); ++i) {
      const std::string path = r.at("export") + "/" + std::to_string(i);
      std::string f = ctx.choice((*e)[i], path, {"csv", "vtk"});
      if (std::find(o.export_formats.begin(), o.export_formats.end(), f) != o.export_formats.end())
        ctx.fail(path, "duplicate format \"" + f + "\"; list each of csv, vtk at most once");
      o.export_formats.push_back(f);
    }
  }
  r.resolved()["export"] = o.export_formats;
  r.finish();
  return o;
}

RenderSettings read_render(Reader& r, const Context& ctx) {
  RenderSettings s;
  if (const json* res = r.find("resolution")) {
    const std::string path = r.at("resolution");
    if (!res->is_array() || res->size() != 2) ctx.fail(path, "expected [width, height] in pixels, got " + show(*res));
    s.width = ctx.integer((*res)[0], path + "/0", 2, 16384);
    s.height = ctx.integer((*res)[1], path + "/1", 2, 16384);
  }
  r.resolved()["resolution"] = {s.width, s.height};
  s.color_by = r.choice("color_by", {"cfl", "speed", "pressure", "density_error"}, "cfl");
  s.colormap = r.choice("colormap", {"spectrum", "viridis", "turbo"}, "spectrum");
  const json* range = r.find("range");
  if (range && !range->is_null()) {
    const Vec2 lohi = ctx.vec2(*range, r.at("range"));
    // hi - lo must be finite too: the colour of a value is (v - lo) / (hi - lo).
    if (!(lohi.y() > lohi.x()) || !std::isfinite(lohi.y() - lohi.x()))
      ctx.fail(r.at("range"), "range " + show(*range) +
                                  " must be [lo, hi] with lo < hi and hi - lo finite (in the units of color_by), or null for automatic");
    s.fixed_range = true;
    s.range_lo = lohi.x();
    s.range_hi = lohi.y();
  }
  r.resolved()["range"] = s.fixed_range ? json{s.range_lo, s.range_hi} : json(nullptr);
  const json* view = r.find("view");
  if (view && !view->is_null()) {
    Reader v(ctx, view, r.at("view"));
    s.view_min = v.vec2("min");
    s.view_max = v.vec2("max");
    v.finish();
    if (!(s.view_max.x() > s.view_min.x() && s.view_max.y() > s.view_min.y()))
      ctx.fail(v.at("max"), "max [" + num(s.view_max.x()) + ", " + num(s.view_max.y()) + "] must be above min [" +
                                num(s.view_min.x()) + ", " + num(s.view_min.y()) + "] in x and y");
    s.fixed_view = true;
    r.resolved()["view"] = v.resolved();
  } else {
    r.resolved()["view"] = nullptr;
  }
  r.finish();
  return s;
}

shapes::FluidShape read_fluid_block(Reader& r, const Context& ctx) {
  shapes::FluidShape f;
  const std::string shape = r.choice("shape", {"rectangle", "ellipse", "polygon"}, nullptr);
  if (shape == "rectangle") {
    f.kind = shapes::FluidShape::Kind::Rectangle;
    f.min = r.vec2("min");
    f.max = r.vec2("max");
    if (f.max.x() < f.min.x() || f.max.y() < f.min.y())
      ctx.fail(r.at("max"), "max [" + num(f.max.x()) + ", " + num(f.max.y()) + "] is below min [" + num(f.min.x()) + ", " +
                                num(f.min.y()) + "]; need min <= max in x and y");
  } else if (shape == "ellipse") {
    f.kind = shapes::FluidShape::Kind::Ellipse;
    f.center = r.vec2("center");
    f.radii = r.vec2("radii");
    if (f.radii.minCoeff() < 0) ctx.fail(r.at("radii"), "radii must be >= 0 [m], got " + show(r.resolved()["radii"]));
  } else {
    f.kind = shapes::FluidShape::Kind::Polygon;
    f.points = r.points("points", 3);
    // Points on one line hold no fluid (the no-fluid error follows); such edges fold back
    // over each other, which is not what the self-intersection message is about.
    const bool on_a_line = std::all_of(f.points.begin(), f.points.end(), [&](const Vec2& p) {
      const Vec2 a = f.points[1] - f.points[0], b = p - f.points[0];
      return a.x() * b.y() - a.y() * b.x() == 0;
    });
    if (on_a_line) {
    } else if (const int seg = shapes::self_intersection(f.points, true); seg >= 0)
      ctx.fail(r.at("points"), "the polygon intersects itself (edge " + std::to_string(seg) +
                                   " crosses another edge); the points must form a simple polygon");
  }
  f.velocity = r.vec2("velocity", Vec2::Zero());
  r.finish();
  return f;
}

// One entry of a per-segment spacing array: a number (uniform), or a pair [s_start, s_end]
// for a spacing that varies linearly from the segment's first vertex to its second (dense
// samples at a tip, sparse ones along a long flat wall).
shapes::SegmentSpacing read_spacing_entry(const json& v, const std::string& path, const Context& ctx) {
  const Range range = Range::positive("[m]");
  if (v.is_number()) {
    const double s = ctx.number(v, path, range);
    return {s, s};
  }
  if (!v.is_array() || v.size() != 2)
    ctx.fail(path, "expected a spacing > 0 [m] or a pair [s_start, s_end] of spacings > 0 [m] (graded from the segment's "
                   "first point to its second), got " + show(v));
  return {ctx.number(v[0], path + "/0", range), ctx.number(v[1], path + "/1", range)};
}

// Per-segment spacing: one number for all, or an array with one entry per segment, each a
// number or a graded pair [s_start, s_end].
std::vector<shapes::SegmentSpacing> read_segment_spacing(Reader& r, const Context& ctx, std::size_t segments, double def,
                                                         bool allow_array, const std::string& order) {
  const json* v = r.find("spacing");
  if (!v) {
    r.resolved()["spacing"] = def;
    return std::vector<shapes::SegmentSpacing>(segments, {def, def});
  }
  r.resolved()["spacing"] = *v;
  if (v->is_array() && allow_array) {
    if (v->size() != segments) {
      // Two numbers for one segment are most likely a graded pair without its brackets.
      const std::string hint = segments == 1 && v->size() == 2 ? "; a graded spacing is a pair inside the array: [[s_start, s_end]]"
                                                                : "; each entry is a number or a pair [s_start, s_end]";
      ctx.fail(r.at("spacing"), "expected " + std::to_string(segments) + " spacings (one per segment" + order + "), got " +
                                    std::to_string(v->size()) + hint);
    }
    std::vector<shapes::SegmentSpacing> out;
    for (std::size_t i = 0; i < segments; ++i)
      out.push_back(read_spacing_entry((*v)[i], r.at("spacing") + "/" + std::to_string(i), ctx));
    return out;
  }
  if (!v->is_number())
    ctx.fail(r.at("spacing"), allow_array ? "expected a number or an array with one entry per segment (a number or a pair "
                                            "[s_start, s_end]), got " + show(*v)
                                          : "expected a number, got " + show(*v) +
                                                "; circles and ellipses are sampled uniformly in arc length, with one spacing");
  const double s = ctx.number(*v, r.at("spacing"), Range::positive("[m]"));
  return std::vector<shapes::SegmentSpacing>(segments, {s, s});
}

// A path given in the scene, relative to the scene file's directory (absolute ones as they are).
std::filesystem::path relative_to_scene(const std::string& scene_file, const std::string& path) {
  const std::filesystem::path p(path);
  return (p.is_absolute() ? p : std::filesystem::path(scene_file).parent_path() / p).lexically_normal();
}

std::string trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r\n"), b = s.find_last_not_of(" \t\r\n");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// The fields of one line of a sample file: comma-separated if it has a comma, else
// separated by blanks.
std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> out;
  if (line.find(',') != std::string::npos) {
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');) out.push_back(trim(f));
    if (line.back() == ',') out.emplace_back();  // getline drops a trailing empty field
  } else {
    std::stringstream ss(line);
    for (std::string f; ss >> f;) out.push_back(f);
  }
  return out;
}

// A whole field as a number (from_chars: the same in every locale; it takes no '+', so
// one is skipped). A number too large for a double reads as infinite, so that the caller
// reports it as not finite; one too small reads as what strtod makes of it (0 or subnormal).
bool parse_number(const std::string& field, double& x) {
  const bool plus = field.size() > 1 && field[0] == '+' && field[1] != '-' && field[1] != '+';
  const char* first = field.data() + (plus ? 1 : 0);
  const char* last = field.data() + field.size();
  const auto [end, ec] = std::from_chars(first, last, x);
  if (ec == std::errc::invalid_argument || end != last) return false;
  if (ec == std::errc::result_out_of_range) x = std::strtod(std::string(first, last).c_str(), nullptr);
  return true;
}

// A first line "x,y" or "x y" (either case) names the columns.
bool is_header(const std::vector<std::string>& fields) {
  auto is = [](const std::string& f, char c) { return f.size() == 1 && std::tolower(static_cast<unsigned char>(f[0])) == c; };
  return fields.size() == 2 && is(fields[0], 'x') && is(fields[1], 'y');
}

// Samples from a text file: one point per line, "x,y" or "x y". Empty lines, lines
// starting with '#' and a header "x,y" before the first sample are skipped.
std::vector<Vec2> read_sample_file(const std::filesystem::path& path, const std::string& json_path, const Context& ctx) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  // A device or folder opens but is not a points file: say what it is, not "cannot open".
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    ctx.fail(json_path, "\"" + path.string() + "\" is not a regular file; expected a text file of points x,y");
  std::ifstream in(path, std::ios::binary);
  if (!in)
    ctx.fail(json_path, "cannot open \"" + path.string() + "\": " + std::strerror(errno) +
                            " (a relative file is looked up in the scene file's directory)");
  std::vector<Vec2> out;
  bool first = true;
  std::string line;
  for (long number = 1; std::getline(in, line); ++number) {
    if (number == 1 && line.starts_with("\xEF\xBB\xBF")) line.erase(0, 3);  // a UTF-8 byte order mark
    const std::string text = trim(line);
    if (text.empty() || text.front() == '#') continue;
    const auto fields = split_fields(text);
    const bool header = first && is_header(fields);
    first = false;
    if (header) continue;
    const std::string where = path.string() + ":" + std::to_string(number);
    const std::string shown = text.size() > 60 ? text.substr(0, 57) + "..." : text;
    double x = 0, y = 0;
    if (fields.size() != 2 || !parse_number(fields[0], x) || !parse_number(fields[1], y))
      ctx.fail(json_path, where + ": expected two numbers x,y, got '" + shown + "'");
    if (!std::isfinite(x) || !std::isfinite(y))
      ctx.fail(json_path, where + ": '" + shown + "' is not a finite point; coordinates must be finite numbers [m]");
    out.emplace_back(x, y);
    if (static_cast<double>(out.size()) > kMaxParticles)
      ctx.fail(json_path, where + ": more than " + num(kMaxParticles) + " samples; the limit is " + num(kMaxParticles));
  }
  if (out.empty())
    ctx.fail(json_path, path.string() + ": no samples (only empty lines, comments or a header); give at least one line x,y");
  return out;
}

// "points": boundary samples used exactly as given, from an inline list or a file. They
// have no curve, no layers and no solid side; fluid lattice points within half a spacing
// of a sample are removed like for any other boundary.
shapes::BoundaryShape read_point_samples(Reader& r, const Context& ctx) {
  shapes::BoundaryShape b;
  b.kind = shapes::BoundaryShape::Kind::Points;
  const json* file = r.find("file");
  const json* samples = r.find("samples");
  r.finish();  // a misspelt key before any file is read
  if ((file != nullptr) == (samples != nullptr))
    ctx.fail(r.path(), std::string(file ? "both \"file\" and" : "neither \"file\" nor") + " \"samples\" given; give exactly one: " +
                           "\"file\" (a text file of x,y lines, relative to the scene file) or \"samples\" (an array of [x, y])");
  if (samples) {
    if (samples->is_array() && samples->empty()) ctx.fail(r.at("samples"), "the list is empty; give at least one sample [x, y]");
    b.points = ctx.points(*samples, r.at("samples"), 1);
    r.resolved()["samples"] = *samples;
  } else {
    const std::filesystem::path path = relative_to_scene(ctx.file, ctx.string(*file, r.at("file")));
    b.points = read_sample_file(path, r.at("file"), ctx);
    // Absolute, so that the resolved scene (written next to the outputs) still finds it.
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    r.resolved()["file"] = (ec ? path : absolute.lexically_normal()).string();
  }
  return b;
}

// One scripted motion component (see motion.h); the object at rest is its shape as given.
MotionComponent read_motion_component(Reader& r, const Context& ctx) {
  MotionComponent m;
  const std::string type = r.choice("type", {"rotation", "translation", "oscillation", "keyframes"}, nullptr);
  if (type != "keyframes") m.start = r.number("start", 0.0, Range::at_least(0, "[s]"));
  if (type == "rotation") {
    m.kind = MotionComponent::Kind::Rotation;
    m.pivot = r.vec2("pivot");
    m.omega = r.number("angular_velocity", Range::any("[rad/s], > 0 counter-clockwise"));
    m.ramp = r.number("ramp", 0.0, Range::at_least(0, "[s]"));
  } else if (type == "translation") {
    m.kind = MotionComponent::Kind::Translation;
    m.velocity = r.vec2("velocity");
    const json* end = r.find("end");
    m.end = kInf;
    if (end && !end->is_null()) {
      m.end = ctx.number(*end, r.at("end"), Range::at_least(0, "[s]"));
      if (m.end < m.start)
        ctx.fail(r.at("end"), "end " + num(m.end) + " s is before start " + num(m.start) + " s; need start <= end, or null for no end");
    }
    r.resolved()["end"] = std::isfinite(m.end) ? json(m.end) : json(nullptr);
  } else if (type == "oscillation") {
    m.kind = MotionComponent::Kind::Oscillation;
    m.period = r.number("period", Range::positive("[s]"));
    m.phase = r.number("phase", 0.0, Range::any("[rad]"));
    const json* amp = r.find("amplitude");
    const json* ang = r.find("angular_amplitude");
    if ((amp != nullptr) == (ang != nullptr))
      ctx.fail(r.path(), "give exactly one of \"amplitude\" (a shift along direction, [m]) and \"angular_amplitude\" (a rotation about pivot, [rad])");
    if (amp) {
      m.amplitude = ctx.number(*amp, r.at("amplitude"), Range::at_least(0, "[m]"));
      r.resolved()["amplitude"] = m.amplitude;
      const json* dir = r.find("direction");
      const json* angle = r.find("angle");
      if (dir && angle) ctx.fail(r.path(), "give at most one of \"direction\" ([x, y]) and \"angle\" ([rad] from the x axis)");
      if (angle) {
        const double a = ctx.number(*angle, r.at("angle"), Range::any("[rad]"));
        m.direction = {std::cos(a), std::sin(a)};
      } else if (dir) {
        m.direction = ctx.vec2(*dir, r.at("direction"));
        if (m.direction.norm() == 0) ctx.fail(r.at("direction"), "the direction [0, 0] has no length; give a non-zero vector");
        m.direction.normalize();
      }
      r.resolved()["direction"] = {m.direction.x(), m.direction.y()};
    } else {
      m.angular_amplitude = ctx.number(*ang, r.at("angular_amplitude"), Range::any("[rad]"));
      r.resolved()["angular_amplitude"] = m.angular_amplitude;
      m.pivot = r.vec2("pivot");
    }
  } else {
    m.kind = MotionComponent::Kind::Keyframes;
    m.smooth = r.choice("interpolation", {"linear", "smooth"}, "linear") == "smooth";
    m.pivot = r.vec2("pivot", Vec2::Zero());
    const json& keys = r.require("keys", "an array of at least 2 keys {\"time\", \"offset\", \"angle\"}");
    if (!keys.is_array() || keys.size() < 2)
      ctx.fail(r.at("keys"), "expected an array of at least 2 keys {\"time\", \"offset\", \"angle\"}, got " + show(keys));
    json resolved_keys = json::array();
    for (std::size_t i = 0; i < keys.size(); ++i) {
      Reader k(ctx, &keys[i], r.at("keys") + "/" + std::to_string(i));
      MotionComponent::Key key;
      key.time = k.number("time", Range::at_least(0, "[s]"));
      key.offset = k.vec2("offset", Vec2::Zero());
      key.angle = k.number("angle", 0.0, Range::any("[rad]"));
      k.finish();
      if (i > 0 && !(key.time > m.keys.back().time))
        ctx.fail(k.at("time"), "time " + num(key.time) + " s is not after the previous key's " + num(m.keys.back().time) +
                                   " s; key times must increase");
      m.keys.push_back(key);
      resolved_keys.push_back(k.resolved());
    }
    r.resolved()["keys"] = resolved_keys;
  }
  r.finish();
  return m;
}

// "motion": one component or an array of them, applied in order.
Motion read_motion(const json& v, const std::string& path, const Context& ctx, json& resolved) {
  Motion motion;
  const bool single = v.is_object();
  if (!single && !v.is_array())
    ctx.fail(path, "expected a motion object or an array of them (types: rotation, translation, oscillation, keyframes), got " + show(v));
  const std::size_t n = single ? 1 : v.size();
  resolved = json::array();
  for (std::size_t i = 0; i < n; ++i) {
    Reader r(ctx, single ? &v : &v[i], single ? path : path + "/" + std::to_string(i));
    motion.components.push_back(read_motion_component(r, ctx));
    resolved.push_back(r.resolved());
  }
  return motion;
}

// The optional "motion" key of a boundary object.
void read_object_motion(Reader& r, const Context& ctx, BoundaryObject& obj) {
  if (const json* m = r.find("motion"); m && !m->is_null()) {
    obj.motion = read_motion(*m, r.at("motion"), ctx, r.resolved()["motion"]);
    obj.moving = true;
  } else {
    r.resolved()["motion"] = nullptr;
  }
}

// A count that is not finite (coordinates near the range of double) is as bad as a huge one.
double finite_or_inf(double x) { return std::isfinite(x) ? x : kInf; }

// What a boundary would cost: the samples BoundaryShape::sample() makes, layer by layer
// as it does (offset layers of a container grow), and the pieces of one fluid spacing
// that curve(h) cuts for the removal of covered fluid. Computed without making them, so
// that a typo in a spacing, a layer spacing or a coordinate is refused before it takes
// the machine's memory.
struct BoundaryCost {
  double samples = 0, curve_pieces = 0;
};

BoundaryCost boundary_cost(const shapes::BoundaryShape& b, double h) {
  using Kind = shapes::BoundaryShape::Kind;
  BoundaryCost c;
  if (b.kind == Kind::Points) {
    c.samples = static_cast<double>(b.points.size());
    return c;
  }
  const bool ellipse = b.kind == Kind::Ellipse;
  for (int k = 0; k < b.layers; ++k) {
    const double d = (k + b.surface_offset) * b.layer_spacing;
    if (ellipse) {
      const Vec2 radii = b.radii + Vec2::Constant(b.fluid_inside ? d : -d);
      if (radii.minCoeff() <= 0) break;
      c.samples += std::max(3.0, finite_or_inf(shapes::ellipse_perimeter(radii.x(), radii.y()) / b.spacing));
      continue;
    }
    const std::vector<Vec2> pts = d == 0 ? b.points : shapes::offset_chain(b.points, b.closed, b.fluid_left ? -d : d);
    const std::size_t n = pts.size(), segs = b.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i)
      c.samples += std::max(1.0, finite_or_inf(std::round(shapes::spacing_integral((pts[(i + 1) % n] - pts[i]).norm(),
                                                                                     b.segment_spacing[i]))));
    c.samples += b.closed ? 0 : 1;
  }
  if (ellipse) {  // curve(h) samples the ellipse at a quarter spacing
    c.curve_pieces = std::max(64.0, finite_or_inf(4 * shapes::ellipse_perimeter(b.radii.x(), b.radii.y()) / h));
  } else {
    const std::size_t n = b.points.size(), segs = b.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i)
      c.curve_pieces += std::max(1.0, finite_or_inf(std::ceil((b.points[(i + 1) % n] - b.points[i]).norm() / h)));
  }
  return c;
}

shapes::BoundaryShape read_boundary(Reader& r, const Context& ctx, std::size_t index, double h, BoundaryObject& obj) {
  std::string& name = obj.name;
  std::string& shape = obj.shape;
  shapes::BoundaryShape b;
  shape = r.choice("shape", {"box", "polyline", "polygon", "circle", "ellipse", "points"}, nullptr);
  name = r.string("name", shape + std::to_string(index));
  if (shape == "points") {
    read_object_motion(r, ctx, obj);
    return read_point_samples(r, ctx);
  }
  bool fluid_inside = false;
  auto side = [&](std::vector<std::string> allowed, const char* def) { return r.choice("fluid_side", allowed, def); };

  if (shape == "box") {
    const Vec2 lo = r.vec2("min"), hi = r.vec2("max");
    if (!(hi.x() > lo.x() && hi.y() > lo.y()))
      ctx.fail(r.at("max"), "max [" + num(hi.x()) + ", " + num(hi.y()) + "] must be above min [" + num(lo.x()) + ", " +
                                num(lo.y()) + "] in x and y");
    b.fluid_left = side({"inside", "outside"}, "inside") == "inside";  // inside is on the left of a CCW walk
    // A container is open at the top by default; an obstacle is a closed solid (a box
    // without its top would be a cup that fills with water).
    const bool lid = r.boolean("lid", !b.fluid_left);
    b.kind = shapes::BoundaryShape::Kind::Box;
    b.min = lo;
    b.max = hi;
    b.lid = lid;
    // spacing entries: bottom, right, top, left (top unused without a lid)
    const auto s = read_segment_spacing(r, ctx, 4, h, true, ": bottom, right, top, left");
    if (lid) {  // counter-clockwise loop from min: bottom, right, top, left
      b.points = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
      b.segment_spacing = s;
      b.closed = true;
    } else {  // open cup: left wall down, bottom, right wall up
      b.points = {{lo.x(), hi.y()}, lo, {hi.x(), lo.y()}, hi};
      b.segment_spacing = {s[3], s[0], s[1]};
    }
  } else if (shape == "polyline" || shape == "polygon") {
    const bool polygon = shape == "polygon";
    b.points = r.points("points", polygon ? 3 : 2);
    b.closed = polygon ? true : r.boolean("closed", false);
    const std::size_t segs = b.closed ? b.points.size() : b.points.size() - 1;
    for (std::size_t i = 0; i < segs; ++i)
      if ((b.points[(i + 1) % b.points.size()] - b.points[i]).norm() == 0)
        ctx.fail(r.at("points") + "/" + std::to_string((i + 1) % b.points.size()),
                 "repeats the previous point; segments must have a length > 0");
    if (const int seg = shapes::self_intersection(b.points, b.closed); seg >= 0)
      ctx.fail(r.at("points"), "segment " + std::to_string(seg) + " crosses or runs along another segment; the " + shape +
                                   " must not intersect or overlap itself");
    if (polygon && shapes::signed_area(b.points) == 0) ctx.fail(r.at("points"), "the polygon has zero area");
    b.segment_spacing = read_segment_spacing(r, ctx, segs, h, true, "");
    if (polygon) {
      fluid_inside = side({"inside", "outside"}, "outside") == "inside";
      b.fluid_left = fluid_inside == (shapes::signed_area(b.points) > 0);
    } else {
      b.fluid_left = side({"left", "right"}, "left") == "left";
    }
  } else {  // circle, ellipse
    b.kind = shapes::BoundaryShape::Kind::Ellipse;
    b.center = r.vec2("center");
    if (shape == "circle") {
      const double radius = r.number("radius", Range::positive("[m]"));
      b.radii = {radius, radius};
    } else {
      b.radii = r.vec2("radii");
      if (b.radii.minCoeff() <= 0) ctx.fail(r.at("radii"), "radii must be > 0 [m], got " + show(r.resolved()["radii"]));
    }
    b.spacing = read_segment_spacing(r, ctx, 1, h, false, "")[0].start;
    b.fluid_inside = side({"inside", "outside"}, "outside") == "inside";
  }
  b.layers = r.integer("layers", 2, 1, 1000);
  b.layer_spacing = r.number("layer_spacing", h, Range::positive("[m]"));
  b.surface_offset = r.number("surface_offset", 0.5, Range::at_least(0, "(in layer spacings)"));
  read_object_motion(r, ctx, obj);
  r.finish();
  return b;
}

std::string about(double count) { return std::isfinite(count) ? "about " + num(std::round(count)) : "too many"; }

// Guard against absurd sample counts (e.g. a spacing typo): refuses a boundary whose
// cost alone, or with the objects before it (`total`, this one included), passes the limit.
void check_boundary_cost(const Context& ctx, const std::string& path, const BoundaryCost& cost, const BoundaryCost& total) {
  if (!(cost.samples <= kMaxParticles))
    ctx.fail(path, "would create " + about(cost.samples) + " boundary samples; the limit is " + num(kMaxParticles) +
                       " (check spacing, layers and layer_spacing)");
  if (!(cost.curve_pieces <= kMaxParticles))
    ctx.fail(path, "the curve would be cut into " + about(cost.curve_pieces) +
                       " pieces of at most one fluid spacing (to clear the fluid next to it); the limit is " +
                       num(kMaxParticles) + " (check the coordinates and /spacing)");
  if (!(total.samples <= kMaxParticles) || !(total.curve_pieces <= kMaxParticles))
    ctx.fail(path, "the boundaries up to this one would create " + about(total.samples) + " samples and " +
                       about(total.curve_pieces) + " curve pieces; the limit is " + num(kMaxParticles) +
                       " of each (check spacing and layers)");
}

// The name becomes a folder (renders/<name>) and a file (<name>.mp4): it must stay one
// path component, so that a scene cannot write outside its output directory.
void check_name(const Context& ctx, const std::string& name) {
  const bool control = std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  if (name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos || control)
    ctx.fail("/name", "invalid value " + show(json(name)) +
                          "; a name must not contain '/', '\\' or control characters, nor be '.' or '..' (it names the "
                          "output folder renders/<name> and the video <name>.mp4)");
}

// Clears the fluid inside the boundaries as they stand at t = 0: objects at rest (and
// moving ones whose script leaves them at rest at t = 0) together, every other moving
// object on its own, with the fluid taken into its rest frame and back.
Index remove_fluid_at_start(Scene& scene, const std::vector<shapes::BoundaryShape>& walls, double h) {
  std::vector<shapes::BoundaryShape> at_rest;
  std::vector<Vec2> rest_samples;
  std::vector<std::size_t> posed;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const BoundaryObject& obj = scene.objects[i];
    const Pose pose = obj.moving ? obj.motion.at(0.0) : Pose{};
    if (pose.angle != 0 || pose.shift != Vec2::Zero()) {
      posed.push_back(i);
      continue;
    }
    at_rest.push_back(walls[i]);
    rest_samples.insert(rest_samples.end(), scene.boundary_x.begin() + obj.first,
                        scene.boundary_x.begin() + obj.first + obj.count);
  }
  Index near = 0;
  Index removed = shapes::remove_covered_fluid(scene.fluid_x, scene.fluid_v, at_rest, rest_samples, h, &near);
  scene.fluid_near_samples = near;
  for (std::size_t i : posed) {
    const BoundaryObject& obj = scene.objects[i];
    const Pose pose = obj.motion.at(0.0);
    const PoseMap back(Pose{-pose.angle, 0, 0, Vec2::Zero(), Vec2::Zero(), Vec2::Zero()});
    // The kept particles are picked by index (carried as the "velocity" of the rest-frame
    // copy), so that their positions are not rounded by the way there and back.
    std::vector<Vec2> rest(scene.fluid_x.size()), index(scene.fluid_x.size());
    for (std::size_t k = 0; k < rest.size(); ++k) {
      rest[k] = back.rotated(scene.fluid_x[k] - pose.shift);
      index[k] = Vec2(static_cast<double>(k), 0);
    }
    const std::vector<Vec2> samples(scene.boundary_x.begin() + obj.first, scene.boundary_x.begin() + obj.first + obj.count);
    removed += shapes::remove_covered_fluid(rest, index, {walls[i]}, samples, h, &near);
    scene.fluid_near_samples += near;
    std::vector<Vec2> x, v;
    for (const Vec2& k : index) {
      x.push_back(scene.fluid_x[static_cast<std::size_t>(k.x())]);
      v.push_back(scene.fluid_v[static_cast<std::size_t>(k.x())]);
    }
    scene.fluid_x = std::move(x);
    scene.fluid_v = std::move(v);
  }
  return removed;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file, const std::vector<std::string>& overrides) {
  const Context ctx{file};
  json root = parse_json(text, ctx);
  // Before the overrides: one of them (e.g. --duration's time.duration) would otherwise
  // report the wrong type as its own mistake.
  if (!root.is_object()) throw SceneError(file + ": the scene must be a JSON object {...}, got " + show(root));
  for (const auto& o : overrides) apply_override(root, o);

  Scene scene;
  scene.file = file;
  Reader top(ctx, &root, "");
  // Look up every top-level key first so that a misspelt section is reported before
  // anything that depends on it.
  const json* name = top.find("name");
  const json* spacing = top.find("spacing");
  const json* sections[5] = {top.find("solver"), top.find("time"), top.find("stability"), top.find("output"),
                             top.find("render")};
  const json* fluid = top.find("fluid");
  const json* boundaries = top.find("boundaries");
  top.finish();

  std::string stem = std::filesystem::path(file).stem().string();
  scene.name = name ? ctx.string(*name, "/name") : (stem.empty() ? "scene" : stem);
  check_name(ctx, scene.name);
  if (!spacing) ctx.fail("/spacing", "missing required key; the fluid particle spacing in m, a number > 0");
  scene.spacing = ctx.number(*spacing, "/spacing", Range::positive("[m]"));
  const double h = scene.spacing;

  json resolved = root;
  resolved["name"] = scene.name;
  resolved["spacing"] = h;
  {
    Reader r(ctx, sections[0], "/solver");
    scene.solver = read_solver(r, ctx);
    resolved["solver"] = r.resolved();
  }
  {
    Reader r(ctx, sections[1], "/time");
    scene.time = read_time(r, ctx);
    resolved["time"] = r.resolved();
  }
  // WCSPH's fixed step must resolve its sound waves (Monaghan 1992): dt <= 0.4 h / c.
  if (scene.solver.type == SolverType::WCSPH && scene.time.dt > 0) {
    const double c = std::sqrt(scene.solver.stiffness / scene.solver.rest_density);
    const double limit = kAcousticCfl * h / c;
    if (scene.time.dt > limit)
      ctx.fail("/time/dt", "WCSPH step " + num(scene.time.dt) + " s exceeds the acoustic limit 0.4 h / c = " + num(limit) +
                               " s (sound speed c = sqrt(stiffness / rest_density) = " + num(c) +
                               " m/s, h = " + num(h) + " m); use time.dt <= " + num(limit) +
                               " or time.dt=null for the adaptive step");
  }
  {
    Reader r(ctx, sections[2], "/stability");
    scene.limits = read_stability(r);
    resolved["stability"] = r.resolved();
  }
  {
    Reader r(ctx, sections[3], "/output");
    scene.output = read_output(r, ctx, scene.name);
    resolved["output"] = r.resolved();
  }
  {
    Reader r(ctx, sections[4], "/render");
    scene.render = read_render(r, ctx);
    resolved["render"] = r.resolved();
  }

  // Shapes.
  if (!fluid) ctx.fail("/fluid", "missing required key; an array of fluid blocks (rectangle, ellipse, polygon)");
  if (!fluid->is_array()) ctx.fail("/fluid", "expected an array of fluid blocks, got " + show(*fluid));
  std::vector<shapes::FluidShape> blocks;
  resolved["fluid"] = json::array();
  for (std::size_t i = 0; i < fluid->size(); ++i) {
    Reader r(ctx, &(*fluid)[i], "/fluid/" + std::to_string(i));
    blocks.push_back(read_fluid_block(r, ctx));
    resolved["fluid"].push_back(r.resolved());
  }

  std::vector<shapes::BoundaryShape> walls;
  std::set<std::string> names;
  BoundaryCost total;  // of all objects: each may stay under the limit, the sum must too
  resolved["boundaries"] = json::array();
  if (boundaries && !boundaries->is_array()) ctx.fail("/boundaries", "expected an array of boundary objects, got " + show(*boundaries));
  for (std::size_t i = 0; boundaries && i < boundaries->size(); ++i) {
    Reader r(ctx, &(*boundaries)[i], "/boundaries/" + std::to_string(i));
    BoundaryObject obj;
    walls.push_back(read_boundary(r, ctx, i, h, obj));
    const BoundaryCost cost = boundary_cost(walls.back(), h);
    total.samples += cost.samples;
    total.curve_pieces += cost.curve_pieces;
    check_boundary_cost(ctx, r.path(), cost, total);
    if (!names.insert(obj.name).second)
      ctx.fail(r.at("name"), "duplicate name \"" + obj.name + "\"; boundary names must be unique");
    resolved["boundaries"].push_back(r.resolved());
    scene.objects.push_back(obj);
  }
  scene.resolved = std::move(resolved);

  // Boundary samples, one contiguous range per object.
  for (std::size_t i = 0; i < walls.size(); ++i) {
    scene.objects[i].geometry = walls[i];
    const auto samples = walls[i].sample();
    // Offsets of coordinates near the range of double overflow; nothing downstream
    // (grids, volumes) can place a sample at infinity.
    for (const Vec2& p : samples)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        ctx.fail("/boundaries/" + std::to_string(i), "its samples would have coordinates beyond the range of numbers "
                                                     "(coordinates, radii or layer_spacing too large); keep them far below 1e300");
    scene.objects[i].first = static_cast<Index>(scene.boundary_x.size());
    scene.objects[i].count = static_cast<Index>(samples.size());
    scene.boundary_x.insert(scene.boundary_x.end(), samples.begin(), samples.end());
    scene.boundary_object.insert(scene.boundary_object.end(), samples.size(), static_cast<Index>(i));
  }

  // Fluid lattice, duplicates of overlapping blocks merged, then the boundary bands cleared.
  double lattice_total = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Vec2 lo, hi;
    blocks[i].bounding_box(lo, hi);
    lattice_total += static_cast<double>(shapes::lattice_count(lo.x(), hi.x(), h)) *
                     static_cast<double>(shapes::lattice_count(lo.y(), hi.y(), h));
    if (lattice_total > kMaxParticles)
      ctx.fail("/fluid/" + std::to_string(i), "the fluid would have more than " + num(kMaxParticles) +
                                                  " lattice points; increase /spacing (now " + num(h) + " m)");
  }
  for (const auto& b : blocks) {
    const auto pts = shapes::fill_lattice(b, h);
    scene.fluid_x.insert(scene.fluid_x.end(), pts.begin(), pts.end());
    scene.fluid_v.insert(scene.fluid_v.end(), pts.size(), b.velocity);
  }
  if (blocks.size() > 1) shapes::merge_duplicates(scene.fluid_x, scene.fluid_v, h, 1e-9 * h);
  const std::size_t lattice_points = scene.fluid_x.size();
  scene.fluid_removed = remove_fluid_at_start(scene, walls, h);
  if (scene.fluid_x.empty())
    ctx.fail("/fluid", "the scene has no fluid particles (" + std::to_string(lattice_points) +
                           (lattice_points ? " lattice points, all removed inside boundaries)"
                                           : " lattice points: the fluid blocks are empty or have no area at this spacing)"));

  // Bounds of everything at t = 0.
  scene.bounds_min = scene.bounds_max = scene.fluid_x.front();
  for (const auto* list : {&scene.fluid_x, &scene.boundary_x})
    for (const Vec2& p : *list) {
      scene.bounds_min = scene.bounds_min.cwiseMin(p);
      scene.bounds_max = scene.bounds_max.cwiseMax(p);
    }
  return scene;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw SceneError(path + ": cannot open scene file: no such file" +
                     (ec && ec != std::errc::no_such_file_or_directory ? " (" + ec.message() + ")" : std::string()));
  if (std::filesystem::is_directory(status))
    throw SceneError(path + ": is a directory; expected a scene file (JSON), e.g. scenes/dam_break.json");
  if (!std::filesystem::is_regular_file(status)) throw SceneError(path + ": not a regular file; expected a scene file (JSON)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file: " + std::strerror(errno));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, overrides);
}

}  // namespace sluice
