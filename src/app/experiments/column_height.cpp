#include "app/experiments/common.h"

#include <cstdio>

namespace sluice::app::experiments {

// --- Figure 6b: IISPH against the column height -------------------------------------------------

void column_height_experiment(Context& c) {
  const std::vector<double> heights =
      c.quick ? std::vector<double>{0.25, 0.5} : std::vector<double>{0.25, 0.5, 1, 2, 4};
  const std::vector<std::string> solvers = {"jacobi", "chebyshev", "multilevel"};
  const double duration = c.quick ? 0.1 : 0.5;
  io::CsvWriter csv(
      "pressure_solver,height,particles,stable,steps,avg_iterations,avg_density_error_percent,s_per_simulated_s");
  for (const std::string& solver : solvers)
    for (double h : heights) {
      auto own = column_height(0.5, h);
      own.push_back("time.dt=1e-3");
      own.push_back("solver.pressure_solver=" + solver);
      own.push_back(number_override("time.duration", duration));
      const Scene scene = c.load("column.json", own);
      const SweepRun r = analysis::run_sweep_point(scene, {});
      print_run(solver + ", height = " + fmt(h) + " m", r);
      csv.row({solver, fmt(h), std::to_string(r.particles), r.stable ? "1" : "0", std::to_string(r.steps),
               fmt(r.avg_iterations, 4), fmt(r.avg_density_error, 4), fmt(r.seconds_per_simulated_second(), 4)});
    }
  csv.write(c.dir / "column_height.csv");
  c.md += "Columns 0.5 m wide of growing height at h = 0.01, dt = 1 ms, " + fmt(duration, 3) +
          " s each, tolerance 0.1 %, for the thesis' relaxed Jacobi, its Chebyshev semi-iteration and the "
          "multilevel solve (solver.pressure_solver; a multilevel iteration is a sweep or a coarse correction). "
          "Compare with the thesis' Figure 6b: with Jacobi, deeper columns need more iterations.\n\n";
  c.table(c.dir / "column_height.csv", {});
  FigureSpec a =
      spec(FigureKind::Series, c.dir / "column_height.csv", "height", {"avg_iterations"}, "iterations_vs_height.png");
  a.style = "linespoints";
  a.where = {"stable=1"};
  a.group = "pressure_solver";
  c.figure(a,
           "Average solver iterations against the column height at dt = 1 ms (thesis Figure 6b), by pressure solver");
}

}  // namespace sluice::app::experiments
