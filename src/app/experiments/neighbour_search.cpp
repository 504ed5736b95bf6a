#include "app/experiments/common.h"

#include <cstdio>

namespace sluice::app::experiments {

// --- Figure 14: naive against hashed neighbour search ----------------------------------------------

void neighbour_search(Context& c) {
  const std::vector<long> counts =
      c.quick ? std::vector<long>{200, 400} : std::vector<long>{500, 1000, 2000, 4000, 8000, 12000};
  const double start_load = load_average();
  io::CsvWriter csv("particles,method,ms_neighbors");
  for (long n : counts) {
    // 50 particles per row at h = 0.01 in a 0.5 m wide column.
    auto own = column_height(0.5, static_cast<double>(n) / 50.0 * 0.01);
    own.insert(own.end(), {"time.dt=5e-4", "time.duration=0.0025"});
    const Scene scene = c.load("column.json", own);
    for (bool brute : {true, false}) {
      const SweepRun r = analysis::run_sweep_point(scene, {}, {}, brute);
      std::printf("  %6ld particles %-8s %9.3f ms per neighbour search\n", r.particles, brute ? "naive" : "hashing",
                  r.ms_phase[0]);
      csv.row({std::to_string(r.particles), brute ? "naive" : "hashing", fmt(r.ms_phase[0], 5)});
    }
  }
  csv.write(c.dir / "neighbour_search.csv");
  c.md +=
      "Columns of growing height, 5 steps each, the neighbour phase's mean wall time per step (fluid-fluid, "
      "fluid-boundary and boundary-fluid lists). Load average " +
      fmt(start_load, 3) +
      " at the start. Compare with the thesis' Figure 14: the naive search grows quadratically, hashing linearly.\n\n";
  c.table(c.dir / "neighbour_search.csv", {});
  FigureSpec a =
      spec(FigureKind::Series, c.dir / "neighbour_search.csv", "particles", {"ms_neighbors"}, "neighbour_search.png");
  a.group = "method";
  a.style = "linespoints";
  c.figure(
      a,
      "Neighbour search time per step against particle count, naive O(n^2) against spatial hashing (thesis Figure 14)");
}

}  // namespace sluice::app::experiments
