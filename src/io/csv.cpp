#include "io/csv.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "io/output.h"

namespace sluice::io {

std::vector<std::string> split(const std::string& s, char sep) {
  std::vector<std::string> out;
  std::string cur;
  std::istringstream in(s);
  while (std::getline(in, cur, sep)) out.push_back(cur);
  if (!s.empty() && s.back() == sep) out.push_back("");
  return out;
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? sep : "") + v[i];
  return s;
}

std::string csv_quote(const std::string& s) {
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

std::vector<std::string> parse_csv_line(const std::string& line) {
  std::vector<std::string> out;
  std::string cur;
  bool in_quotes = false;
  for (std::size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (in_quotes) {
      if (c == '"' && i + 1 < line.size() && line[i + 1] == '"')
        cur += '"', ++i;
      else if (c == '"')
        in_quotes = false;
      else
        cur += c;
    } else if (c == '"') {
      in_quotes = true;
    } else if (c == ',') {
      out.push_back(cur);
      cur.clear();
    } else if (c != '\r') {
      cur += c;
    }
  }
  out.push_back(cur);
  return out;
}

bool CsvTable::has_column(const std::string& name) const {
  for (const auto& h : header)
    if (h == name) return true;
  return false;
}

int CsvTable::column(const std::string& name) const {
  for (std::size_t i = 0; i < header.size(); ++i)
    if (header[i] == name) return static_cast<int>(i);
  throw InputError(path + ": no column '" + name + "' (it has: " + join(header, ", ") + ")");
}

std::vector<double> CsvTable::numbers(const std::string& name) const {
  const int c = column(name);
  std::vector<double> v;
  v.reserve(rows.size());
  for (const auto& r : rows) {
    const std::string& f = r[static_cast<std::size_t>(c)];
    char* end = nullptr;
    const double x = std::strtod(f.c_str(), &end);
    v.push_back(!f.empty() && end && *end == '\0' ? x : std::nan(""));
  }
  return v;
}

void CsvWriter::write(const std::string& path) const { write_file_atomic(path, text_); }

CsvTable read_csv_table(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  CsvTable t;
  t.path = path;
  std::string line;
  if (!std::getline(in, line) || line.empty())
    throw InputError(path + ": line 1: expected a header row of column names");
  t.header = parse_csv_line(line);
  for (long n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    auto f = parse_csv_line(line);
    if (f.size() != t.header.size())
      throw InputError(path + ": line " + std::to_string(n) + ": " + std::to_string(f.size()) +
                       " fields, the header has " + std::to_string(t.header.size()));
    t.rows.push_back(std::move(f));
  }
  return t;
}

}  // namespace sluice::io
