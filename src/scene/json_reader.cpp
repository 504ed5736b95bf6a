// The validation framework of scene files and the parsing of their text (json_reader.h).
#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <iterator>
#include <optional>
#include <set>

#include "scene/scene.h"

namespace sluice::scene_detail {

namespace {

// Nesting of JSON arrays and objects: a scene needs 7 levels; a hostile file of a
// million '[' would overflow the stack where values are copied or printed.
constexpr std::size_t kMaxDepth = 100;

// "line:column" (1-based) of byte `pos` of `text`.
std::string line_column(const std::string& text, std::size_t pos) {
  const std::size_t line =
      1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<long>(pos), '\n'));
  const std::size_t nl = pos == 0 ? std::string::npos : text.rfind('\n', pos - 1);
  return std::to_string(line) + ":" + std::to_string(nl == std::string::npos ? pos + 1 : pos - nl);
}

std::string message(const std::string& file, const std::string& where, const std::string& path,
                    const std::string& problem) {
  return file + (where.empty() ? "" : ":" + where) + ": " + (path.empty() ? "/" : path) + ": " + problem;
}

// The opening quote of the string whose closing quote is at `close` (one not escaped by
// an odd number of backslashes); `close` itself when there is none.
std::size_t opening_quote(const std::string& text, std::size_t close) {
  for (std::size_t q = close; q-- > 0;)
    if (text[q] == '"') {
      std::size_t slashes = 0;
      while (q > slashes && text[q - 1 - slashes] == '\\') ++slashes;
      if (slashes % 2 == 0) return q;
    }
  return close;
}

// A character iterator that counts the characters the parser has taken, so that a parser
// callback knows where in the text it is: the last token (and, after a number, the one
// character the lexer looked ahead) ends at the count.
class CountingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  CountingIterator(const char* p, std::size_t* taken) : p_(p), taken_(taken) {}
  reference operator*() const { return *p_; }
  CountingIterator& operator++() {
    ++p_;
    ++*taken_;
    return *this;
  }
  CountingIterator operator++(int) {
    CountingIterator old = *this;
    ++*this;
    return old;
  }
  bool operator==(const CountingIterator& o) const { return p_ == o.p_; }

 private:
  const char* p_;
  std::size_t* taken_;
};

// Where the scalar (string, number, true, false, null) that ends at `taken` characters begins.
std::size_t scalar_start(const std::string& text, std::size_t taken) {
  std::size_t end = std::min(taken, text.size());
  if (end > 0 && text[end - 1] == '"') return opening_quote(text, end - 1);
  auto token = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '+' || c == '-'; };
  if (end > 0 && !token(text[end - 1])) --end;  // the character a number was ended by
  while (end > 0 && token(text[end - 1])) --end;
  return end;
}

// The JSON pointer of each value the parser's callback is told about.
struct PathTracker {
  struct Frame {
    bool array = false;
    long index = 0;
    std::string path, key;
    std::set<std::string> keys;
  };
  std::vector<Frame> frames;

  std::string child_path() const {
    if (frames.empty()) return std::string();
    const Frame& f = frames.back();
    return f.path + "/" + (f.array ? std::to_string(f.index) : escape_key(f.key));
  }
  void start(bool array) { frames.push_back({array, 0, child_path(), "", {}}); }
  void end() {
    frames.pop_back();
    next();
  }
  void next() {
    if (!frames.empty() && frames.back().array) ++frames.back().index;
  }
};

// The offset of the value at `path` in valid JSON `text` (the last one, were a key
// repeated); none when the text has no such value.
std::optional<std::size_t> locate(const std::string& text, const std::string& path) {
  std::size_t taken = 0;
  PathTracker t;
  std::optional<std::size_t> found;
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (t.child_path() == path) found = taken - 1;
        t.start(event == json::parse_event_t::array_start);
        return true;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        t.end();
        return true;
      case json::parse_event_t::key:
        t.frames.back().key = parsed.get<std::string>();
        return true;
      case json::parse_event_t::value:
        if (t.child_path() == path) found = scalar_start(text, taken);
        t.next();
        return false;  // only the positions are wanted, not the values
    }
    return true;
  };
  const json skeleton =
      json::parse(CountingIterator(text.data(), &taken), CountingIterator(text.data() + text.size(), &taken), callback,
                  /*allow_exceptions=*/false);
  (void)skeleton;  // the containers, emptied of their values
  return found;
}

}  // namespace

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

std::string escape_key(const std::string& key) {
  std::string out;
  for (char c : key) out += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
  return out;
}

// --- ranges and single values ------------------------------------------------------------------

bool Range::contains(double v) const {
  return std::isfinite(v) && (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::describe() const {
  std::string s;
  if (hi == kInf && lo == -kInf)
    s = "must be a finite number";
  else if (hi == kInf)
    s = std::string("must be ") + (lo_open ? "> " : ">= ") + num(lo);
  else
    s = "must be in " + std::string(lo_open ? "(" : "[") + num(lo) + ", " + num(hi) + (hi_open ? ")" : "]");
  return unit.empty() ? s : s + " " + unit;
}

void Context::fail(const std::string& path, const std::string& problem) const {
  // A value an override set, or one holding such a value, is not the file's as written.
  const bool as_written = std::none_of(overridden.begin(), overridden.end(), [&](const std::string& o) {
    return path == o || path.starts_with(o + "/") || o.starts_with(path + "/");
  });
  std::string where;
  if (text && as_written)
    if (const auto at = locate(*text, path)) where = line_column(*text, *at);
  throw SceneError(message(file, where, path, problem));
}

double Context::number(const json& v, const std::string& path, const Range& r) const {
  if (!v.is_number()) fail(path, "expected a number, got " + show(v));
  const double x = v.get<double>();
  if (!r.contains(x)) fail(path, "value " + show(v) + " is out of range; " + r.describe());
  return x;
}

int Context::integer(const json& v, const std::string& path, int lo, int hi) const {
  if (!v.is_number_integer()) fail(path, "expected an integer, got " + show(v));
  const long double x = v.is_number_unsigned() ? static_cast<long double>(v.get<unsigned long long>())
                                               : static_cast<long double>(v.get<long long>());
  if (x < lo || x > hi)
    fail(path, "value " + show(v) + " is out of range; must be an integer in [" + std::to_string(lo) + ", " +
                   std::to_string(hi) + "]");
  return static_cast<int>(x);
}

bool Context::boolean(const json& v, const std::string& path) const {
  if (!v.is_boolean()) fail(path, "expected true or false, got " + show(v));
  return v.get<bool>();
}

std::string Context::string(const json& v, const std::string& path) const {
  if (!v.is_string() || v.get<std::string>().empty()) fail(path, "expected a non-empty string, got " + show(v));
  return v.get<std::string>();
}

std::string Context::choice(const json& v, const std::string& path, const std::vector<std::string>& allowed) const {
  if (!v.is_string() || std::find(allowed.begin(), allowed.end(), v.get<std::string>()) == allowed.end())
    fail(path, "invalid value " + show(v) + "; must be one of: " + join(allowed));
  return v.get<std::string>();
}

Vec2 Context::vec2(const json& v, const std::string& path) const {
  if (!v.is_array() || v.size() != 2 || !v[0].is_number() || !v[1].is_number() || !std::isfinite(v[0].get<double>()) ||
      !std::isfinite(v[1].get<double>()))
    fail(path, "expected an array of 2 numbers, got " + show(v));
  return {v[0].get<double>(), v[1].get<double>()};
}

std::vector<Vec2> Context::points(const json& v, const std::string& path, std::size_t min_count) const {
  if (!v.is_array() || v.size() < min_count)
    fail(path, "expected an array of at least " + std::to_string(min_count) + " points [x, y], got " + show(v));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < v.size(); ++i) out.push_back(vec2(v[i], path + "/" + std::to_string(i)));
  return out;
}

// --- the keys of one object --------------------------------------------------------------------

Reader::Reader(const Context& ctx, const json* j, std::string path) : ctx_(ctx), path_(std::move(path)) {
  if (j && !j->is_object()) ctx.fail(path_, "expected an object, got " + show(*j));
  if (j) j_ = *j;
}

const json* Reader::find(const std::string& key) {
  allowed_.push_back(key);
  const auto it = j_.find(key);
  return it == j_.end() ? nullptr : &*it;
}

const json& Reader::require(const std::string& key, const std::string& what) {
  if (const json* v = find(key)) return *v;
  ctx_.fail(at(key), "missing required key; " + what);
}

double Reader::number(const std::string& key, double def, const Range& r) {
  const json* v = find(key);
  const double x = v ? ctx_.number(*v, at(key), r) : def;
  out_[key] = x;
  return x;
}

double Reader::number(const std::string& key, const Range& r) {
  const double x = ctx_.number(require(key, "a number that " + r.describe()), at(key), r);
  out_[key] = x;
  return x;
}

int Reader::integer(const std::string& key, int def, int lo, int hi) {
  const json* v = find(key);
  const int x = v ? ctx_.integer(*v, at(key), lo, hi) : def;
  out_[key] = x;
  return x;
}

bool Reader::boolean(const std::string& key, bool def) {
  const json* v = find(key);
  const bool x = v ? ctx_.boolean(*v, at(key)) : def;
  out_[key] = x;
  return x;
}

std::string Reader::string(const std::string& key, const std::string& def) {
  const json* v = find(key);
  std::string x = v ? ctx_.string(*v, at(key)) : def;
  out_[key] = x;
  return x;
}

Vec2 Reader::vec2(const std::string& key, const Vec2& def) {
  const json* v = find(key);
  const Vec2 x = v ? ctx_.vec2(*v, at(key)) : def;
  out_[key] = {x.x(), x.y()};
  return x;
}

Vec2 Reader::vec2(const std::string& key) {
  const Vec2 x = ctx_.vec2(require(key, "an array of 2 numbers [x, y]"), at(key));
  out_[key] = {x.x(), x.y()};
  return x;
}

std::vector<Vec2> Reader::points(const std::string& key, std::size_t min_count) {
  const json& v = require(key, "an array of at least " + std::to_string(min_count) + " points [x, y]");
  auto pts = ctx_.points(v, at(key), min_count);
  out_[key] = v;
  return pts;
}

std::string Reader::choice(const std::string& key, const std::vector<std::string>& allowed, const char* def) {
  const json* v = def ? find(key) : &require(key, "must be one of: " + join(allowed));
  std::string x = v ? ctx_.choice(*v, at(key), allowed) : def;
  out_[key] = x;
  return x;
}

void Reader::finish() const {
  for (const auto& item : j_.items())
    if (std::find(allowed_.begin(), allowed_.end(), item.key()) == allowed_.end())
      ctx_.fail(at(item.key()), "unknown key; allowed keys: " + join(allowed_));
}

// --- parsing the text --------------------------------------------------------------------------

json parse_json(const std::string& text, const Context& ctx) {
  // nlohmann keeps the last of duplicate keys; the callback turns that into an error.
  PathTracker t;
  std::size_t taken = 0;  // characters the parser has read
  std::string duplicate;
  std::size_t duplicate_at = 0;
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (t.frames.size() >= kMaxDepth)
          throw SceneError(message(ctx.file, line_column(text, taken - 1), t.child_path(),
                                   "arrays and objects are nested more than " + std::to_string(kMaxDepth) +
                                       " levels deep; a scene needs fewer than 10"));
        t.start(event == json::parse_event_t::array_start);
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        t.end();
        break;
      case json::parse_event_t::key:
        t.frames.back().key = parsed.get<std::string>();
        if (!t.frames.back().keys.insert(t.frames.back().key).second && duplicate.empty()) {
          duplicate = t.child_path();
          // Its value follows the ':' (were the text not valid there, the syntax error wins).
          duplicate_at = std::min(text.find_first_not_of(" \t\r\n:", taken), text.size());
        }
        break;
      case json::parse_event_t::value:
        t.next();
        break;
    }
    return true;
  };
  // A NUL ends what some readers see of the file; nothing may hide after one.
  if (const std::size_t nul = text.find('\0'); nul != std::string::npos)
    throw SceneError(ctx.file + ":" + line_column(text, nul) + ": a NUL byte; a scene file is JSON text");
  json j;
  try {
    j = json::parse(CountingIterator(text.data(), &taken), CountingIterator(text.data() + text.size(), &taken),
                    callback);
  } catch (const json::parse_error& e) {
    // e.byte counts the characters read; the last one read is where the error is.
    std::size_t pos = std::min<std::size_t>(e.byte > 0 ? e.byte - 1 : 0, text.size());
    // An unexpected string is reported at its closing quote; point at its opening quote.
    if (pos < text.size() && text[pos] == '"' &&
        std::string(e.what()).find("unexpected string literal") != std::string::npos)
      pos = opening_quote(text, pos);
    std::string detail = e.what();
    std::size_t p = detail.find("column ");
    p = p == std::string::npos ? detail.find("] ") : detail.find(": ", p);
    if (p != std::string::npos) detail = detail.substr(p + 2);
    throw SceneError(ctx.file + ":" + line_column(text, pos) + ": JSON parse error: " + detail);
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e999'" carries no position: find the number in the text.
    const std::string what = e.what();
    const std::size_t q1 = what.find('\''), q2 = what.rfind('\'');
    const std::size_t at =
        q1 != std::string::npos && q2 > q1 ? text.find(what.substr(q1 + 1, q2 - q1 - 1)) : std::string::npos;
    const std::string detail = what.substr(what.find("] ") == std::string::npos ? 0 : what.find("] ") + 2);
    throw SceneError(ctx.file + (at == std::string::npos ? "" : ":" + line_column(text, at)) +
                     ": JSON parse error: " + detail + " (numbers must be within the range of double, about 1.8e308)");
  } catch (const json::exception& e) {
    throw SceneError(ctx.file + ": JSON parse error: " + e.what());
  }
  if (!duplicate.empty())
    throw SceneError(
        message(ctx.file, line_column(text, duplicate_at), duplicate, "duplicate key; each key may appear only once"));
  return j;
}

}  // namespace sluice::scene_detail
