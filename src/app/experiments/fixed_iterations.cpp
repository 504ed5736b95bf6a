#include "app/experiments/common.h"

#include <cstdio>

namespace sluice::app::experiments {

// --- Figure 7: compression error against a fixed number of iterations ----------------------------

void fixed_iterations(Context& c) {
  const std::vector<int> counts = c.quick ? std::vector<int>{2, 8} : std::vector<int>{1, 2, 3, 4, 6, 8, 12, 16, 24, 32};
  const double duration = c.quick ? 0.1 : 0.5;
  io::CsvWriter csv(
      "iterations,stable,steps,avg_density_error_percent,max_density_error_percent,avg_predicted_error_percent,"
      "message");
  for (int n : counts) {
    const Scene scene = c.load(
        "column.json", {"time.dt=1e-3", number_override("time.duration", duration),
                        "solver.min_iterations=" + std::to_string(n), "solver.max_iterations=" + std::to_string(n)});
    double predicted = 0;
    const SweepRun r =
        analysis::run_sweep_point(scene, {}, [&](const StepStats& st) { predicted += st.avg_error_percent; });
    print_run(std::to_string(n) + " iterations", r);
    csv.row({std::to_string(n), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4),
             fmt(r.max_density_error, 4), fmt(r.steps > 0 ? predicted / static_cast<double>(r.steps) : 0, 4),
             io::csv_quote(r.message)});
  }
  csv.write(c.dir / "fixed_iterations.csv");
  c.md +=
      "The column with exactly N relaxed Jacobi iterations per step (min = max = N), dt = 1 ms, " + fmt(duration, 3) +
      " s each. The density error is Eq. 15's at each step's start; the predicted error is Eq. 23's at the solver's "
      "exit. Compare with the thesis' Figure 7: the error falls as the iterations grow.\n\n";
  c.table(c.dir / "fixed_iterations.csv", {"iterations", "stable", "avg_density_error_percent",
                                           "max_density_error_percent", "avg_predicted_error_percent"});
  FigureSpec a = spec(FigureKind::Series, c.dir / "fixed_iterations.csv", "iterations",
                      {"avg_density_error_percent", "avg_predicted_error_percent"}, "error_vs_iterations.png");
  a.style = "linespoints";
  a.logy = true;
  a.where = {"stable=1"};
  a.xlabel = "solver iterations per step (fixed)";
  a.ylabel = "average compression error [%]";
  c.figure(a, "Compression error against a fixed number of Jacobi iterations (thesis Figure 7)");
}

}  // namespace sluice::app::experiments
