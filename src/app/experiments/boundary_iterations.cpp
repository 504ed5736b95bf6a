#include "app/experiments/common.h"

#include <cstdio>
#include <map>

namespace sluice::app::experiments {

// --- Figures 9 and 10: boundary methods -----------------------------------------------------------

void boundary_iterations(Context& c) {
  // The gammas of boundary-gamma when it ran into the same output directory.
  std::map<std::string, std::vector<std::string>> gammas;
  const fs::path best = c.root / "boundary-gamma" / "best.csv";
  if (fs::exists(best)) {
    const auto t = io::read_csv_table(best.string());
    for (const auto& row : t.rows)
      gammas[row[static_cast<std::size_t>(t.column("method"))]] = {
          "solver.gamma1=" + row[static_cast<std::size_t>(t.column("gamma1"))],
          "solver.gamma2=" + row[static_cast<std::size_t>(t.column("gamma2"))],
          "solver.gamma3=" + row[static_cast<std::size_t>(t.column("gamma3"))]};
  }
  io::CsvWriter steps("method,time,iterations,density_error_percent");
  io::CsvWriter means("method,gammas,stable,steps,avg_iterations,avg_density_error_percent");
  for (const char* method : kMethods) {
    auto own = boundary_scene(c, 2.0);
    own.push_back(std::string("solver.boundary_pressure=") + method);
    const auto g = gammas.find(method);
    if (g != gammas.end()) own.insert(own.end(), g->second.begin(), g->second.end());
    const SweepRun r = analysis::run_sweep_point(c.load("dam_break.json", own), {}, [&](const StepStats& st) {
      steps.row({method, fmt(st.time), std::to_string(st.iterations), fmt(st.density_error_percent, 5)});
    });
    print_run(method, r);
    means.row({method, g == gammas.end() ? "scene" : io::csv_quote(io::join(g->second, " ")), r.stable ? "1" : "0",
               std::to_string(r.steps), fmt(r.avg_iterations, 4), fmt(r.avg_density_error, 4)});
  }
  steps.write(c.dir / "iterations.csv");
  means.write(c.dir / "means.csv");
  c.md += std::string("The breaking dam at h = 0.02, dt = 2 ms, with each boundary method, ") +
          (gammas.empty() ? "with the scene's gammas (run boundary-gamma first into the same output directory to use "
                            "its best ones)"
                          : "with boundary-gamma's best gammas") +
          ". Compare with the thesis' Figure 10 (extrapolation 20.5, mirroring 21.2, zero pressure 21.4 iterations on "
          "average).\n\n";
  c.table(c.dir / "means.csv", {});
  FigureSpec a = spec(FigureKind::Box, c.dir / "iterations.csv", "", {"iterations"}, "iterations_by_method.png");
  a.group = "method";
  c.figure(a,
           "Distribution of the solver iterations per step for each boundary method; the dot is the mean (thesis "
           "Figure 10)");
}

}  // namespace sluice::app::experiments
