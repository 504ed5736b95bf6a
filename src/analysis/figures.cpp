#include "analysis/figures.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>

#include "analysis/plot.h"
#include "scene/scene.h"

namespace sluice::analysis {

using io::CsvTable;
using io::InputError;
using io::join;
using io::read_csv_table;

namespace fs = std::filesystem;

namespace {

// Colour-blind-safe cycle (Tableau 10): the first is IISPH blue, the second WCSPH red in
// the bench figure, so the same solver keeps its colour across figures.
const char* const kColors[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                               "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
const char* color(std::size_t i) { return kColors[i % (sizeof kColors / sizeof kColors[0])]; }

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.10g", v);
  return buf;
}

std::string short_num(double v, int digits = 3) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

bool parse_number(const std::string& s, double& v) {
  char* end = nullptr;
  v = std::strtod(s.c_str(), &end);
  return !s.empty() && end && *end == '\0';
}

double mean_of(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;  // fixed order: the same figure from the same data
  return v.empty() ? 0 : s / static_cast<double>(v.size());
}

// "renders/dam_break/stats.csv" -> "dam_break"; "bench.csv" -> "bench".
std::string default_label(const std::string& path) {
  const fs::path p(path);
  const std::string parent = p.parent_path().filename().string();
  return parent.empty() || parent == "." ? p.stem().string() : parent;
}

struct Where {
  int column;
  std::string value;
};

std::vector<Where> parse_where(const FigureSpec& spec, const CsvTable& t) {
  std::vector<Where> out;
  for (const auto& w : spec.where) {
    const auto eq = w.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--where " + w + ": expected COLUMN=VALUE, e.g. solver=iisph");
    out.push_back({t.column(w.substr(0, eq)), w.substr(eq + 1)});
  }
  return out;
}

bool row_matches(const std::vector<std::string>& row, const std::vector<Where>& where) {
  for (const auto& w : where) {
    const std::string& f = row[static_cast<std::size_t>(w.column)];
    double a = 0, b = 0;
    if (f != w.value && !(parse_number(f, a) && parse_number(w.value, b) && a == b)) return false;
  }
  return true;
}

double field_number(const std::vector<std::string>& row, int column) {
  double v = 0;
  return parse_number(row[static_cast<std::size_t>(column)], v) ? v : std::nan("");
}

std::string terminal(const FigureSpec& spec) {
  const std::string size = std::to_string(spec.width) + "," + std::to_string(spec.height);
  switch (figure_format(spec.output)) {
    case FigureFormat::Png:
      return "set terminal pngcairo size " + size + " enhanced font \"DejaVu Sans,20\" linewidth 2\n";
    case FigureFormat::Svg:
      return "set terminal svg size " + size +
             " dynamic enhanced font \"DejaVu Sans,20\" linewidth 2 background \"white\"\n";
    case FigureFormat::Pdf:
      // 1200 x 800 px -> 6 x 4 in: a column figure at 10 pt, like the PNG's 20 pt at 1200 px.
      return "set terminal pdfcairo size " + short_num(spec.width / 200.0, 6) + "in," +
             short_num(spec.height / 200.0, 6) + "in enhanced font \"DejaVu Sans,10\" linewidth 1.5\n";
  }
  return "";
}

std::string datablock(const std::string& name, const std::vector<std::vector<double>>& columns) {
  std::string s = "$" + name + " << EOD\n";
  const std::size_t n = columns.empty() ? 0 : columns[0].size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t c = 0; c < columns.size(); ++c) s += (c ? " " : "") + num(columns[c][i]);
    s += "\n";
  }
  return s + "EOD\n";
}

std::string series_plot(const FigureSpec& spec, const std::vector<FigureSeries>& series) {
  std::string s, plot;
  const std::string with = spec.style == "points"        ? "points pt 7 ps 1.2"
                           : spec.style == "linespoints" ? "linespoints pt 7 ps 1.2 lw 2"
                                                         : "lines lw 2";
  for (std::size_t i = 0; i < series.size(); ++i) {
    const auto& f = series[i];
    s += datablock("s" + std::to_string(i), {f.x, f.y});
    plot += std::string(plot.empty() ? "plot " : ", \\\n     ") + "$s" + std::to_string(i) + " using 1:2 with " + with +
            " lc rgb \"" + color(i) + "\" title " + gnuplot_quote(f.label) + " noenhanced";
    if (spec.mean && !f.x.empty()) {
      // The mean over the series' own x range: a shorter run's line ends where it ends.
      const auto [lo, hi] = std::minmax_element(f.x.begin(), f.x.end());
      s += datablock("m" + std::to_string(i), {{*lo, *hi}, {f.mean, f.mean}});
      plot += ", \\\n     $m" + std::to_string(i) + " using 1:2 with lines dt 2 lw 2 lc rgb \"" + color(i) +
              "\" title " + gnuplot_quote("mean " + short_num(f.mean, 4)) + " noenhanced";
    }
  }
  return s + plot + "\n";
}

std::string box_plot(const std::vector<FigureSeries>& series) {
  std::vector<double> pos, q1, lo, hi, q3, med, mean, out_x, out_y;
  std::string tics;
  // Beyond five boxes (e.g. `figures run A B`: five phases of two runs) two-line labels
  // run into each other: one line each, slanted.
  const bool slanted = series.size() > 5;
  std::size_t longest = 0;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const BoxStats b = box_stats(series[i].y);
    const double x = static_cast<double>(i + 1);
    pos.push_back(x), q1.push_back(b.q1), lo.push_back(b.whisker_lo), hi.push_back(b.whisker_hi), q3.push_back(b.q3);
    med.push_back(b.median), mean.push_back(b.mean);
    for (double v : series[i].y)
      if (v < b.whisker_lo || v > b.whisker_hi) out_x.push_back(x), out_y.push_back(v);
    // The tic label's second line gives the mean (backslash-n is a newline inside gnuplot's double quotes).
    std::string tic = gnuplot_quote(series[i].label);
    tic.pop_back();
    // Slanted labels leave the mean to its dot (a longer label would leave the image).
    const std::string mean_text = slanted ? "" : "\\nmean " + short_num(b.mean, 3);
    tics += std::string(tics.empty() ? "" : ", ") + tic + mean_text + "\" " + num(x);
    longest = std::max(longest, series[i].label.size() + mean_text.size());
  }
  std::string s = datablock("box", {pos, q1, lo, hi, q3, med, mean});
  if (!out_x.empty()) s += datablock("outliers", {out_x, out_y});
  // A label slanted by 30 degrees needs about a quarter of its length in character heights below the axis.
  s += "set xtics (" + tics + ") noenhanced" + (slanted ? " rotate by 30 right" : "") +
       "\nset xrange [0.4:" + num(static_cast<double>(series.size()) + 0.6) + "]\n" + "set bmargin " +
       std::to_string(slanted ? 3 + static_cast<int>(static_cast<double>(longest) * 0.25) : 5) + "\n" +
       "set boxwidth 0.5\nset style fill solid 0.35 border -1\n"
       "plot $box using 1:2:3:4:5 with candlesticks whiskerbars 0.5 lc rgb \"#1f77b4\" title \"quartiles, 1.5 IQR "
       "whiskers\", \\\n"
       "     $box using 1:6:6:6:6 with candlesticks lc rgb \"black\" lw 2 notitle, \\\n"
       "     $box using 1:7 with points pt 7 ps 1.6 lc rgb \"black\" title \"mean\"";
  if (!out_x.empty())
    s += ", \\\n     $outliers using 1:2 with points pt 6 ps 0.8 lc rgb \"#7f7f7f\" title \"outliers\"";
  return s + "\n";
}

std::string scatter_plot(const FigureSpec& spec, const std::vector<FigureSeries>& series) {
  std::string s, plot;
  const bool palette = !spec.color.empty();
  if (palette)
    s += "set palette defined (0 \"#fde725\", 0.5 \"#21918c\", 1 \"#440154\")\nset cblabel " +
         gnuplot_quote(axis_label(spec.color)) + " noenhanced\n";
  std::vector<double> all_x, all_y;
  for (std::size_t i = 0; i < series.size(); ++i) {
    const auto& f = series[i];
    s += palette ? datablock("s" + std::to_string(i), {f.x, f.y, f.c}) : datablock("s" + std::to_string(i), {f.x, f.y});
    const std::string pt = std::to_string(i % 2 == 0 ? 7 : 5);
    plot += std::string(plot.empty() ? "plot " : ", \\\n     ") + "$s" + std::to_string(i) +
            (palette ? " using 1:2:3 with points pt " + pt + " ps 1.6 lc palette"
                     : " using 1:2 with points pt " + pt + " ps 1.6 lc rgb \"" + color(i) + "\"") +
            " title " + gnuplot_quote(f.label) + " noenhanced";
    all_x.insert(all_x.end(), f.x.begin(), f.x.end());
    all_y.insert(all_y.end(), f.y.begin(), f.y.end());
  }
  std::vector<double> hx, hy;
  for (const auto& f : series)
    hx.insert(hx.end(), f.hx.begin(), f.hx.end()), hy.insert(hy.end(), f.hy.begin(), f.hy.end());
  if (!hx.empty()) {
    s += datablock("highlight", {hx, hy});
    plot += ", \\\n     $highlight using 1:2 with points pt 6 ps 3.2 lw 3 lc rgb \"#e31a1c\" title " +
            // "best=1" is titled "best"; other conditions as written.
            gnuplot_quote(spec.highlight.size() > 2 && spec.highlight.ends_with("=1")
                              ? spec.highlight.substr(0, spec.highlight.size() - 2)
                              : spec.highlight) +
            " noenhanced";
  }
  if (spec.pareto) {
    std::vector<double> px, py;
    for (std::size_t k : pareto_front(all_x, all_y)) px.push_back(all_x[k]), py.push_back(all_y[k]);
    s += datablock("pareto", {px, py});
    plot +=
        ", \\\n     $pareto using 1:2 with linespoints dt 2 lw 2 pt 6 ps 2.4 lc rgb \"black\" title \"Pareto front\"";
  }
  return s + plot + "\n";
}

}  // namespace

FigureFormat figure_format(const std::string& output) {
  const std::string ext = fs::path(output).extension().string();
  if (ext == ".png") return FigureFormat::Png;
  if (ext == ".svg") return FigureFormat::Svg;
  if (ext == ".pdf") return FigureFormat::Pdf;
  throw InputError("-o " + output + ": the figure's format comes from its extension; allowed: .png, .svg, .pdf");
}

BoxStats box_stats(std::vector<double> v) {
  BoxStats b;
  v.erase(std::remove_if(v.begin(), v.end(), [](double x) { return !std::isfinite(x); }), v.end());
  b.count = static_cast<long>(v.size());
  if (v.empty()) return b;
  b.mean = mean_of(v);
  std::sort(v.begin(), v.end());
  auto quantile = [&](double q) {
    const double pos = q * static_cast<double>(v.size() - 1);
    const auto k = static_cast<std::size_t>(std::floor(pos));
    const double f = pos - static_cast<double>(k);
    return k + 1 < v.size() ? v[k] + f * (v[k + 1] - v[k]) : v[k];
  };
  b.min = v.front(), b.max = v.back();
  b.q1 = quantile(0.25), b.median = quantile(0.5), b.q3 = quantile(0.75);
  const double iqr = b.q3 - b.q1;
  b.whisker_lo = b.q1, b.whisker_hi = b.q3;
  for (double x : v)
    if (x >= b.q1 - 1.5 * iqr) {
      b.whisker_lo = x;
      break;
    }
  for (auto it = v.rbegin(); it != v.rend(); ++it)
    if (*it <= b.q3 + 1.5 * iqr) {
      b.whisker_hi = *it;
      break;
    }
  return b;
}

std::vector<std::size_t> pareto_front(const std::vector<double>& x, const std::vector<double>& y) {
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < x.size(); ++i)
    if (std::isfinite(x[i]) && std::isfinite(y[i])) idx.push_back(i);
  // By x, then y: a point is on the front when its y is below every y before it.
  std::stable_sort(idx.begin(), idx.end(),
                   [&](std::size_t a, std::size_t b) { return x[a] != x[b] ? x[a] < x[b] : y[a] < y[b]; });
  std::vector<std::size_t> front;
  double best = HUGE_VAL;
  for (std::size_t i : idx)
    if (y[i] < best) {
      front.push_back(i);
      best = y[i];
    }
  return front;
}

std::string axis_label(const std::string& c) {
  static const std::map<std::string, std::string> known = {
      {"time", "simulated time [s]"},
      {"dt", "time step [s]"},
      {"step", "step"},
      {"iterations", "pressure solver iterations"},
      {"avg_iterations", "average solver iterations per step"},
      {"avg_error_percent", "average compression error [%]"},
      {"max_error_percent", "largest compression error [%]"},
      {"density_error_percent", "average density error [%]"},
      {"avg_density_error_percent", "average density error [%]"},
      {"max_density_error_percent", "largest per-step density error [%]"},
      {"max_cfl", "largest CFL number"},
      {"fluid_particles", "fluid particles"},
      {"particles", "fluid particles"},
      {"threads", "threads"},
      {"ms_neighbors", "neighbour search [ms per step]"},
      {"ms_nonpressure", "non-pressure forces [ms per step]"},
      {"ms_pressure", "pressure solve [ms per step]"},
      {"ms_integrate", "integration [ms per step]"},
      {"ms_total", "wall time per step [ms]"},
      {"ms_boundary", "moving boundaries [ms per step]"},
      {"ms_moving_boundaries", "moving boundaries [ms per step]"},
      {"wall_s", "wall time [s]"},
      {"s_per_simulated_s", "wall time per simulated second [s]"},
      {"us_per_particle_step", "wall time per particle-step [µs]"},
      {"us_neighbors_per_particle", "neighbour search per particle-step [µs]"},
      {"us_pressure_per_particle_iteration", "pressure solve per particle and iteration [µs]"},
      {"us_per_particle_step_fixed_iterations", "wall time per particle-step, fixed iterations [µs]"},
      {"stiffness", "stiffness k [Pa m]"},
      {"pressure_s", "pressure solve [s]"},
      {"neighbors_s", "neighbour search [s]"},
      {"overall_s", "overall [s]"},
      {"avg_predicted_error_percent", "predicted compression error (Eq. 23) [%]"},
      {"ms_per_step", "wall time per step [ms]"},
      {"ms_neighbors_per_step", "neighbour search [ms per step]"},
      {"height", "column height [m]"},
      {"gamma1", "γ1"},
      {"gamma2", "γ2"},
      {"gamma3", "γ3"},
  };
  const auto it = known.find(c);
  return it == known.end() ? c : it->second;
}

std::vector<FigureSeries> figure_series(const FigureSpec& spec, const std::vector<CsvTable>& tables) {
  if (spec.y.empty()) throw InputError("--y: missing; name the column(s) to plot, e.g. --y iterations");
  if (!spec.labels.empty() && spec.labels.size() != spec.inputs.size())
    throw InputError("--label: " + std::to_string(spec.labels.size()) + " given for " +
                     std::to_string(spec.inputs.size()) + " inputs; give one per input or none");
  std::vector<FigureSeries> out;
  for (std::size_t i = 0; i < tables.size(); ++i) {
    const CsvTable& t = tables[i];
    const std::string input_label = spec.labels.empty() ? default_label(t.path) : spec.labels[i];
    const auto where = parse_where(spec, t);
    std::vector<Where> highlight;
    if (!spec.highlight.empty()) {
      FigureSpec h;
      h.where = {spec.highlight};
      highlight = parse_where(h, t);
    }
    const int xc = spec.kind == FigureKind::Box ? -1 : t.column(spec.x);
    const int cc = spec.color.empty() ? -1 : t.column(spec.color);
    std::vector<int> yc;
    for (const auto& y : spec.y) yc.push_back(t.column(y));
    // Groups in the order they first appear (the order the experiment wrote them).
    std::vector<std::string> groups;
    const int gc = spec.group.empty() ? -1 : t.column(spec.group);
    for (const auto& row : t.rows)
      if (row_matches(row, where)) {
        const std::string g = gc < 0 ? "" : row[static_cast<std::size_t>(gc)];
        if (std::find(groups.begin(), groups.end(), g) == groups.end()) groups.push_back(g);
      }
    if (groups.empty())
      throw InputError(t.path + ": no rows" +
                       (spec.where.empty() ? "" : " match --where " + join(spec.where, " --where ")));
    for (const auto& g : groups)
      for (std::size_t k = 0; k < yc.size(); ++k) {
        FigureSeries f;
        std::vector<std::string> parts;
        if (tables.size() > 1 || (groups.size() == 1 && yc.size() == 1)) parts.push_back(input_label);
        // A group is named by its column, except where the value names itself (iisph, zero).
        double numeric = 0;
        const std::string group_name = parse_number(g, numeric) ? spec.group + " = " + g : g;
        if (gc >= 0 && (groups.size() > 1 || tables.size() == 1))
          parts = {tables.size() > 1 ? input_label + ": " + group_name : group_name};
        if (yc.size() > 1) {
          // Box tics are short: "ms_pressure" -> "pressure"; legends get the full label.
          const std::string& y = spec.y[k];
          parts.push_back(spec.kind != FigureKind::Box ? axis_label(y) : y.rfind("ms_", 0) == 0 ? y.substr(3) : y);
        }
        f.label = join(parts, ", ");
        for (const auto& row : t.rows) {
          if (!row_matches(row, where) || (gc >= 0 && row[static_cast<std::size_t>(gc)] != g)) continue;
          const double y = field_number(row, yc[k]);
          const double x = xc < 0 ? 0 : field_number(row, xc);
          const double c = cc < 0 ? 0 : field_number(row, cc);
          if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(c)) continue;
          if ((spec.logx && x <= 0) || (spec.logy && y <= 0)) continue;  // not drawable on a log axis
          f.x.push_back(x), f.y.push_back(y);
          if (cc >= 0) f.c.push_back(c);
          if (!highlight.empty() && row_matches(row, highlight)) f.hx.push_back(x), f.hy.push_back(y);
        }
        f.mean = mean_of(f.y);
        out.push_back(std::move(f));
      }
  }
  return out;
}

std::string figure_script(const FigureSpec& spec, const std::vector<FigureSeries>& series) {
  std::string s = "# Written by `sluice figures`; the data is inline. Rerun: gnuplot " +
                  fs::path(spec.output).stem().string() + ".gp\n" + terminal(spec) + "set output " +
                  gnuplot_quote(fs::path(spec.output).filename().string()) +
                  "\nset grid lc rgb \"#dddddd\"\nset key top left box opaque\n";
  if (!spec.title.empty()) s += "set title " + gnuplot_quote(spec.title) + " noenhanced\n";
  const std::string xl = !spec.xlabel.empty() ? spec.xlabel : spec.kind == FigureKind::Box ? "" : axis_label(spec.x);
  const std::string yl = !spec.ylabel.empty() ? spec.ylabel : spec.y.size() == 1 ? axis_label(spec.y[0]) : "";
  if (!xl.empty()) s += "set xlabel " + gnuplot_quote(xl) + " noenhanced\n";
  if (!yl.empty()) s += "set ylabel " + gnuplot_quote(yl) + " noenhanced\n";
  if (spec.logx) s += "set logscale x\n";
  if (spec.logy) s += "set logscale y\n";
  // The legend above the plot, in rows: inside it covered the data where runs start
  // (the spikes at t = 0) or a box's outliers; beside it, it took a third of the width.
  s += "set key outside top center horizontal box opaque\n";
  switch (spec.kind) {
    case FigureKind::Series:
      return s + series_plot(spec, series);
    case FigureKind::Box:
      return s + box_plot(series);
    case FigureKind::Scatter:
      return s + scatter_plot(spec, series);
  }
  return s;
}

std::string make_figure(const FigureSpec& spec) {
  figure_format(spec.output);  // a bad extension fails before any work
  if (spec.inputs.empty()) throw InputError("figures: no input CSV files");
  if (spec.style != "lines" && spec.style != "linespoints" && spec.style != "points")
    throw InputError("--style " + spec.style + ": allowed: lines, linespoints, points");
  if (spec.width < 100 || spec.height < 100 || spec.width > 10000 || spec.height > 10000)
    throw InputError("--size " + std::to_string(spec.width) + "x" + std::to_string(spec.height) +
                     ": each side must be 100 to 10000 pixels");
  std::vector<CsvTable> tables;
  for (const auto& in : spec.inputs) tables.push_back(read_csv_table(in));
  const auto series = figure_series(spec, tables);
  for (const auto& f : series)
    if (f.y.empty())
      throw InputError("figures: the series '" + f.label + "' has no plottable rows (all NaN" +
                       std::string(spec.logx || spec.logy ? ", or not positive on a log axis" : "") + ")");
  const fs::path out(spec.output);
  if (out.has_parent_path()) fs::create_directories(out.parent_path());
  fs::path script = out;
  script.replace_extension(".gp");
  return run_gnuplot(script.string(), figure_script(spec, series));
}

std::string markdown_table(const CsvTable& t, const std::vector<std::string>& columns, int digits) {
  std::vector<int> cols;
  for (const auto& c : columns) cols.push_back(t.column(c));
  if (cols.empty())
    for (std::size_t i = 0; i < t.header.size(); ++i) cols.push_back(static_cast<int>(i));
  auto cell = [&](const std::string& f) {
    double v = 0;
    std::string s =
        parse_number(f, v) && f.find_first_not_of("0123456789-") != std::string::npos ? short_num(v, digits) : f;
    std::string e;
    for (char ch : s) e += ch == '|' ? std::string("\\|") : std::string(1, ch);
    return e;
  };
  std::string md = "|", rule = "|";
  for (int c : cols) md += " " + t.header[static_cast<std::size_t>(c)] + " |", rule += "---|";
  md += "\n" + rule + "\n";
  for (const auto& row : t.rows) {
    md += "|";
    for (int c : cols) md += " " + cell(row[static_cast<std::size_t>(c)]) + " |";
    md += "\n";
  }
  return md;
}

}  // namespace sluice::analysis
