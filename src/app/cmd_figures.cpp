// `sluice figures`: its flags; the figures are run_figures (app/figures.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_figures(CLI::App& app) {
  auto fig = std::make_shared<FiguresOptions>();
  CLI::App* figcmd = app.add_subcommand(
      "figures", "Figures from stats/bench/experiment CSV files with gnuplot: series, box, scatter, table, run");
  figcmd
      ->add_option("kind", fig->kind,
                   "series (y over x), box (distributions), scatter (points, Pareto front), "
                   "table (Markdown), run (the standard figures of run directories)")
      ->required()
      ->check(CLI::IsMember({"series", "box", "scatter", "table", "run"}));
  figcmd->add_option("inputs", fig->inputs, "CSV files (run: directories holding stats.csv)")->required();
  figcmd->add_option("--x", fig->x, "Column on the x axis (default time)");
  figcmd->add_option("--y", fig->y, "Column(s) to plot; each is its own series")->delimiter(',');
  figcmd->add_option("--label", fig->labels, "Legend label per input (default: its directory's name)");
  figcmd->add_option("--group", fig->group, "Split each input's rows into series by this column's value");
  figcmd->add_option("--where", fig->where, "Keep only rows with COLUMN=VALUE (repeatable)");
  figcmd->add_option("--color", fig->color, "scatter: colour the points by this column");
  figcmd->add_flag("--mean", fig->mean, "series: add a dashed line at each series' mean");
  figcmd->add_flag("--pareto", fig->pareto, "scatter: draw the Pareto front (smaller x and y are better)");
  figcmd->add_option("--highlight", fig->highlight, "scatter: ring the rows with COLUMN=VALUE in red (e.g. best=1)");
  figcmd->add_flag("--logx", fig->logx, "Logarithmic x axis");
  figcmd->add_flag("--logy", fig->logy, "Logarithmic y axis");
  figcmd->add_option("--style", fig->style, "series: lines, linespoints or points")
      ->check(CLI::IsMember({"lines", "linespoints", "points"}));
  figcmd->add_option("--title", fig->title, "Figure title (default none: papers put it in the caption)");
  figcmd->add_option("--xlabel", fig->xlabel, "x axis label (default: the column with its unit)");
  figcmd->add_option("--ylabel", fig->ylabel, "y axis label (default: the column with its unit)");
  figcmd->add_option("-o,--output", fig->output,
                     "Figure file; .png, .svg or .pdf picks the format (table: a .md file, default stdout; "
                     "run: a directory, default RUN/figures)");
  figcmd->add_option("--size", fig->size, "Figure size WxH in pixels (default 1200x800; PDF: 6x4 in)");
  figcmd->add_option("--columns", fig->columns, "table: the columns to show (default all)")->delimiter(',');
  figcmd->add_option("--format", fig->format, "run: png, svg or pdf")->check(CLI::IsMember({"png", "svg", "pdf"}));
  return {figcmd, [fig] { return run_figures(*fig); }};
}

}  // namespace sluice::app
