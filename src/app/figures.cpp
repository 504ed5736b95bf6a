// `sluice figures`: the command-line face of analysis/figures.h.
#include <cstdio>
#include <filesystem>

#include "analysis/figures.h"
#include "app/commands.h"
#include "io/output.h"
#include "scene/scene.h"

namespace sluice::app {

namespace fs = std::filesystem;
using analysis::FigureKind;
using analysis::FigureSpec;

namespace {

// --size: the syntax of --resolution (view::parse_resolution), with a figure's bounds.
void parse_size(const std::string& text, FigureSpec& spec) {
  view::parse_resolution(text, spec.width, spec.height, "--size");
  if (spec.width < 100 || spec.height < 100 || spec.width > 10000 || spec.height > 10000)
    throw view::FlagError("--size", text, "WxH in pixels, each side 100 to 10000 (e.g. 1200x800)");
}

FigureSpec spec_from(const FiguresOptions& o, FigureKind kind) {
  FigureSpec s;
  s.kind = kind;
  s.inputs = o.inputs;
  s.labels = o.labels;
  s.x = o.x;
  s.y = o.y;
  s.group = o.group;
  s.where = o.where;
  s.color = o.color;
  s.mean = o.mean;
  s.pareto = o.pareto;
  s.highlight = o.highlight;
  s.logx = o.logx;
  s.logy = o.logy;
  s.style = o.style;
  s.title = o.title;
  s.xlabel = o.xlabel;
  s.ylabel = o.ylabel;
  s.output = o.output.empty() ? "figure.png" : o.output;
  parse_size(o.size, s);
  return s;
}

void report(const std::string& output, const std::string& why) {
  if (why.empty())
    std::printf("wrote %s\n", output.c_str());
  else
    throw OutputError(output + ": no figure: " + why);
}

// The standard figures of one or more runs (directories with stats.csv): iterations and
// errors over time with their means, the step size and CFL number, and the distribution
// of the wall time per step over the phases.
int run_standard_figures(const FiguresOptions& o) {
  if (o.inputs.size() > 1 && o.output.empty())
    throw view::FlagError("-o", "(missing)", "a directory for the figures when comparing several runs");
  FiguresOptions base = o;
  base.inputs.clear();
  for (const auto& dir : o.inputs) {
    const fs::path stats = fs::path(dir) / "stats.csv";
    if (!fs::is_regular_file(stats))
      throw io::InputError(stats.string() +
                           ": not found; `figures run` takes run directories written by simulate or render");
    base.inputs.push_back(stats.string());
  }
  const fs::path out = o.output.empty() ? fs::path(o.inputs[0]) / "figures" : fs::path(o.output);
  const std::string ext = "." + o.format;
  struct Plot {
    const char* name;
    FigureKind kind;
    std::vector<std::string> y;
    bool mean;
  };
  const Plot plots[] = {
      {"iterations", FigureKind::Series, {"iterations"}, true},
      {"density_error", FigureKind::Series, {"density_error_percent"}, true},
      {"compression_error", FigureKind::Series, {"avg_error_percent"}, true},
      {"time_step", FigureKind::Series, {"dt"}, false},
      {"cfl", FigureKind::Series, {"max_cfl"}, true},
      {"phases", FigureKind::Box, {"ms_neighbors", "ms_nonpressure", "ms_pressure", "ms_integrate", "ms_total"}, false},
  };
  for (const Plot& p : plots) {
    FiguresOptions f = base;
    f.y = p.y;
    f.mean = p.mean;
    f.x = "time";
    f.output = (out / (std::string(p.name) + ext)).string();
    FigureSpec spec = spec_from(f, p.kind);
    if (p.kind == FigureKind::Box) {
      // One box per phase and run: the phases as labels, the runs as inputs.
      spec.ylabel = "wall time per step [ms]";
    }
    report(spec.output, analysis::make_figure(spec));
  }
  return 0;
}

}  // namespace

int run_figures(const FiguresOptions& o) {
  if (o.inputs.empty()) throw view::FlagError("inputs", "(none)", "one or more CSV files (run: run directories)");
  if (o.kind == "run") {
    if (o.format != "png" && o.format != "svg" && o.format != "pdf")
      throw view::FlagError("--format", o.format, "png, svg or pdf");
    return run_standard_figures(o);
  }
  if (o.kind == "table") {
    std::string md;
    for (const auto& in : o.inputs) {
      const auto t = io::read_csv_table(in);
      if (o.inputs.size() > 1) md += "**" + in + "**\n\n";
      md += analysis::markdown_table(t, o.columns) + (o.inputs.size() > 1 ? "\n" : "");
    }
    if (o.output.empty()) {
      std::fputs(md.c_str(), stdout);
    } else {
      const fs::path out(o.output);
      if (out.has_parent_path()) fs::create_directories(out.parent_path());
      write_file_atomic(o.output, md);
      std::printf("wrote %s\n", o.output.c_str());
    }
    return 0;
  }
  const FigureKind kind = o.kind == "series" ? FigureKind::Series
                          : o.kind == "box"  ? FigureKind::Box
                                             : FigureKind::Scatter;
  const FigureSpec spec = spec_from(o, kind);
  report(spec.output, analysis::make_figure(spec));
  return 0;
}

}  // namespace sluice::app
