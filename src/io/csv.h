#pragma once
// Comma-separated values as sluice writes and reads them: a header row, then one row per
// record; fields holding commas, quotes or semicolons are quoted ("" for a quote).
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace sluice::io {

// A CSV input that cannot be read or lacks what was asked of it (a missing file or
// column, a ragged row), or a figure request that does not fit its data. Not a scene's
// fault: the program answers "sluice: error: ..." and exit status 1.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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

  // Index of a column; throws InputError naming the file, the column and the columns it has.
  int column(const std::string& name) const;
  bool has_column(const std::string& name) const;
  // A column as numbers (NaN for an empty or non-numeric field).
  std::vector<double> numbers(const std::string& name) const;
};

// A CSV file built row by row in memory and written at once (write_file_atomic): the
// header line, then each row's fields joined by commas as given (csv_quote them first
// where they may hold a comma or a quote).
class CsvWriter {
 public:
  explicit CsvWriter(std::string header) : text_(std::move(header) + "\n") {}
  void row(const std::vector<std::string>& fields) { text_ += join(fields, ",") + "\n"; }
  const std::string& text() const { return text_; }
  // Throws OutputError.
  void write(const std::string& path) const;

 private:
  std::string text_;
};

// Reads a CSV file; throws InputError naming the file and line (a missing file, no header,
// a row whose field count differs from the header's).
CsvTable read_csv_table(const std::string& path);

}  // namespace sluice::io
