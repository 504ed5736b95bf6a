// Physics of the simulation (src/solver/simulation.cpp) on small scenes built from inline
// JSON: rest density, boundary volumes, a block at rest, hydrostatic pressure for every
// solver and boundary method, IISPH convergence and containment in a dam break,
// determinism, frame landing, the instability detector, brute force vs grid search.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "analysis/validation.h"
#include "scene/scene.h"
#include "solver/probe.h"
#include "solver/simulation.h"
#include "test_util.h"

namespace sluice {
namespace {

using test::scene_from_json;

constexpr double kPi = 3.14159265358979323846;

double max_speed(const Simulation& sim) {
  double v = 0.0;
  for (const Vec2& u : sim.fluid().v) v = std::max(v, u.norm());
  return v;
}

// --- rest density ------------------------------------------------------------------

TEST(Physics, RestDensityOnFilledLattice) {
  const Scene scene = scene_from_json(R"({
    "spacing": 0.02,
    "solver": {"gravity": [0, 0], "rest_density": 1000},
    "fluid": [{"shape": "rectangle", "min": [0.1, -0.3], "max": [0.7, 0.3]}]
  })");
  Simulation sim(scene);
  sim.recompute_density();
  const double h = scene.spacing, rho0 = 1000.0;
  int interior = 0;
  const FluidParticles& f = sim.fluid();
  for (Index i = 0; i < f.size(); ++i) {
    const Vec2 x = f.x[i];
    const double edge = std::min({x.x() - 0.1, 0.7 - x.x(), x.y() + 0.3, 0.3 - x.y()});
    if (edge <= 2.0 * h) continue;
    ++interior;
    // m = rho0 / lattice sum makes a full neighbourhood exactly rho0; what remains is
    // round-off of a 13-term sum and of lattice positions (~1e-15); 1e-9 would still
    // catch m = rho0 h^2 (8.6e-4 off) by many orders.
    EXPECT_NEAR(f.rho[i] / rho0, 1.0, 1e-9) << "particle " << f.id[i];
  }
  EXPECT_EQ(interior, 26 * 26);  // 30 x 30 lattice minus the two rows within 2h of each side
  // Surface particles see fewer neighbours: below rest density.
  for (Index i = 0; i < f.size(); ++i)
    if (std::abs(f.x[i].x() - 0.11) < 1e-9) {
      EXPECT_LT(f.rho[i], 0.99 * rho0);
    }
  EXPECT_NEAR(sim.fluid_mass() * lattice_kernel_sum(sim.kernel(), h), rho0, 1e-9 * rho0);
}

// --- Akinci boundary volume -------------------------------------------------------------

// Volumes of the samples of a long straight wall far from its ends (more than 2h).
std::vector<double> interior_wall_volumes(int layers, double gamma1, double h) {
  const std::string text = R"({"spacing": )" + std::to_string(h) + R"(, "solver": {"gamma1": )" +
                           std::to_string(gamma1) +
                           R"(}, "fluid": [{"shape": "rectangle", "min": [0.5, 0.5], "max": [0.6, 0.6]}],
      "boundaries": [{"shape": "polyline", "points": [[0, 0], [2, 0]], "layers": )" +
                           std::to_string(layers) + "}]}";
  const Scene scene = scene_from_json(text);
  Simulation sim(scene);
  const BoundaryParticles& b = sim.boundary();
  std::vector<double> v;
  for (Index k = 0; k < b.size(); ++k)
    if (b.x[k].x() > 3 * h && b.x[k].x() < 2.0 - 3 * h) v.push_back(b.volume[k]);
  return v;
}

TEST(Physics, AkinciVolumeStraightWall) {
  const double h = 0.02, gamma1 = 0.7;
  const double alpha = 5.0 / (14.0 * kPi * h * h);
  // One row at spacing h: self 4 alpha + two neighbours at h (alpha each); 2h is outside.
  const double sum1 = 6.0 * alpha;
  // Two rows h apart: add the sample across (alpha) and two diagonals at sqrt(2) h.
  const double sum2 = sum1 + alpha * (1.0 + 2.0 * std::pow(2.0 - std::sqrt(2.0), 3));
  EXPECT_NEAR(1.0 / (sum1 * h * h), 1.4661, 1e-4);  // the documented numbers, 4 digits
  EXPECT_NEAR(1.0 / (sum2 * h * h), 1.1884, 1e-4);
  for (int layers : {1, 2}) {
    SCOPED_TRACE(layers);
    const std::vector<double> v = interior_wall_volumes(layers, gamma1, h);
    ASSERT_GT(v.size(), 90u * layers);
    const double expected = gamma1 / (layers == 1 ? sum1 : sum2);
    // Samples of a straight wall are uniform up to round-off of their positions
    // (segment length / n): 1e-9 relative is far tighter than the 4 digits asked for.
    for (double vb : v) EXPECT_NEAR(vb / expected, 1.0, 1e-9);
  }
}

// --- block at rest -------------------------------------------------------------------------

TEST(Physics, BlockAtRestStaysAtRest) {
  const Scene scene = scene_from_json(R"({
    "spacing": 0.02,
    "solver": {"gravity": [0, 0]},
    "time": {"dt": 1e-3, "duration": 1},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 0.3]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.4, 0.5]}]
  })");
  ASSERT_EQ(scene.fluid_removed, 0);
  ASSERT_EQ(scene.solver.gamma1, 0.84);  // the default under test
  Simulation sim(scene);
  double vmax = 0.0;
  for (int s = 0; s < 50; ++s) {
    sim.step();
    vmax = std::max(vmax, max_speed(sim));
  }
  std::printf("[ measured ] block at rest: max speed over 50 steps %.3e m/s\n", vmax);
  // Measured 2.8e-14 m/s (round-off). An inconsistent start moves the block within the
  // 50 steps: m = rho0 h^2 0.11 m/s, gamma1 = 1 3.3 m/s, wall layer on the curve
  // (surface_offset 0) 30 m/s; 1e-6 sits far between.
  EXPECT_LT(vmax, 1e-6);
}

// The same block on wider supports: the walls' volumes keep the thesis' kernel (gamma1's
// calibration) in units of the fluid's m / rho0, and the samples' wall share follows the
// support, so the block starts at rest density next to the walls and stays still.
// Measured: 2e-14 m/s on 3 spacings, 1.6e-5 on 4. Before, on 3 spacings, the fluid row
// next to a wall started 5.5 % compressed and a dam break blew up in its first step. (On
// 2.5 spacings the block moves at 0.01 m/s: the side walls' samples, 0.0196 m apart to fit
// the wall's length, do not continue the fluid's lattice, and a row two spacings from
// the wall reads up to 0.045 % above rest density.)
TEST(Physics, BlockAtRestStaysAtRestOnWiderSupports) {
  for (const char* support : {"3", "4"}) {
    for (const char* kernel : {"cubic_spline", "wendland_c2"}) {
      SCOPED_TRACE(std::string(kernel) + " on " + support + " spacings");
      const Scene scene = scene_from_json(std::string(R"({
        "spacing": 0.02,
        "solver": {"gravity": [0, 0], "support": )") +
                                          support + R"(, "kernel": ")" + kernel + R"("},
        "time": {"dt": 1e-3, "duration": 1},
        "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 0.3]}],
        "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.4, 0.5]}]
      })");
      Simulation sim(scene);
      double vmax = 0.0;
      for (int s = 0; s < 50; ++s) {
        sim.step();
        vmax = std::max(vmax, max_speed(sim));
      }
      std::printf("[ measured ] block at rest, %s on %s spacings: max speed over 50 steps %.3e m/s\n", kernel, support,
                  vmax);
      EXPECT_LT(vmax, 1e-4);
    }
  }
}

// --- walls: free slip and no slip ------------------------------------------------------------

// A layer sliding along the floor without gravity, 0.2 s at 0.5 m/s (100 steps). Against a
// free-slip wall (the default) the artificial viscosity acts only on the velocity normal to
// the wall, so nothing but the fluid's own forces moves its x-momentum; a no-slip wall slows
// it through its viscosity. Until 2026-12-05 the artificial viscosity acted on the whole
// relative velocity against walls, a friction: the same layer lost 0.41 % of its momentum.
TEST(Physics, FreeSlipWallLetsALayerSlideAndANoSlipWallSlowsIt) {
  auto momentum_kept = [](const std::string& wall) {
    const Scene scene = scene_from_json(R"({
      "spacing": 0.01,
      "solver": {"gravity": [0, 0]},
      "time": {"dt": 2e-3, "duration": 0.2},
      "fluid": [{"shape": "rectangle", "min": [0.5, 0], "max": [1.0, 0.1], "velocity": [0.5, 0]}],
      "boundaries": [{"shape": "box", "min": [0, 0], "max": [2.0, 0.3])" +
                                        wall + R"(}]
    })");
    Simulation sim(scene);
    auto px = [&] {
      double p = 0.0;
      for (const Vec2& v : sim.fluid().v) p += v.x();
      return p;
    };
    const double p0 = px();
    for (int s = 0; s < 100; ++s) sim.step();
    return px() / p0;
  };
  const double free_slip = momentum_kept("");
  const double no_slip = momentum_kept(R"(, "wall": "no_slip", "wall_viscosity": 1e-3)");
  std::printf("[ measured ] x-momentum kept after 0.2 s: free slip %.6f, no slip (1e-3 m^2/s) %.6f\n", free_slip,
              no_slip);
  EXPECT_NEAR(free_slip, 1.0, 1e-3);
  EXPECT_LT(no_slip, free_slip - 0.01);
}

// --- hydrostatic column ---------------------------------------------------------------------

// scenes/validation/hydrostatic.json: box [0,0]-[0.4,0.6] without a lid, water
// [0,0]-[0.4,0.5], h = 0.02 (500 particles), viscosity 0.01, settled for 0.5 s, 2 s.
// The pressure is averaged per depth bin over every step of the last 0.5 s (see
// analysis/validation.h); the cases and their tolerances (with the measurements they
// come from) are analysis::hydrostatic_cases(), which `sluice validate hydrostatic` prints.
class Hydrostatic : public ::testing::TestWithParam<analysis::HydrostaticCase> {};

TEST_P(Hydrostatic, PressureMatchesDepth) {
  const analysis::HydrostaticCase& c = GetParam();
  const Scene scene = load_scene(std::string(SLUICE_SOURCE_DIR) + "/scenes/validation/hydrostatic.json", c.set);
  const auto r = analysis::run_hydrostatic(scene, 0.4, 1.5, c.zero_pressure_wall);
  if (std::getenv("SLUICE_TEST_VERBOSE"))
    for (const auto& b : r.bins) std::printf("  d = %.3f  <p>/(rho0 g d) = %.4f\n", b.depth, b.ratio);
  std::printf(
      "[ measured ] hydrostatic %s: %ld steps (%ld at max_iterations), surface %.4f m, end max speed "
      "%.3e m/s, worst bin error %.4f at d = %.3f m, slope error %.4f, floor bin ratio %.3f\n",
      c.name.c_str(), r.steps, r.capped, r.surface, r.max_speed_end, r.worst_bin_error, r.worst_depth, r.slope_error,
      r.floor_ratio);
  ASSERT_GE(r.bins.size(), 10u);
  EXPECT_LT(r.worst_bin_error, c.bin_tolerance);
  EXPECT_LT(r.slope_error, c.slope_tolerance);
  EXPECT_GT(r.surface, 0.48);  // the column neither collapses nor boils: the surface stays within h
  EXPECT_LT(r.surface, 0.52);
  if (c.zero_pressure_wall) {
    EXPECT_GT(r.floor_ratio, 1.3);  // the documented drawback of p_b = 0 (measured 1.74-1.75)
  }
}

// The known limits fail their bounds: `sluice validate hydrostatic` lists them as failing.
std::vector<analysis::HydrostaticCase> holding_hydrostatic_cases() {
  std::vector<analysis::HydrostaticCase> cases;
  for (const auto& c : analysis::hydrostatic_cases())
    if (!c.known_limit) cases.push_back(c);
  return cases;
}

INSTANTIATE_TEST_SUITE_P(Physics, Hydrostatic, ::testing::ValuesIn(holding_hydrostatic_cases()),
                         [](const ::testing::TestParamInfo<analysis::HydrostaticCase>& param_info) {
                           return param_info.param.name;
                         });

// --- dam break: IISPH convergence and containment --------------------------------------------

// Tank 2 x 2 m without a lid, water column 0.5 x 1 m, h = 0.02 (1250 particles), 0.4 s
// with the adaptive CFL step. Run once, shared by the tests below.
struct DamBreakRun {
  Scene scene;
  std::vector<StepStats> stats;
  long escapes = 0;          // particle-steps outside the tank (margin h/2)
  std::string first_escape;  // description of the first one
};

const DamBreakRun& dam_break() {
  static const DamBreakRun run = [] {
    DamBreakRun r;
    r.scene = scene_from_json(R"({
      "spacing": 0.02,
      "time": {"duration": 0.4},
      "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.5, 1]}],
      "boundaries": [{"shape": "box", "min": [0, 0], "max": [2, 2]}]
    })");
    Simulation sim(r.scene);
    const double m = 0.5 * r.scene.spacing;
    while (!sim.finished()) {
      r.stats.push_back(sim.step());
      const FluidParticles& f = sim.fluid();
      for (Index i = 0; i < f.size(); ++i) {
        const Vec2 x = f.x[i];
        if (x.x() < -m || x.x() > 2.0 + m || x.y() < -m) {
          if (r.escapes++ == 0) {
            r.first_escape = "particle " + std::to_string(f.id[i]) + " at (" + std::to_string(x.x()) + ", " +
                             std::to_string(x.y()) + ") at t = " + std::to_string(sim.time());
          }
        }
      }
    }
    return r;
  }();
  return run;
}

TEST(Physics, DamBreakIisphMeetsTolerance) {
  const DamBreakRun& r = dam_break();
  const SolverSettings& s = r.scene.solver;
  ASSERT_GT(r.stats.size(), 300u);  // 0.4 s at dt <= 1e-3 (plus frame landings)
  long capped = 0;
  int max_iter = 0;
  double worst = 0.0;
  for (const StepStats& st : r.stats) {
    max_iter = std::max(max_iter, st.iterations);
    EXPECT_GE(st.iterations, s.min_iterations);
    if (st.iterations >= s.max_iterations) {
      ++capped;
      continue;
    }
    worst = std::max(worst, st.avg_error_percent);
  }
  // The compression the positions really reach (Eq. 15 at the next step's start), not the
  // solver's own prediction (Eq. 23, which the loop's exit condition bounds): it tests the
  // source term and the operator, and what a user sees.
  double realized = 0, realized_max = 0;
  for (size_t k = 1; k < r.stats.size(); ++k) {
    realized += r.stats[k].density_error_percent;
    realized_max = std::max(realized_max, r.stats[k].density_error_percent);
  }
  realized /= static_cast<double>(r.stats.size() - 1);
  std::printf(
      "[ measured ] dam break: %zu steps, max iterations %d, steps at max_iterations %ld, worst predicted %.4f%%, "
      "realized average %.4f%%, largest %.4f%%\n",
      r.stats.size(), max_iter, capped, worst, realized, realized_max);
  EXPECT_EQ(capped, 0);
  EXPECT_LE(realized, s.tolerance_percent);
  EXPECT_LE(realized_max, 2 * s.tolerance_percent);
}

// solver.pressure_solver = chebyshev: in a 4 m column (h = 0.02, 200 rows) at dt = 1 ms,
// the same tolerance in far fewer iterations than the thesis' relaxed Jacobi, at the same
// realized compression (Eq. 15 at each step's start). 200 rows: Jacobi's iterations grow
// with the rows, Chebyshev's about with their square root (docs/performance.md).
TEST(Physics, ChebyshevSolvesADeepColumnInFewerIterations) {
  const char* column = R"({"spacing": 0.02,
    "time": {"duration": 0.5, "fps": 10, "dt": 1e-3},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 4]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.4, 4.2], "lid": false}]})";
  auto run = [&](const std::string& solver, double& realized) {
    Simulation sim(scene_from_json(column, {"solver.pressure_solver=" + solver}));
    const test::RunAverages r = test::run_to_end(sim);
    realized = r.largest_compression;
    return r.iterations;
  };
  double jacobi_error = 0, chebyshev_error = 0;
  const double jacobi = run("jacobi", jacobi_error), chebyshev = run("chebyshev", chebyshev_error);
  std::printf("[ measured ] 4 m column: iterations Jacobi %.2f, Chebyshev %.2f; largest compression %.4f%%, %.4f%%\n",
              jacobi, chebyshev, jacobi_error, chebyshev_error);
  EXPECT_LT(chebyshev, 0.6 * jacobi);
  EXPECT_LT(chebyshev_error, 2 * jacobi_error);
}

TEST(Physics, DamBreakStaysInTank) {
  const DamBreakRun& r = dam_break();
  // Walls at x = 0, x = 2 and y = 0; the fluid keeps h/2 off them, so crossing a wall
  // by more than h/2 means a particle went through the boundary.
  EXPECT_EQ(r.escapes, 0) << "first: " << r.first_escape;
}

// --- determinism -------------------------------------------------------------------------

// 2400 particles (h = 0.01), more than two reduction blocks of 1024, so that thread
// counts really split the work; 40 steps cross two spatial reorders (every 16 steps).
std::uint64_t run_hash(const std::string& solver, double dt, int threads, int steps) {
  test::ThreadCount t(threads);
  const Scene scene = scene_from_json(R"({
    "spacing": 0.01,
    "solver": {)" + solver + R"(},
    "time": {"dt": )" + std::to_string(dt) +
                                      R"(, "duration": 1},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.8]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.8, 1.0]}]
  })");
  Simulation sim(scene);
  for (int s = 0; s < steps; ++s) sim.step();
  EXPECT_GT(max_speed(sim), 0.01);  // the column is moving: not a trivially static state
  return test::state_hash(sim);
}

struct DeterminismCase {
  std::string name, solver;
  double dt;
  int steps;
};

std::ostream& operator<<(std::ostream& os, const DeterminismCase& c) { return os << c.name; }

class Determinism : public ::testing::TestWithParam<DeterminismCase> {};

TEST_P(Determinism, SameBitsForThreadsAndRuns) {
  const DeterminismCase& c = GetParam();
  const std::uint64_t a = run_hash(c.solver, c.dt, 1, c.steps);
  const std::uint64_t b = run_hash(c.solver, c.dt, 2, c.steps);
  const std::uint64_t b2 = run_hash(c.solver, c.dt, 2, c.steps);
  const std::uint64_t d = run_hash(c.solver, c.dt, 3, c.steps);
  EXPECT_EQ(a, b) << "1 vs 2 threads";
  EXPECT_EQ(b, b2) << "two runs with 2 threads";
  EXPECT_EQ(a, d) << "1 vs 3 threads";
}

INSTANTIATE_TEST_SUITE_P(
    Physics, Determinism,
    ::testing::Values(
        DeterminismCase{"iisph", R"("type": "iisph")", 2e-3, 40},
        DeterminismCase{"iisph_multilevel", R"("type": "iisph", "pressure_solver": "multilevel")", 2e-3, 40},
        DeterminismCase{"iisph_viscosity_mirroring",
                        R"("type": "iisph", "viscosity": 0.01, "boundary_pressure": "mirroring")", 2e-3, 40},
        DeterminismCase{"wcsph", R"("type": "wcsph", "stiffness": 5e5)", 1.5e-4, 60},
        DeterminismCase{"wcsph_viscosity", R"("type": "wcsph", "stiffness": 5e5, "viscosity": 0.01)", 1.5e-4, 60}),
    [](const ::testing::TestParamInfo<DeterminismCase>& param_info) { return param_info.param.name; });

// The fused Jacobi sweep (Simulation::jacobi_sweep) gives the bits of the two plain
// passes (block size -1) for any blocks and ranges: one block holding every particle,
// blocks of 64 particles (most updates wait for a later block or are deferred), blocks
// of 1024, the automatic choice, and 2, 3 or 7 ranges (more ranges than threads: a
// thread sweeps several); each boundary method reads accelerations differently.
TEST(Physics, JacobiSweepBlocksDoNotChangeBits) {
  struct Sweep {
    Index block, ranges;
  };
  for (const char* method : {"solved", "extrapolation", "mirroring", "zero"}) {
    const Scene scene = scene_from_json(R"({
      "spacing": 0.01,
      "solver": {"type": "iisph", "boundary_pressure": ")" +
                                        std::string(method) + R"("},
      "time": {"dt": 2e-3, "duration": 1},
      "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.8]}],
      "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.8, 1.0]}]
    })");
    const Sweep sweeps[] = {{-1, 0}, {Index(1) << 30, 1}, {64, 1}, {64, 3}, {1024, 2}, {1024, 7}, {0, 0}};
    std::vector<std::uint64_t> hashes;
    for (const Sweep& sweep : sweeps) {
      Simulation sim(scene);
      SolverProbe(sim).set_jacobi_sweep(sweep.block, sweep.ranges);
      int iterations = 0;
      for (int s = 0; s < 30; ++s) iterations += sim.step().iterations;
      EXPECT_GT(iterations, 30) << method;  // the solver iterated: the sweep ran more than once per step
      EXPECT_GT(max_speed(sim), 0.01) << method;
      hashes.push_back(test::state_hash(sim));
    }
    for (size_t k = 1; k < hashes.size(); ++k)
      EXPECT_EQ(hashes[0], hashes[k]) << method << ", block " << sweeps[k].block << ", ranges " << sweeps[k].ranges;
  }
}

// --- frame landing -----------------------------------------------------------------------

const char* kSmallDamBreak = R"({
  "spacing": 0.02,
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.2, 0.4]}],
  "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.6, 0.6]}]
})";

TEST(Physics, FixedStepLandsOnFrames) {
  const Scene scene = scene_from_json(kSmallDamBreak, {"time.fps=30", "time.dt=0.0007", "time.duration=0.25"});
  Simulation sim(scene);
  EXPECT_EQ(sim.frame_count(), 8);  // ceil(0.25 * 30)
  Index expected_frame = 1;
  double prev = 0.0, longest = 0.0;
  long steps = 0;
  while (!sim.finished()) {
    const StepStats st = sim.step();
    ++steps;
    longest = std::max(longest, st.dt);
    EXPECT_LE(st.dt, 0.0007) << "step " << st.step;  // steps are only ever shortened
    EXPECT_GT(st.time, prev);
    EXPECT_EQ(st.time, sim.time());
    prev = st.time;
    if (st.frame >= 0) {
      ASSERT_EQ(st.frame, expected_frame);
      // Frame times are exact: k / fps, not an accumulated sum of steps. The last frame
      // is cut at the duration.
      const double t = std::min(static_cast<double>(st.frame) / 30.0, 0.25);
      EXPECT_EQ(st.time, t) << "frame " << st.frame;
      EXPECT_EQ(sim.frame(), st.frame);
      ++expected_frame;
    } else {
      EXPECT_LT(st.time, static_cast<double>(expected_frame) / 30.0);
    }
  }
  EXPECT_EQ(expected_frame, 9);
  EXPECT_EQ(sim.time(), 0.25);
  // 1/30 s / 0.0007 s = 47.6, so 48 steps of 0.000694 s per frame; 0.25 s is 7.5 frames.
  EXPECT_EQ(steps, 7 * 48 + 24);
  std::printf("[ measured ] fixed dt frames: %ld steps, longest %.10g s\n", steps, longest);
}

TEST(Physics, AdaptiveStepLandsOnFrames) {
  const Scene scene = scene_from_json(kSmallDamBreak, {"time.fps=30", "time.duration=0.3", "time.dt_max=0.004"});
  ASSERT_EQ(scene.time.dt, 0.0);
  Simulation sim(scene);
  Index expected_frame = 1;
  double longest = 0.0, shortest = INFINITY;
  while (!sim.finished()) {
    const StepStats st = sim.step();
    longest = std::max(longest, st.dt);
    shortest = std::min(shortest, st.dt);
    EXPECT_LE(st.dt, 0.004) << "step " << st.step;
    // The CFL condition of Eq. 14 with the velocities after the step may exceed lambda by
    // what one step's acceleration adds; 2 lambda bounds it generously.
    EXPECT_LE(st.max_cfl, 2 * 0.4) << "step " << st.step;
    if (st.frame >= 0) {
      ASSERT_EQ(st.frame, expected_frame);
      EXPECT_EQ(st.time, static_cast<double>(st.frame) / 30.0);
      ++expected_frame;
    }
  }
  EXPECT_EQ(expected_frame, 10);
  std::printf("[ measured ] adaptive frames: dt in [%.4g, %.4g] s\n", shortest, longest);
  EXPECT_LT(shortest, longest);  // the step did adapt to the flow
}

// The ambient-pressure limit of the adaptive step (kHydrostaticCfl): a 2 m column at rest
// whose Eq. 14 (v = 0) and dt_max would allow 10 ms steps, 2.2 times the h / sqrt(g H) past
// which a column boils from the bottom (docs/performance.md, "The stable step of a deep
// fluid"). With the limit the steps stay near 0.6 h / sqrt(g H) and the column stays still.
TEST(Physics, DeepColumnStepKeepsToTheAmbientPressureLimit) {
  const double h = 0.02, height = 2.0, g = 9.81;
  const Scene scene = scene_from_json(R"({"spacing": 0.02,
    "time": {"duration": 0.6, "fps": 10, "cfl": 1.0, "dt_max": 0.01},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.5, 2]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.5, 2.5], "lid": false}]})");
  Simulation sim(scene);
  // H is the extent of the particles' centres (2 m less a spacing), less what the column
  // settles by: 5 % covers both.
  const double limit = kHydrostaticCfl * h / std::sqrt(g * 0.95 * height);
  double longest = 0.0, kinetic = 0.0;
  try {
    while (!sim.finished()) {
      const StepStats st = sim.step();
      longest = std::max(longest, st.dt);
      kinetic = st.kinetic_energy;
    }
  } catch (const SimulationUnstable& e) {
    FAIL() << e.what();  // without the limit: 10 ms steps, stopped at t = 0.24 s
  }
  std::printf(
      "[ measured ] 2 m column, adaptive step: longest %.4g s (limit %.4g s), kinetic energy at 0.6 s %.4g J/m\n",
      longest, limit, kinetic);
  EXPECT_LE(longest, limit);
  // 1000 kg/m of fluid. Fixed steps of 1 ms end at 3.6 J/m (the lattice settling), of 4 ms
  // (0.89 h / sqrt(g H)) at 15.9 J/m, boiling.
  EXPECT_LT(kinetic, 8.0);
}

// --- instability detector ------------------------------------------------------------------

TEST(Physics, InstabilityIsDetected) {
  // A WCSPH fluid far too soft for its column (c = 1 m/s): it compresses past the
  // detector's 50 % limit. (A step beyond the acoustic limit is refused at load.)
  const Scene scene = scene_from_json(kSmallDamBreak, {"solver.type=wcsph", "solver.stiffness=1e3", "time.dt=5e-3"});
  Simulation sim(scene);
  std::string message;
  int steps = 0;
  try {
    for (; steps < 200; ++steps) sim.step();
  } catch (const SimulationUnstable& e) {
    message = e.what();
  }
  std::printf("[ measured ] instability after %d steps: %s\n", steps, message.c_str());
  ASSERT_FALSE(message.empty()) << "no SimulationUnstable in 200 steps";
  EXPECT_NE(message.find("unstable at step"), std::string::npos) << message;
  const bool has_cause =
      message.find("non-finite") != std::string::npos || message.find("left the scene") != std::string::npos ||
      message.find("compression error") != std::string::npos || message.find("past a wall") != std::string::npos ||
      message.find("dt_min") != std::string::npos;
  EXPECT_TRUE(has_cause) << message;
}

// A deep column at a step far above h / sqrt(g H) (docs/performance.md, "The stable step
// of a deep fluid"): the solver meets its tolerance and no particle leaves the bounds or
// enters a wall, but the column heats up. The energy and speed tests stop it, each on its
// own (both at t = 0.233 s); without them it runs to its end at 0.25 s. (Since the walls
// are free-slip, nothing damps its sliding along them, and at 0.267 s a particle leaves
// the bounds, which the bounds test then reports; until then it ran to 0.3 s.)
std::vector<std::string> hot_column(const std::string& limits) {
  return {"spacing=0.01",
          "time.dt=3.2e-3",
          "fluid.0.max=[0.5,2]",
          "boundaries.0.max=[0.5,5]",
          "time.duration=0.25",
          "solver.pressure_solver=jacobi",
          limits};
}

std::string unstable_message(const std::vector<std::string>& overrides) {
  Simulation sim(load_scene(SLUICE_SOURCE_DIR "/scenes/column.json", overrides));
  try {
    while (!sim.finished()) sim.step();
  } catch (const SimulationUnstable& e) {
    return e.what();
  }
  return "";
}

TEST(Physics, ABlowUpInsideTheBoundsIsStoppedByItsEnergy) {
  const std::string message = unstable_message(hot_column("stability.max_speed_ratio=1000"));
  std::printf("[ measured ] %s\n", message.c_str());
  EXPECT_NE(message.find("mechanical energy rose by"), std::string::npos) << message;
  EXPECT_NE(message.find("stability.max_energy_gain = 0.1"), std::string::npos) << message;
}

TEST(Physics, ABlowUpInsideTheBoundsIsStoppedByItsSpeed) {
  const std::string message = unstable_message(hot_column("stability.max_energy_gain=10"));
  std::printf("[ measured ] %s\n", message.c_str());
  EXPECT_NE(message.find("fastest fluid particle moves at"), std::string::npos) << message;
  EXPECT_NE(message.find("stability.max_speed_ratio = 3"), std::string::npos) << message;
}

TEST(Physics, ABlowUpInsideTheBoundsRunsToItsEndWithoutTheseTests) {
  std::vector<std::string> relaxed = hot_column("stability.max_energy_gain=10");
  relaxed.push_back("stability.max_speed_ratio=1000");
  EXPECT_EQ(unstable_message(relaxed), "");
}

// --- brute force vs grid -------------------------------------------------------------------

TEST(Physics, BruteForceMatchesGrid) {
  const Scene scene = scene_from_json(kSmallDamBreak, {"time.dt=0.002"});
  Simulation grid(scene), brute(scene);
  brute.set_brute_force_neighbors(true);
  for (int s = 0; s < 40; ++s) {
    grid.step();
    brute.step();
  }
  ASSERT_GT(max_speed(grid), 0.05);
  const test::OrderedState a = test::ordered_state(grid), b = test::ordered_state(brute);
  double dx = 0.0, dv = 0.0, dp = 0.0, pmax = 0.0;
  for (size_t i = 0; i < a.x.size(); ++i) {
    dx = std::max(dx, (a.x[i] - b.x[i]).norm());
    dv = std::max(dv, (a.v[i] - b.v[i]).norm());
    dp = std::max(dp, std::abs(a.p[i] - b.p[i]));
    pmax = std::max(pmax, std::abs(a.p[i]));
  }
  std::printf(
      "[ measured ] brute vs grid after 40 steps: max |dx| %.3e m, |dv| %.3e m/s, |dp| %.3e (max p %.3e), "
      "bitwise %s\n",
      dx, dv, dp, pmax, test::state_hash(grid) == test::state_hash(brute) ? "equal" : "different");
  // Not bitwise: the brute-force lists are sorted by index, the grid's are in cell
  // order, so every neighbour sum is added in a different order. Measured after 40 steps:
  // |dx| 2.9e-16 m, |dv| 3.9e-14 m/s, |dp| 1.6e-9 of p up to 2e3 (8e-13 relative). The
  // bounds leave ~1000x for growth of round-off; a missing or extra neighbour (W ~ 1e2
  // near q = 1.9) would change a pressure by far more than 1e-9 relative.
  EXPECT_LT(dx, 1e-12);
  EXPECT_LT(dv, 1e-10);
  EXPECT_LT(dp, 1e-9 * pmax);
}

}  // namespace
}  // namespace sluice
