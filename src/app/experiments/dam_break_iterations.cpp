#include "app/experiments/common.h"

#include <algorithm>
#include <cstdio>

#include "io/output.h"

namespace sluice::app::experiments {

// --- Figure 3: iterations and compression error over time (breaking dam) ------------------

void dam_break_iterations(Context& c) {
  std::vector<std::string> own;
  if (c.quick) own = {"time.duration=0.5"};
  const Scene scene = c.load("dam_break.json", own);
  StatsCsv stats((c.dir / "stats.csv").string());
  long max_iterations = 0;
  const SweepRun r = analysis::run_sweep_point(scene, {}, [&](const StepStats& st) {
    stats.write(st);
    max_iterations = std::max<long>(max_iterations, st.iterations);
  });
  stats.finish();
  print_run(scene.name, r);
  c.md += "Scene `" + c.scene_path("dam_break.json") + "`: " + std::to_string(r.particles) + " particles, " +
          std::to_string(r.steps) + " steps to t = " + fmt(r.simulated, 4) + " s" +
          (r.stable ? "" : " (UNSTABLE: " + r.message + ")") + ". Average iterations " + fmt(r.avg_iterations, 4) +
          " (largest " + std::to_string(max_iterations) + "), average density error " + fmt(r.avg_density_error, 3) +
          " %.\n\n";
  FigureSpec a = spec(FigureKind::Series, c.dir / "stats.csv", "time", {"iterations"}, "iterations.png");
  a.mean = true;
  c.figure(a, "Solver iterations per step over time, with their mean (thesis Figure 3, left)");
  FigureSpec b = spec(FigureKind::Series, c.dir / "stats.csv", "time", {"avg_error_percent"}, "compression_error.png");
  b.mean = true;
  c.figure(b, "Predicted average compression error (Eq. 23) at the solver's exit over time (thesis Figure 3, right)");
}

}  // namespace sluice::app::experiments
