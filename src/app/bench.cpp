// `sluice bench`: time scenes side by side; print a table and write CSV.
// Each scene runs `repeat` times from its initial state for `steps` steps; the run with
// the median wall time is reported, with its per-phase split per particle-step.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/commands.h"
#include "io/output.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace sluice::app {

namespace {

struct BenchRow {
  std::string scene;
  std::string solver;
  int threads = 0;
  long particles = 0;
  RunTotals totals;
  double us_per_particle_step(int phase) const {
    const double ps = static_cast<double>(totals.steps) * static_cast<double>(particles);
    return ps > 0 ? 1000.0 * totals.sum_ms[phase] / ps : 0.0;
  }
};

BenchRow run_once(const Scene& scene, long steps, bool brute_force) {
  Simulation sim(scene);
  sim.set_brute_force_neighbors(brute_force);
  BenchRow row;
  row.scene = scene.name;
  row.solver = to_string(scene.solver.type);
  row.threads = omp_get_max_threads();
  row.particles = static_cast<long>(scene.fluid_x.size());
  const auto t0 = std::chrono::steady_clock::now();
  while (!sim.finished() && (steps == 0 || row.totals.steps < steps)) row.totals.add(sim.step());
  row.totals.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

}  // namespace

int run_bench(const BenchOptions& o) {
  set_threads(o.threads);
  std::vector<BenchRow> rows;
  std::printf("%-18s %-6s %3s %8s %6s %7s %9s %9s %9s | %8s %8s %8s %8s %8s\n", "scene", "solver", "thr", "particles",
              "steps", "iters", "err_%", "dens_err%", "us/p-step", "neighb", "nonpres", "pressure", "integr", "moving");
  for (const std::string& file : o.scenes) {
    const Scene scene = load_scene(file, o.set);
    std::vector<BenchRow> runs;
    for (int r = 0; r < o.repeat; ++r) runs.push_back(run_once(scene, o.steps, o.brute_force));
    std::sort(runs.begin(), runs.end(),
              [](const BenchRow& a, const BenchRow& b) { return a.totals.sum_ms[4] < b.totals.sum_ms[4]; });
    const BenchRow& m = runs[runs.size() / 2];
    const double ns = std::max(1.0, static_cast<double>(m.totals.steps));
    std::printf("%-18s %-6s %3d %8ld %6ld %7.2f %9.4f %9.4f %9.4f | %8.4f %8.4f %8.4f %8.4f %8.4f\n", m.scene.c_str(),
                m.solver.c_str(), m.threads, m.particles, m.totals.steps, m.totals.sum_iterations / ns,
                m.totals.sum_avg_error / ns, m.totals.sum_density_error / ns, m.us_per_particle_step(4),
                m.us_per_particle_step(0), m.us_per_particle_step(1), m.us_per_particle_step(2),
                m.us_per_particle_step(3), m.us_per_particle_step(5));
    std::fflush(stdout);
    rows.push_back(m);
  }
  const std::filesystem::path csv(o.csv);
  if (csv.has_parent_path()) std::filesystem::create_directories(csv.parent_path());
  std::string text =
      "scene,solver,threads,particles,steps,avg_iterations,avg_error_percent,density_error_percent,"
      "us_per_particle_step,us_neighbors,us_nonpressure,us_pressure,us_integrate,us_moving_boundaries,ms_per_step,repeats\n";
  for (const BenchRow& m : rows) {
    const double ns = std::max(1.0, static_cast<double>(m.totals.steps));
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%ld,%ld,%.4f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f,%d\n",
                  m.scene.c_str(), m.solver.c_str(), m.threads, m.particles, m.totals.steps,
                  m.totals.sum_iterations / ns, m.totals.sum_avg_error / ns, m.totals.sum_density_error / ns,
                  m.us_per_particle_step(4), m.us_per_particle_step(0), m.us_per_particle_step(1),
                  m.us_per_particle_step(2), m.us_per_particle_step(3), m.us_per_particle_step(5),
                  m.totals.sum_ms[4] / ns, o.repeat);
    text += line;
  }
  write_file_atomic(o.csv, text);
  std::printf("wrote %s\n", o.csv.c_str());
  return 0;
}

}  // namespace sluice::app
