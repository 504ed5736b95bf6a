// `sluice figures` (analysis/figures.h) and `sluice experiment`: the statistics a figure
// shows, the gnuplot script, errors on bad input, and the quick versions of the thesis'
// experiments through the program itself, checked for the trends the thesis reports.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "analysis/figures.h"
#include "analysis/plot.h"
#include "app/eta.h"
#include "io/csv.h"
#include "scene/scene.h"
#include "test_process.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using analysis::FigureKind;
using analysis::FigureSpec;
using test::CaseDir;
using test::read_text;
using test::run_sluice;
using test::write_text;

io::CsvTable table_of(const CaseDir& dir, const std::string& name, const std::string& text) {
  write_text(dir.work() / name, text);
  return io::read_csv_table((dir.work() / name).string());
}

TEST(Figures, BoxStatsQuartilesWhiskersAndMean) {
  const auto b = analysis::box_stats({4, 1, 100, 3, 2, std::nan("")});
  EXPECT_EQ(b.count, 5);
  EXPECT_DOUBLE_EQ(b.min, 1);
  EXPECT_DOUBLE_EQ(b.q1, 2);
  EXPECT_DOUBLE_EQ(b.median, 3);
  EXPECT_DOUBLE_EQ(b.q3, 4);
  EXPECT_DOUBLE_EQ(b.max, 100);
  EXPECT_DOUBLE_EQ(b.mean, 22);
  EXPECT_DOUBLE_EQ(b.whisker_lo, 1);
  EXPECT_DOUBLE_EQ(b.whisker_hi, 4);  // 100 lies beyond q3 + 1.5 IQR = 7: an outlier
  const auto even = analysis::box_stats({1, 2, 3, 4});
  EXPECT_DOUBLE_EQ(even.median, 2.5);
  EXPECT_DOUBLE_EQ(even.q1, 1.75);
  EXPECT_EQ(analysis::box_stats({}).count, 0);
}

TEST(Figures, ParetoFrontKeepsOnlyUndominatedPointsSortedByX) {
  const std::vector<double> x = {3, 1, 2, 4, 2, 5, std::nan("")};
  const std::vector<double> y = {4, 5, 3, 1, 3.5, 1, 0};
  const auto front = analysis::pareto_front(x, y);
  ASSERT_EQ(front.size(), 3u);
  EXPECT_EQ(front[0], 1u);  // (1, 5)
  EXPECT_EQ(front[1], 2u);  // (2, 3); (2, 3.5) and (3, 4) are dominated
  EXPECT_EQ(front[2], 3u);  // (4, 1); (5, 1) is dominated by it
}

TEST(Figures, SeriesGroupsFiltersAndDropsWhatCannotBeDrawn) {
  const CaseDir dir;
  const auto t = table_of(dir, "runs.csv",
                          "solver,stable,x,y\niisph,1,1,10\nwcsph,1,2,20\niisph,0,3,30\niisph,1,4,\nwcsph,1,-1,5\n");
  FigureSpec s;
  s.kind = FigureKind::Scatter;
  s.inputs = {t.path};
  s.x = "x";
  s.y = {"y"};
  s.group = "solver";
  s.where = {"stable=1"};
  s.logx = true;
  const auto series = analysis::figure_series(s, {t});
  ASSERT_EQ(series.size(), 2u);
  EXPECT_EQ(series[0].label, "iisph");
  EXPECT_EQ(series[0].x, std::vector<double>({1}));  // unstable row filtered, empty y dropped
  EXPECT_EQ(series[1].label, "wcsph");
  EXPECT_EQ(series[1].x, std::vector<double>({2}));  // x = -1 cannot sit on a log axis
  EXPECT_DOUBLE_EQ(series[1].mean, 20);
}

TEST(Figures, ScriptCarriesItsDataMeansAndFormat) {
  const CaseDir dir;
  const auto t = table_of(dir, "stats.csv", "time,iterations\n0.1,4\n0.2,6\n0.3,8\n");
  FigureSpec s;
  s.inputs = {t.path};
  s.y = {"iterations"};
  s.mean = true;
  s.output = "out/it.svg";
  const auto series = analysis::figure_series(s, {t});
  const std::string gp = analysis::figure_script(s, series);
  EXPECT_NE(gp.find("set terminal svg"), std::string::npos);
  EXPECT_NE(gp.find("$s0 << EOD\n0.1 4\n0.2 6\n0.3 8\nEOD"), std::string::npos) << gp;
  EXPECT_NE(gp.find("mean 6"), std::string::npos);
  EXPECT_NE(gp.find("simulated time [s]"), std::string::npos);  // the unit from the column's name
  EXPECT_NE(gp.find("pressure solver iterations"), std::string::npos);
  s.output = "it.pdf";
  EXPECT_NE(analysis::figure_script(s, series).find("pdfcairo"), std::string::npos);
}

TEST(Figures, LegendGoesWhereItCoversNoData) {
  const CaseDir dir;
  const auto t =
      table_of(dir, "scaling.csv", "particles,us_per_particle_step,us_neighbors_per_particle,a,b,c\n1,2,3,4,5,6\n");
  FigureSpec s;
  s.inputs = {t.path};
  s.x = "particles";
  for (const auto& y :
       std::vector<std::vector<std::string>>{{"a"}, {"a", "b"}, {"a", "b", "c", "us_per_particle_step"}}) {
    s.y = y;
    const std::string gp = analysis::figure_script(s, analysis::figure_series(s, {t}));
    // Above the plot, whatever the entries: inside, it covered the spikes at t = 0.
    EXPECT_NE(gp.find("set key outside top center horizontal"), std::string::npos) << gp;
    EXPECT_EQ(gp.find("set key top left"), gp.rfind("set key top left")) << gp;  // only the preamble's default
  }
}

TEST(Figures, MeanLineEndsWithItsRun) {
  const CaseDir dir;
  const auto a = table_of(dir, "a/stats.csv", "time,iterations\n0,4\n0.5,6\n1.0,8\n");
  const auto b = table_of(dir, "b/stats.csv", "time,iterations\n0,2\n0.25,4\n");
  FigureSpec s;
  s.inputs = {a.path, b.path};
  s.y = {"iterations"};
  s.mean = true;
  const std::string gp = analysis::figure_script(s, analysis::figure_series(s, {a, b}));
  // Each mean is a segment over its run's times, not a line across the whole axis.
  EXPECT_NE(gp.find("$m0 << EOD\n0 6\n1 6\nEOD"), std::string::npos) << gp;
  EXPECT_NE(gp.find("$m1 << EOD\n0 3\n0.25 3\nEOD"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("\n     6 with lines"), std::string::npos) << gp;
}

TEST(Figures, CrowdedBoxLabelsAreSlantedOnOneLine) {
  const CaseDir dir;
  const auto a = table_of(dir, "runA/stats.csv", "ms_neighbors,ms_nonpressure,ms_pressure\n1,2,3\n2,3,4\n");
  const auto b = table_of(dir, "runB/stats.csv", "ms_neighbors,ms_nonpressure,ms_pressure\n1,2,3\n2,3,4\n");
  FigureSpec s;
  s.kind = FigureKind::Box;
  s.inputs = {a.path};
  s.y = {"ms_neighbors", "ms_nonpressure", "ms_pressure"};
  std::string gp = analysis::figure_script(s, analysis::figure_series(s, {a}));
  EXPECT_EQ(gp.find("rotate"), std::string::npos);  // three boxes: two-line labels fit
  s.inputs = {a.path, b.path};
  gp = analysis::figure_script(s, analysis::figure_series(s, {a, b}));
  EXPECT_NE(gp.find("rotate by 30 right"), std::string::npos) << gp;
  EXPECT_NE(gp.find("\"runB, nonpressure\" 5"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("\\nmean"), std::string::npos) << gp;
}

TEST(Figures, BadInputNamesTheFileTheColumnAndWhatIsAllowed) {
  const CaseDir dir;
  const auto t = table_of(dir, "stats.csv", "time,iterations\n0.1,4\n");
  FigureSpec s;
  s.inputs = {t.path};
  s.y = {"iterationz"};
  try {
    analysis::figure_series(s, {t});
    FAIL() << "a missing column must throw";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no column 'iterationz' (it has: time, iterations)"), std::string::npos)
        << e.what();
  }
  s.y = {"iterations"};
  s.where = {"time=9"};
  EXPECT_THROW(analysis::figure_series(s, {t}), io::InputError);  // no rows match
  EXPECT_THROW(analysis::figure_format("a.jpg"), io::InputError);
  write_text(dir.work() / "ragged.csv", "a,b\n1,2\n3\n");
  try {
    io::read_csv_table((dir.work() / "ragged.csv").string());
    FAIL() << "a short row must throw";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("line 3: 1 fields, the header has 2"), std::string::npos) << e.what();
  }
}

// The progress line's ETA (src/app/eta.h): none before a few frames, then the recent
// frames' pace rather than the pace since the start.
TEST(Eta, NoEstimateBeforeAFewFramesThenTheRecentPace) {
  app::EtaEstimate eta(10, 3);
  eta.add(0, 0);
  eta.add(17, 0.1);  // the first frame carries 16 s of set-up
  EXPECT_FALSE(eta.seconds_left(2.0).has_value());
  eta.add(18, 0.2);
  eta.add(19, 0.3);
  EXPECT_FALSE(eta.seconds_left(2.0).has_value());               // three frames: still none
  for (int k = 4; k <= 14; ++k) eta.add(19 + (k - 3), 0.1 * k);  // then 1 s per 0.1 s
  ASSERT_TRUE(eta.seconds_left(2.0).has_value());
  // 0.6 s left at 10 s per simulated second; since the start it would say about 14 s.
  EXPECT_NEAR(*eta.seconds_left(2.0), 6.0, 1e-9);
  EXPECT_EQ(*eta.seconds_left(1.0), 0.0);  // past the end
}

TEST(Figures, MarkdownTableChoosesColumnsAndEscapes) {
  const CaseDir dir;
  const auto t = table_of(dir, "t.csv", "name,value,count\n\"a|b\",0.123456789,12\n");
  EXPECT_EQ(analysis::markdown_table(t, {"name", "value"}), "| name | value |\n|---|---|\n| a\\|b | 0.1235 |\n");
  EXPECT_EQ(analysis::markdown_table(t, {"count"}), "| count |\n|---|\n| 12 |\n");
}

TEST(Figures, MakeFigureWritesTheImageAndItsScript) {
  ASSERT_TRUE(analysis::gnuplot_available()) << "gnuplot-nox is a dependency (scripts/install-deps.sh)";
  const CaseDir dir;
  const auto t = table_of(dir, "it.csv", "method,iterations\nextrapolation,3\nextrapolation,5\nzero,4\nzero,9\n");
  FigureSpec s;
  s.kind = FigureKind::Box;
  s.inputs = {t.path};
  s.y = {"iterations"};
  s.group = "method";
  for (const char* ext : {"png", "svg", "pdf"}) {
    s.output = (dir.work() / "figs" / (std::string("box.") + ext)).string();
    EXPECT_EQ(analysis::make_figure(s), "");
    EXPECT_GT(fs::file_size(s.output), 1000u) << s.output;
  }
  EXPECT_TRUE(fs::exists(dir.work() / "figs" / "box.gp"));
}

// --- the program ---------------------------------------------------------------------------

std::vector<std::string> experiment_args(const std::vector<std::string>& names) {
  std::vector<std::string> a = {"experiment"};
  a.insert(a.end(), names.begin(), names.end());
  a.insert(a.end(), {"--quick", "-o", "out", "--scenes", std::string(SLUICE_SOURCE_DIR) + "/scenes"});
  return a;
}

double value(const io::CsvTable& t, std::size_t row, const std::string& column) { return t.numbers(column).at(row); }

TEST(Experiments, FixedIterationsErrorFallsWithIterations) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"fixed-iterations"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto t = io::read_csv_table((dir.work() / "out/fixed-iterations/fixed_iterations.csv").string());
  ASSERT_EQ(t.rows.size(), 2u);  // 2 and 8 iterations
  EXPECT_EQ(value(t, 0, "stable"), 1);
  EXPECT_EQ(value(t, 1, "stable"), 1);
  EXPECT_LT(value(t, 1, "avg_density_error_percent"), 0.5 * value(t, 0, "avg_density_error_percent"));
  EXPECT_TRUE(fs::exists(dir.work() / "out/fixed-iterations/error_vs_iterations.png"));
  EXPECT_NE(read_text(dir.work() / "out/fixed-iterations/summary.md").find("Figure 7"), std::string::npos);
}

TEST(Experiments, IterationsGrowWithTimeStepAndColumnHeight) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"iisph-dt", "column-height"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto dt = io::read_csv_table((dir.work() / "out/iisph-dt/iisph_dt.csv").string());
  ASSERT_EQ(dt.rows.size(), 2u);
  EXPECT_GT(value(dt, 1, "avg_iterations"), value(dt, 0, "avg_iterations"));  // Figure 6a
  const auto h = io::read_csv_table((dir.work() / "out/column-height/column_height.csv").string());
  ASSERT_EQ(h.rows.size(), 6u);  // Jacobi at 0.25 and 0.5 m, then Chebyshev and multilevel at both
  EXPECT_EQ(h.rows[0][0], "jacobi");
  EXPECT_EQ(h.rows[2][0], "chebyshev");
  EXPECT_EQ(h.rows[4][0], "multilevel");
  EXPECT_GT(value(h, 1, "particles"), value(h, 0, "particles"));
  EXPECT_GT(value(h, 1, "avg_iterations"), value(h, 0, "avg_iterations"));  // Figure 6b
  // The quick runs (0.1 s from the lattice) take 3 to 4 iterations, about the 3 plain sweeps
  // before Chebyshev's extrapolation starts: its advantage in depth is tested by
  // Physics.ChebyshevSolvesADeepColumnInFewerIterations, the multilevel solve's flat
  // iterations by Multilevel.IterationsDoNotGrowWithTheDepth. Here: their runs hold the tolerance.
  for (std::size_t row : {2u, 3u, 4u, 5u}) {
    EXPECT_EQ(value(h, row, "stable"), 1);
    EXPECT_LE(value(h, row, "avg_density_error_percent"), 0.1);
  }
  EXPECT_TRUE(fs::exists(dir.work() / "out/README.md"));  // the index of several experiments
}

TEST(Experiments, BoundaryIterationsUseTheGammaSearchsBest) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"boundary-gamma", "boundary-iterations"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto best = io::read_csv_table((dir.work() / "out/boundary-gamma/best.csv").string());
  EXPECT_EQ(best.rows.size(), 3u);
  const auto means = io::read_csv_table((dir.work() / "out/boundary-iterations/means.csv").string());
  ASSERT_EQ(means.rows.size(), 3u);
  for (const auto& row : means.rows) EXPECT_NE(row[static_cast<std::size_t>(means.column("gammas"))], "scene");
  const auto steps = io::read_csv_table((dir.work() / "out/boundary-iterations/iterations.csv").string());
  EXPECT_GT(steps.rows.size(), 30u);
  EXPECT_TRUE(fs::exists(dir.work() / "out/boundary-iterations/iterations_by_method.png"));
  EXPECT_TRUE(fs::exists(dir.work() / "out/boundary-gamma/gamma_zero.png"));
}

TEST(Experiments, NeighbourSearchAndSpeedErrorWriteTheirTables) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"neighbour-search", "speed-error"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto ns = io::read_csv_table((dir.work() / "out/neighbour-search/neighbour_search.csv").string());
  ASSERT_EQ(ns.rows.size(), 4u);
  EXPECT_EQ(ns.rows[0][1], "naive");
  EXPECT_EQ(ns.rows[1][1], "hashing");
  EXPECT_EQ(ns.rows[0][0], ns.rows[1][0]);  // the same scene for both searches
  const auto se = io::read_csv_table((dir.work() / "out/speed-error/dam_break.csv").string());
  ASSERT_EQ(se.rows.size(), 2u);
  EXPECT_EQ(se.rows[0][2], "iisph");
  EXPECT_EQ(se.rows[1][2], "wcsph");
  EXPECT_NE(read_text(dir.work() / "out/speed-error/summary.md").find("Pareto front from fastest"), std::string::npos);
}

TEST(Experiments, ScalingRunsEachWidthAtTheToleranceAndWithFixedIterations) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"scaling"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto t = io::read_csv_table((dir.work() / "out/scaling/scaling.csv").string());
  ASSERT_EQ(t.rows.size(), 2u);
  const auto col = [&](const std::string& name) { return static_cast<size_t>(t.column(name)); };
  EXPECT_LT(std::stol(t.rows[0][col("particles")]), std::stol(t.rows[1][col("particles")]));
  for (const auto& row : t.rows)
    EXPECT_EQ(std::stod(row[col("fixed_iterations")]), 6.0);  // every step ran exactly the fixed count
  // The ratio column is the wider run's time over the first's (to the table's 4 digits).
  const auto us = [&](size_t row) { return std::stod(t.rows[row][col("us_per_particle_step_fixed_iterations")]); };
  EXPECT_NEAR(std::stod(t.rows[1][col("ratio_to_first_fixed_iterations")]), us(1) / us(0), 1e-3 * us(1) / us(0));
  EXPECT_NE(read_text(dir.work() / "out/scaling/summary.md").find("with fixed iterations"), std::string::npos);
}

TEST(Experiments, ParallelTimesTheSolverAndTheMachinesLoopsForEachThreadCount) {
  const CaseDir dir;
  const auto r = run_sluice(dir, experiment_args({"parallel"}));
  ASSERT_EQ(r.status, 0) << r.err;
  const auto eff = io::read_csv_table((dir.work() / "out/parallel/efficiency.csv").string());
  ASSERT_GE(eff.rows.size(), 2u);  // 1 and 2 threads (and all cores where there are more)
  EXPECT_EQ(value(eff, 0, "threads"), 1);
  // One round (--quick): the speed-up is the 1-thread time over the t-thread time, its
  // range is that one value, and the efficiency is the speed-up per thread.
  for (size_t row = 0; row < eff.rows.size(); ++row) {
    const double speedup = value(eff, row, "speedup"), threads = value(eff, row, "threads");
    EXPECT_NEAR(speedup, value(eff, 0, "ms_per_step") / value(eff, row, "ms_per_step"), 2e-3 * speedup) << row;
    EXPECT_NEAR(value(eff, row, "efficiency"), speedup / threads, 2e-3 * speedup) << row;
    EXPECT_EQ(value(eff, row, "speedup_min"), speedup);
    EXPECT_EQ(value(eff, row, "speedup_max"), speedup);
  }
  const auto m = io::read_csv_table((dir.work() / "out/parallel/machine.csv").string());
  ASSERT_EQ(m.rows.size(), 2 * eff.rows.size());  // the memory stream and the arithmetic loop per thread count
  const auto col = [&](const std::string& name) { return static_cast<size_t>(m.column(name)); };
  EXPECT_EQ(m.rows[0][col("loop")], "memory stream");
  EXPECT_EQ(m.rows[1][col("loop")], "arithmetic");
  // The stream moves 3 arrays of 8 MiB twice (--quick) at every thread count: GB/s times ms
  // is that volume in MB.
  for (size_t row = 0; row < m.rows.size(); row += 2) {
    const double volume = std::stod(m.rows[row][col("gb_per_s")]) * std::stod(m.rows[row][col("ms")]);
    EXPECT_NEAR(volume, 3.0 * (8 << 20) * 2 / 1e6, 2e-3 * volume) << m.rows[row][col("threads")] << " threads";
  }
  EXPECT_NE(read_text(dir.work() / "out/parallel/summary.md").find("The machine in the same rounds"),
            std::string::npos);
  // Figure 11's columns: a row per thread count, the speed-up of one thread against itself is 1.
  const auto cols = io::read_csv_table((dir.work() / "out/parallel/column_threads.csv").string());
  ASSERT_EQ(cols.rows.size(), eff.rows.size());  // the quick run has one column
  EXPECT_EQ(value(cols, 0, "threads"), 1);
  for (size_t row = 0; row < cols.rows.size(); ++row) {
    const double speedup = value(cols, row, "speedup");
    EXPECT_NEAR(speedup, value(cols, 0, "ms_per_step") / value(cols, row, "ms_per_step"), 2e-3 * speedup) << row;
  }
  EXPECT_EQ(value(cols, 0, "avg_iterations"), value(cols, 1, "avg_iterations"));  // the same bits for any thread count
}

TEST(Experiments, UnknownNameAndBadFiguresInputAreOneLineErrors) {
  const CaseDir dir;
  auto r = run_sluice(dir, {"experiment", "figure-99"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("figure-99"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("iisph-dt"), std::string::npos) << r.err;  // lists what is allowed
  write_text(dir.work() / "s.csv", "time,iterations\n0,3\n");
  // A CSV or figure mistake is the input's, not a scene's: exit 1, not "scene error" (2).
  r = run_sluice(dir, {"figures", "series", "s.csv", "--y", "iterations", "-o", "x.jpg"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find(".png, .svg, .pdf"), std::string::npos) << r.err;
  r = run_sluice(dir, {"figures", "series", "s.csv", "--y", "iters", "-o", "x.png"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("no column 'iters'"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("scene error"), std::string::npos) << r.err;
  r = run_sluice(dir, {"figures", "run", "nowhere"});
  EXPECT_EQ(r.status, 1);
  EXPECT_NE(r.err.find("nowhere/stats.csv"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("scene error"), std::string::npos) << r.err;
}

TEST(Experiments, FiguresRunDrawsTheStandardFiguresOfARun) {
  const CaseDir dir;
  auto r = run_sluice(dir, {"simulate", std::string(SLUICE_SOURCE_DIR) + "/scenes/column.json", "-q", "-o", "run",
                            "--set", "spacing=0.04", "--duration", "0.1"});
  ASSERT_EQ(r.status, 0) << r.err;
  r = run_sluice(dir, {"figures", "run", "run"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"iterations", "density_error", "compression_error", "time_step", "cfl", "phases"})
    EXPECT_TRUE(fs::exists(dir.work() / "run/figures" / (std::string(f) + ".png"))) << f;
  r = run_sluice(dir, {"figures", "table", "run/stats.csv", "--columns", "step,iterations"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.rfind("| step | iterations |\n|---|---|\n| 1 | ", 0), 0u) << r.out;
}

}  // namespace
}  // namespace sluice
