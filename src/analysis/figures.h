#pragma once
// `sluice figures`: plots of stats and bench CSV files through gnuplot. The numbers a
// figure shows (series, means, box statistics, the Pareto front) are computed here and
// written into the gnuplot script as inline data blocks, so the script next to the
// figure is self-contained: restyle it and rerun `gnuplot FILE.gp`.
#include <string>
#include <vector>

#include "io/csv.h"

namespace sluice::analysis {

enum class FigureKind {
  Series,   // y against x, one line per input (and per --group value); optional mean lines
  Box,      // the distribution of y per input/group: box, whiskers (1.5 IQR), mean as a dot
  Scatter,  // y against x as points; optional colour column (palette) and Pareto front
};

// PNG (pngcairo), SVG or PDF (pdfcairo), chosen by the output file's extension.
enum class FigureFormat { Png, Svg, Pdf };
// Throws SceneError for any other extension, naming the file and what is allowed.
FigureFormat figure_format(const std::string& output);

struct FigureSpec {
  FigureKind kind = FigureKind::Series;
  std::vector<std::string> inputs;  // CSV files
  std::vector<std::string> labels;  // one per input (default: the file's folder and name)
  std::string x = "time";           // series/scatter
  std::vector<std::string> y;       // one or more columns; each makes its own series
  std::string group;                // split each input's rows by this column's value
  std::vector<std::string> where;   // keep only rows with COLUMN=VALUE (all must hold)
  std::string color;                // scatter: colour points by this column (palette)
  bool mean = false;                // series: a dashed line at each series' mean
  bool pareto = false;              // scatter: the Pareto front (smaller x and y better)
  std::string highlight;            // scatter: ring the rows with COLUMN=VALUE in red (e.g. best=1)
  bool logx = false, logy = false;
  std::string style = "lines";        // series: lines, linespoints or points
  std::string title, xlabel, ylabel;  // labels (default: the column's name with its unit)
  std::string output = "figure.png";
  int width = 1200, height = 800;  // pixels for PNG/SVG; PDF is width/200 x height/200 inches
};

// One plotted series: its legend text and points (NaN rows dropped).
struct FigureSeries {
  std::string label;
  std::vector<double> x, y, c;  // c: the colour column (scatter with `color`)
  std::vector<double> hx, hy;   // the highlighted points (scatter with `highlight`)
  double mean = 0;              // of y
};

// Box statistics of one distribution (quartiles by linear interpolation, whiskers at the
// most extreme values within 1.5 IQR of the box).
struct BoxStats {
  double min = 0, q1 = 0, median = 0, q3 = 0, max = 0, mean = 0;
  double whisker_lo = 0, whisker_hi = 0;
  long count = 0;
};
BoxStats box_stats(std::vector<double> values);

// Indices of the Pareto front of (x, y), both smaller-is-better, sorted by x.
std::vector<std::size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y);

// The axis label of a known sluice column, with its unit ("time" -> "simulated time [s]");
// other names are returned as they are.
std::string axis_label(const std::string& column);

// The series the spec selects from the tables (one table per input). Throws SceneError
// naming the file and column when a column is missing or a --where is malformed.
std::vector<FigureSeries> figure_series(const FigureSpec& spec, const std::vector<io::CsvTable>& tables);

// The gnuplot script drawing `series` as the spec asks (pure: for tests).
std::string figure_script(const FigureSpec& spec, const std::vector<FigureSeries>& series);

// Reads the inputs, writes OUTPUT's script (OUTPUT with .gp) and runs gnuplot. Returns ""
// on success or the one-line reason there is no figure (see run_gnuplot). Throws
// SceneError for bad inputs or specs.
std::string make_figure(const FigureSpec& spec);

// A Markdown table of the given columns (all when empty) of a CSV table; numbers are
// printed with `digits` significant digits.
std::string markdown_table(const io::CsvTable& table, const std::vector<std::string>& columns, int digits = 4);

}  // namespace sluice::analysis
