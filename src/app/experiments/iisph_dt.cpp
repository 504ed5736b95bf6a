#include "app/experiments/common.h"

#include <cstdio>

namespace sluice::app::experiments {

// --- Figure 6a and Table 2: IISPH against the time step --------------------------------------

void iisph_dt(Context& c) {
  const std::vector<double> dts =
      c.quick ? std::vector<double>{1e-3, 2e-3} : std::vector<double>{2.5e-4, 5e-4, 7.5e-4, 1e-3, 1.5e-3, 2e-3};
  // 100 frames at 30 fps, as the thesis' Table 2.
  const double duration = c.quick ? 0.1 : 100.0 / 30.0;
  io::CsvWriter csv(
      "dt,stable,particles,steps,avg_iterations,avg_density_error_percent,max_density_error_percent,pressure_s,"
      "neighbors_s,overall_s,s_per_simulated_s,best");
  std::vector<SweepRun> runs;
  for (double dt : dts) {
    const Scene scene = c.load("column.json", {number_override("time.dt", dt),
                                               number_override("time.duration", duration), "solver.type=iisph"});
    runs.push_back(analysis::run_sweep_point(scene, {}));
    print_run("dt = " + fmt(dt), runs.back());
  }
  std::size_t best = runs.size();
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].stable && (best == runs.size() || runs[i].ms_phase[4] * static_cast<double>(runs[i].steps) <
                                                      runs[best].ms_phase[4] * static_cast<double>(runs[best].steps)))
      best = i;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SweepRun& r = runs[i];
    const double n = static_cast<double>(r.steps) / 1000.0;
    csv.row({fmt(dts[i]), r.stable ? "1" : "0", std::to_string(r.particles), std::to_string(r.steps),
             fmt(r.avg_iterations, 4), fmt(r.avg_density_error, 4), fmt(r.max_density_error, 4),
             fmt(r.ms_phase[2] * n, 4), fmt(r.ms_phase[0] * n, 4), fmt(r.ms_phase[4] * n, 4),
             fmt(r.seconds_per_simulated_second(), 4), i == best ? "1" : "0"});
  }
  csv.write(c.dir / "iisph_dt.csv");
  c.md +=
      "The 5000-particle column (`" + c.scene_path("column.json") + "`), " + fmt(duration, 4) +
      " simulated seconds per run, tolerance 0.1 %. Times are the solver's wall time in seconds (pressure = the "
      "relaxed Jacobi solve, neighbors = the neighbour search, overall = the whole steps); load average at the end " +
      fmt(load_average(), 3) +
      ". Compare with the thesis' Table 2 and Figure 6a: iterations grow with dt, the "
      "overall time has a minimum where fewer steps stop paying for more iterations.\n\n";
  c.table(c.dir / "iisph_dt.csv", {"dt", "stable", "steps", "avg_iterations", "avg_density_error_percent", "pressure_s",
                                   "neighbors_s", "overall_s", "best"});
  if (best < runs.size()) c.md += "Fastest overall: dt = " + fmt(dts[best]) + " s (`best` = 1).\n\n";
  FigureSpec a = spec(FigureKind::Series, c.dir / "iisph_dt.csv", "dt", {"avg_iterations"}, "iterations_vs_dt.png");
  a.style = "linespoints";
  a.where = {"stable=1"};
  c.figure(a, "Average solver iterations against the time step (thesis Figure 6a)");
  FigureSpec b = spec(FigureKind::Series, c.dir / "iisph_dt.csv", "dt", {"pressure_s", "neighbors_s", "overall_s"},
                      "times_vs_dt.png");
  b.style = "linespoints";
  b.where = {"stable=1"};
  b.ylabel = "wall time for the run [s]";
  c.figure(b, "Pressure solve, neighbour search and overall time against the time step (thesis Table 2)");
}

}  // namespace sluice::app::experiments
