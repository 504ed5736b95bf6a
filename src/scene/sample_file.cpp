// Boundary samples from a text file (sample_file.h).
#include "scene/sample_file.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <system_error>

namespace sluice::scene_detail {

namespace {

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
  auto is = [](const std::string& f, char c) {
    return f.size() == 1 && std::tolower(static_cast<unsigned char>(f[0])) == c;
  };
  return fields.size() == 2 && is(fields[0], 'x') && is(fields[1], 'y');
}
}  // namespace

std::vector<Vec2> read_sample_file(const std::filesystem::path& path, const std::string& json_path,
                                   const Context& ctx) {
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
    ctx.fail(json_path,
             path.string() + ": no samples (only empty lines, comments or a header); give at least one line x,y");
  return out;
}

}  // namespace sluice::scene_detail
