#pragma once
// Comma-separated values as sluice writes and reads them: a header row, then one row per
// record; fields holding commas, quotes or semicolons are quoted ("" for a quote).
#include <string>
#include <vector>

namespace sluice::analysis {

// Splits at every `sep` (an empty string gives no fields; a trailing sep an empty last one).
std::vector<std::string> split(const std::string& s, char sep);
std::string join(const std::vector<std::string>& v, const char* sep);

// A field in double quotes with inner quotes doubled.
std::string csv_quote(const std::string& s);
// The fields of one CSV line (quotes removed).
std::vector<std::string> parse_csv_line(const std::string& line);

// A whole CSV file in memory: its header and rows of fields, as text.
struct CsvTable {
  std::string path;
  std::vector<std::string> header;
  std::vector<std::vector<std::string>> rows;

  // Index of a column; throws SceneError naming the file, the column and the columns it has.
  int column(const std::string& name) const;
  bool has_column(const std::string& name) const;
  // A column as numbers (NaN for an empty or non-numeric field).
  std::vector<double> numbers(const std::string& name) const;
};

// Reads a CSV file; throws SceneError naming the file and line (a missing file, no header,
// a row whose field count differs from the header's).
CsvTable read_csv_table(const std::string& path);

}  // namespace sluice::analysis
