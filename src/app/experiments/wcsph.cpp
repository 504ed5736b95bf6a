#include "app/experiments/common.h"

#include <cstdio>

namespace sluice::app::experiments {

// --- Table 3 and Figure 12: WCSPH ---------------------------------------------------------------

void wcsph(Context& c) {
  const std::vector<double> ks = c.quick ? std::vector<double>{1e5, 1e6} : std::vector<double>{1e5, 3e5, 1e6, 3e6, 1e7};
  const double duration = c.quick ? 0.05 : 1.0;
  io::CsvWriter series("stiffness,time,density_error_percent");
  io::CsvWriter by_k(
      "stiffness,stable,steps,avg_density_error_percent,max_density_error_percent,s_per_simulated_s,message");
  for (double k : ks) {
    Scene scene;
    try {
      scene = c.load("column.json", {"solver.type=wcsph", number_override("solver.stiffness", k), "time.dt=1e-4",
                                     number_override("time.duration", duration)});
    } catch (const SceneError& e) {  // a step beyond WCSPH's acoustic limit is refused at load
      std::printf("  k = %s: refused: %s\n", fmt(k).c_str(), e.what());
      by_k.row({fmt(k), "0", "0", "", "", "", io::csv_quote(std::string("refused: ") + e.what())});
      continue;
    }
    long n = 0;
    const SweepRun r = analysis::run_sweep_point(scene, {}, [&](const StepStats& st) {
      // Every 10th step from 10 ms on (the first steps start from the lattice's zero error,
      // which a log axis would stretch over ten decades).
      if (n++ % 10 == 0 && st.time >= 0.01) series.row({fmt(k), fmt(st.time), fmt(st.density_error_percent, 5)});
    });
    print_run("k = " + fmt(k), r);
    by_k.row({fmt(k), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4),
              fmt(r.max_density_error, 4), fmt(r.seconds_per_simulated_second(), 4), io::csv_quote(r.message)});
  }
  series.write(c.dir / "error_over_time.csv");
  by_k.write(c.dir / "stiffness.csv");

  const std::vector<double> dts =
      c.quick ? std::vector<double>{1e-4, 2e-4} : std::vector<double>{2.5e-5, 5e-5, 1e-4, 2e-4, 4e-4};
  const double k = 1e6;
  const double dt_duration = c.quick ? 0.05 : 0.5;
  io::CsvWriter by_dt(
      "dt,stable,steps,avg_density_error_percent,pressure_s,neighbors_s,overall_s,s_per_simulated_s,message");
  for (double dt : dts) {
    Scene scene;
    try {
      scene = c.load("column.json", {"solver.type=wcsph", number_override("solver.stiffness", k),
                                     number_override("time.dt", dt), number_override("time.duration", dt_duration)});
    } catch (const SceneError& e) {
      std::printf("  k = 1e6, dt = %s: refused: %s\n", fmt(dt).c_str(), e.what());
      by_dt.row({fmt(dt), "0", "0", "", "", "", "", "", io::csv_quote(std::string("refused: ") + e.what())});
      continue;
    }
    const SweepRun r = analysis::run_sweep_point(scene, {});
    print_run("k = 1e6, dt = " + fmt(dt), r);
    const double n = static_cast<double>(r.steps) / 1000.0;
    by_dt.row({fmt(dt), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4),
               fmt(r.ms_phase[2] * n, 4), fmt(r.ms_phase[0] * n, 4), fmt(r.ms_phase[4] * n, 4),
               fmt(r.seconds_per_simulated_second(), 4), io::csv_quote(r.message)});
  }
  by_dt.write(c.dir / "time_step.csv");
  c.md += "WCSPH on the 5000-particle column, " + fmt(duration, 3) + " simulated seconds per stiffness run and " +
          fmt(dt_duration, 3) +
          " per time-step run (the thesis' Table 3 uses 100 frames). First the stiffness k at dt = 0.1 ms "
          "(thesis Figure 12: the error falls as k grows), then the time step at k = 1e6 (thesis Table 3: WCSPH's "
          "pressure is cheap, its step is small; an unstable run is reported, not hidden). Load average at the end " +
          fmt(load_average(), 3) + ".\n\n";
  c.table(c.dir / "stiffness.csv",
          {"stiffness", "stable", "avg_density_error_percent", "max_density_error_percent", "s_per_simulated_s"});
  c.table(c.dir / "time_step.csv",
          {"dt", "stable", "steps", "avg_density_error_percent", "pressure_s", "neighbors_s", "overall_s"});
  FigureSpec a =
      spec(FigureKind::Series, c.dir / "error_over_time.csv", "time", {"density_error_percent"}, "error_over_time.png");
  a.group = "stiffness";
  a.mean = true;
  a.logy = true;
  c.figure(a, "WCSPH average density error over time for each stiffness k at dt = 0.1 ms (thesis Figure 12)");
}

}  // namespace sluice::app::experiments
