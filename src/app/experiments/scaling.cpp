#include "app/experiments/common.h"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace sluice::app::experiments {

// --- O(n): time per particle-step from 10k to 1M particles ----------------------------------------

void scaling(Context& c) {
  // A layer 0.5 m deep (50 rows at h = 0.01) widened to the particle count: the work per
  // particle (neighbours, pairs) stays the same. The solver's iterations still grow a
  // little with the width (the tolerance is on the average error), so each width also
  // runs with a fixed number of Jacobi iterations: then the work per particle-step is
  // exactly the same and any growth of its time is the implementation's.
  const std::vector<long> counts =
      c.quick ? std::vector<long>{2000, 8000} : std::vector<long>{10000, 30000, 100000, 300000, 1000000};
  constexpr int kFixedIterations = 6;
  const double start_load = load_average();
  io::CsvWriter csv(
      "particles,width,steps,avg_iterations,ms_per_step,us_per_particle_step,ratio_to_first,us_neighbors_per_particle,"
      "us_pressure_per_particle_iteration,fixed_iterations,us_per_particle_step_fixed_iterations,ratio_to_first_fixed_"
      "iterations");
  // Every width with and without fixed iterations, the runs of one round in a row and the
  // rounds repeated, so that a slow spell of a shared machine hits every width alike.
  // Small widths repeat their run within a round (the round's figure is the mean per
  // step over its repeats): 20 steps of 10k particles take tens of milliseconds.
  struct Width {
    double width;
    Scene scene, fixed;
    int repeat;
    std::vector<double> ms_natural, ms_fixed;
    SweepRun r, rf;
  };
  std::vector<Width> widths;
  for (long n : counts) {
    const double width = static_cast<double>(n) / 50.0 * 0.01;
    auto own = column_height(width, 0.5);
    own.insert(own.end(), {"time.dt=5e-4", "time.duration=0.01"});
    Scene scene = c.load("column.json", own);
    own.insert(own.end(), {"solver.min_iterations=" + std::to_string(kFixedIterations),
                           "solver.max_iterations=" + std::to_string(kFixedIterations)});
    Scene fixed = c.load("column.json", own);
    const int repeat = c.quick ? 1 : static_cast<int>(std::max(1L, 300000L / n));
    widths.push_back({width, std::move(scene), std::move(fixed), repeat, {}, {}, {}, {}});
  }
  const int rounds = c.quick ? 1 : 5;
  const int threads = omp_get_max_threads();
  for (int k = 0; k < rounds; ++k)
    for (Width& w : widths) {
      w.ms_natural.push_back(mean(interleaved_ms_per_step(w.scene, {threads}, w.repeat, &w.r)[0]));
      w.ms_fixed.push_back(mean(interleaved_ms_per_step(w.fixed, {threads}, w.repeat, &w.rf)[0]));
    }
  double first = 0, first_fixed = 0, lo = HUGE_VAL, hi = 0, lo_fixed = HUGE_VAL, hi_fixed = 0;
  for (const Width& w : widths) {
    const SweepRun &r = w.r, &rf = w.rf;
    const double np = static_cast<double>(r.particles);
    const double us = 1000.0 * median(w.ms_natural) / np, us_fixed = 1000.0 * median(w.ms_fixed) / np;
    if (first == 0) first = us, first_fixed = us_fixed;
    lo = std::min(lo, us), hi = std::max(hi, us);
    lo_fixed = std::min(lo_fixed, us_fixed), hi_fixed = std::max(hi_fixed, us_fixed);
    std::printf("  %8ld particles: %.4f us per particle-step (%.2f iterations), %.4f with %d fixed iterations\n",
                r.particles, us, r.avg_iterations, us_fixed, kFixedIterations);
    // The split of the last fixed-iteration run: the neighbour phase per particle, and the
    // pressure solve per particle and iteration.
    csv.row({std::to_string(r.particles), fmt(w.width, 5), std::to_string(r.steps), fmt(r.avg_iterations, 4),
             fmt(median(w.ms_natural), 5), fmt(us, 5), fmt(us / first, 4), fmt(1000.0 * rf.ms_phase[0] / np, 4),
             fmt(1000.0 * rf.ms_phase[2] / (np * kFixedIterations), 4), fmt(rf.avg_iterations, 4), fmt(us_fixed, 5),
             fmt(us_fixed / first_fixed, 4)});
  }
  csv.write(c.dir / "scaling.csv");
  c.md += "A layer 0.5 m deep widened from " + std::to_string(counts.front()) + " to " + std::to_string(counts.back()) +
          " particles, 20 steps of 0.5 ms, at the solver's tolerance and with " + std::to_string(kFixedIterations) +
          " fixed Jacobi iterations (the same work per particle at every width); " +
          (c.quick ? "1 round"
                   : "median of 5 rounds, each round running every width and variant in turn (widths under 300k "
                     "repeat their run 300k / n times within a round)") +
          ", " + std::to_string(omp_get_max_threads()) + " threads, load average " + fmt(start_load, 3) +
          " at the start. Target: the time per particle-step within 25 % over the range (O(n)). Measured: largest / "
          "smallest = " +
          fmt(hi / lo, 3) + " at the tolerance (iterations grow with the width), " + fmt(hi_fixed / lo_fixed, 3) +
          " with fixed iterations.\n\n";
  c.table(c.dir / "scaling.csv", {});
  FigureSpec a = spec(FigureKind::Series, c.dir / "scaling.csv", "particles",
                      {"us_per_particle_step", "us_per_particle_step_fixed_iterations", "us_neighbors_per_particle",
                       "us_pressure_per_particle_iteration"},
                      "scaling.png");
  a.ylabel = "wall time [µs]";
  a.style = "linespoints";
  a.logx = true;
  c.figure(
      a,
      "Wall time per particle-step against particle count (flat = O(n)), at the tolerance and with fixed iterations");
}

}  // namespace sluice::app::experiments
