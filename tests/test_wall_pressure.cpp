// Issue 37, item 2: the pressure at the floor of the shipped tank (scenes/hydrostatic.json)
// under pressure boundaries (solver.boundary_pressure = solved, Band et al. 2018), swept
// over the solve's tolerance with each solver. docs/performance.md ("Pressure at the
// floor", 2026-12-04) has the measurements and the diagnosis.
//
// What the solve converges is the floor's whole load: the walls' pressure force on the
// fluid (the boundary part of Eq. 24 summed over the fluid) equals the fluid's weight at
// every tolerance. How that load is split between the floor samples' p_b and the bottom
// fluid row's p_i it does not converge: the samples add one unknown per lattice column that
// the fluid's forces do not see (with Eq. 24's sum form, a row's own pressure exerts no
// force on it), so an alternating pattern through the samples and the rows above them is a
// (near-)null mode of the PPE. The bottom row is therefore printed, not bounded. The mode
// has opposite signs in the first sample layer (y = -h/2) and the bottom row (y = h/2), so
// their mean, the pressure at the floor line y = 0, is determined, and it is bounded.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "analysis/validation.h"
#include "scene/scene.h"
#include "solver/probe.h"
#include "solver/simulation.h"

namespace sluice {
namespace {

const std::string kTank = std::string(SLUICE_SOURCE_DIR) + "/scenes/hydrostatic.json";
constexpr double kTankWidth = 0.4;

// The columns the tank's measures read: more than 3 h from its side walls.
bool away_from_side_walls(const Vec2& x, double h) { return x.x() >= 3 * h && x.x() <= kTankWidth - 3 * h; }

// The fluid's highest particle [m].
double top_of(const FluidParticles& f) {
  double top = -std::numeric_limits<double>::infinity();
  for (const Vec2& x : f.x) top = std::max(top, x.y());
  return top;
}

struct FloorResult {
  double load_ratio = 0;           // walls' vertical pressure force / the fluid's weight, averaged
  double bottom_row = 0;           // <p> / (rho0 g d) of the particles within h of the floor, as validate
  double lower_half = 0;           // the same over the bins at least half the depth down, as validate
  double samples = 0;              // <p_b> / (rho0 g d_b) of the floor's first sample layer
  double floor_line = 0;           // (bottom_row + samples) / 2: the pressure at y = 0
  std::vector<double> rows;        // <p> / (rho0 g d) of the first four fluid rows
  double median_speed = 0;         // at the end [m/s]
  double iterations_per_step = 0;  // over the whole run
};

// The shipped tank with `set`: analysis::run_hydrostatic's run and averages (bottom row,
// lower half, median speed; the particles more than 3 h from the side walls), and, over
// the same last 0.5 s, the walls' load, the floor's first sample layer and rows 1-4.
FloorResult measure_floor(const std::vector<std::string>& set) {
  const Scene scene = load_scene(kTank, set);
  const double h = scene.spacing, rho0 = scene.solver.rest_density, g = scene.solver.gravity.norm();
  const double from = scene.time.duration - 0.5;
  double load = 0, sample_p = 0, sample_d = 0, iterations = 0;
  std::vector<double> row_p(4, 0.0), row_d(4, 0.0);
  long steps = 0, measured = 0;
  const auto observe = [&](Simulation& sim, const StepStats& st) {
    ++steps;
    iterations += st.iterations;
    if (st.time < from) return;
    ++measured;
    const double weight = sim.fluid_mass() * static_cast<double>(sim.fluid().size()) * g;
    load += SolverProbe(sim).boundary_pressure_force().y() / weight;
    const FluidParticles& f = sim.fluid();
    const double surface = top_of(f) + 0.5 * h;  // as in run_hydrostatic
    for (Index i = 0; i < f.size(); ++i) {
      const Vec2 x = f.x[i];
      const auto row = static_cast<std::size_t>(std::max(0.0, x.y() / h));
      if (!away_from_side_walls(x, h) || row >= row_p.size()) continue;
      row_p[row] += f.p[i];
      row_d[row] += surface - x.y();
    }
    const BoundaryParticles& b = sim.boundary();
    for (Index k = 0; k < b.size(); ++k)
      if (away_from_side_walls(b.x[k], h) && b.x[k].y() < 0 && b.x[k].y() > -h) {
        sample_p += b.p[k];
        sample_d += surface - b.x[k].y();
      }
  };
  const analysis::HydrostaticResult hr = analysis::run_hydrostatic(scene, kTankWidth, from, false, observe);
  const double rho_g = rho0 * g;
  FloorResult r;
  r.load_ratio = load / static_cast<double>(measured);
  r.bottom_row = hr.bottom_row_ratio;
  r.lower_half = hr.lower_half_ratio;
  r.samples = sample_p / (rho_g * sample_d);
  r.floor_line = 0.5 * (r.bottom_row + r.samples);
  for (std::size_t k = 0; k < row_p.size(); ++k) r.rows.push_back(row_p[k] / (rho_g * row_d[k]));
  r.median_speed = hr.median_speed_end;
  r.iterations_per_step = iterations / static_cast<double>(steps);
  return r;
}

// Each solver at tolerances 0.1 % (the default), 0.03 % and 0.01 %, without the
// stabilisation (Eq. 20 as printed; the multilevel solve's own kappa is 1): the tank stays at rest
// (RestBounds), the lower half within 1 %, the walls carry the fluid's weight within 0.1 %
// and the pressure at the floor line is within 3 % of rho0 g d (RestBounds' bottom-row
// bound). Measured: the load within 0.013 % and the floor line within 1.22 % in every
// case, while the bottom row read -11.2 to +11.7 % and the first sample layer -12.0 to
// +13.7 % (multilevel: +11.07 / -11.44 % at 0.1 %, the floor line -0.19 %).
TEST(WallPressure, FloorLoadAndFloorLinePressureConvergeAtEveryTolerance) {
  const analysis::RestBounds bounds;
  for (const char* solver : {"jacobi", "chebyshev", "multilevel"}) {
    for (const char* tolerance : {"0.1", "0.03", "0.01"}) {
      const FloorResult r =
          measure_floor({std::string("solver.pressure_solver=") + solver, std::string("solver.tolerance=") + tolerance,
                         "solver.pressure_stabilisation=0"});
      std::printf(
          "[ measured ] %s, tolerance %s %%: load/weight %.5f, bottom row %+.2f %%, rows 1-4 %+.2f %+.2f %+.2f %+.2f "
          "%%, "
          "floor samples %+.2f %%, floor line %+.2f %%, lower half %+.2f %%, median %.5f m/s, %.2f iterations per "
          "step\n",
          solver, tolerance, r.load_ratio, 100 * (r.bottom_row - 1), 100 * (r.rows[0] - 1), 100 * (r.rows[1] - 1),
          100 * (r.rows[2] - 1), 100 * (r.rows[3] - 1), 100 * (r.samples - 1), 100 * (r.floor_line - 1),
          100 * (r.lower_half - 1), r.median_speed, r.iterations_per_step);
      SCOPED_TRACE(std::string(solver) + ", tolerance " + tolerance);
      EXPECT_NEAR(r.load_ratio, 1.0, 1e-3);
      EXPECT_LE(std::abs(r.floor_line - 1), bounds.bottom_row);
      EXPECT_LE(r.median_speed, bounds.median_speed);
      EXPECT_LE(std::abs(r.lower_half - 1), bounds.lower_half);
    }
  }
}

// With the pressure stabilisation (solver.pressure_stabilisation, pressure_kernels.h) the
// odd-even mode is no longer a null mode of the PPE, and the bottom row itself reads
// rho0 g d, at every tolerance, with each solver (without it, the first test: -8.6 to
// +11 %): Jacobi with kappa 2 (1 is not enough: +5.02 % at 0.03 %), Chebyshev with 3, the
// multilevel solve with its own kappa (1; 2 moves the tank at 0.03 %). Jacobi and
// multilevel keep the tank at rest and the walls' load at every tolerance; Chebyshev's
// tank moves at 0.1 and 0.03 % (0.035 and 0.0059 m/s; bound 0.005), printed only
// (docs/performance.md, "The stabilisation as an option").
TEST(WallPressure, StabilisedBottomRowConvergesAtEveryTolerance) {
  const analysis::RestBounds bounds;
  const std::pair<const char*, const char*> solvers[] = {
      {"jacobi", "2"}, {"chebyshev", "3"}, {"multilevel", "null"}};  // null: the solver's own
  for (const auto& [solver, kappa] : solvers) {
    for (const char* tolerance : {"0.1", "0.03", "0.01"}) {
      const FloorResult r =
          measure_floor({std::string("solver.pressure_solver=") + solver, std::string("solver.tolerance=") + tolerance,
                         std::string("solver.pressure_stabilisation=") + kappa});
      std::printf(
          "[ measured ] stabilised (kappa %s), %s, tolerance %s %%: load/weight %.5f, bottom row %+.2f %%, rows 1-4 "
          "%+.2f %+.2f "
          "%+.2f %+.2f %%, floor samples %+.2f %%, lower half %+.2f %%, median %.5f m/s, %.2f iterations per step\n",
          kappa, solver, tolerance, r.load_ratio, 100 * (r.bottom_row - 1), 100 * (r.rows[0] - 1),
          100 * (r.rows[1] - 1), 100 * (r.rows[2] - 1), 100 * (r.rows[3] - 1), 100 * (r.samples - 1),
          100 * (r.lower_half - 1), r.median_speed, r.iterations_per_step);
      SCOPED_TRACE(std::string(solver) + ", tolerance " + tolerance);
      EXPECT_LE(std::abs(r.bottom_row - 1), bounds.bottom_row);
      EXPECT_LE(std::abs(r.lower_half - 1), bounds.lower_half);
      if (std::string(solver) == "chebyshev") continue;
      EXPECT_NEAR(r.load_ratio, 1.0, 1e-3);
      EXPECT_LE(r.median_speed, bounds.median_speed);
    }
  }
}

}  // namespace
}  // namespace sluice

namespace sluice {
namespace {

// Issue 35 item 3: a one-layer plate on a column of the fluid lattice in still water
// (scenes/hard/thin_plate.json without its settling) starts at rest density on both
// sides: its samples, whose wall share is what of their support the fluid leaves (their
// own row's, Simulation::compute_sample_wall_shares), and the fluid next to them, whose
// boundary volume is then a lattice cell. Before: samples 13 % over rho0, the fluid
// next to the plate 3.7 % (cubic spline). The start as sampled: without the relaxation.
TEST(ThinObjects, OneLayerPlateStartsAtRestDensity) {
  for (const char* kernel : {"cubic_spline", "wendland_c2"}) {
    SCOPED_TRACE(kernel);
    const Scene scene = load_scene(std::string(SLUICE_SOURCE_DIR) + "/scenes/hard/thin_plate.json",
                                   {"time.settle=0", "time.relax_start=false", std::string("solver.kernel=") + kernel});
    Simulation sim(scene);
    SolverProbe probe(sim);
    probe.prepare_pressure_system(1e-3);
    const double rho0 = scene.solver.rest_density, h = scene.spacing, x_plate = 0.405;
    const auto mid = [](const Vec2& x) { return x.y() > 0.13 && x.y() < 0.37; };  // away from the plate's ends
    const std::vector<double> rho_b = probe.sample_density();
    double worst_sample = 0, worst_fluid = 0;
    int samples = 0, fluid = 0;
    for (Index b = 0; b < sim.boundary().size(); ++b) {
      if (sim.boundary().object[b] != 1 || !mid(sim.boundary().x[b])) continue;
      ++samples;
      worst_sample = std::max(worst_sample, std::abs(rho_b[b] / rho0 - 1));
    }
    for (Index i = 0; i < sim.fluid().size(); ++i) {
      const Vec2 x = sim.fluid().x[i];
      if (std::abs(x.x() - x_plate) > 1.5 * h || !mid(x)) continue;
      ++fluid;
      worst_fluid = std::max(worst_fluid, std::abs(sim.fluid().rho[i] / rho0 - 1));
    }
    std::printf(
        "[ measured ] %s: %d plate samples within %.3f %% of rho0, %d fluid particles next to it within %.3f %%\n",
        kernel, samples, 100 * worst_sample, fluid, 100 * worst_fluid);
    EXPECT_GT(samples, 20);
    EXPECT_GT(fluid, 40);
    EXPECT_LE(worst_sample, 0.005);
    EXPECT_LE(worst_fluid, 0.005);
  }
}

// The start's relaxation (Simulation::relax_start, time.relax_start): a plate 0.2 spacings
// right of a fluid column keeps the column 0.8 h from it, 13.8 % compressed as sampled;
// relaxed, no fluid particle is more than kRelaxStartPercent compressed, and as the tank is at
// rest it then settles (time.settle "auto") for kAutoSettleSeconds and starts still. A start on
// the lattice (the dam break's column) is not touched, to the bit; a dam break off its lattice
// (hard/thin_walls.json, 5.97 %) is relaxed but not settled: its column must fall at t = 0;
// nor is a fluid that starts moving.
TEST(ThinObjects, OffLatticePlateStartIsRelaxed) {
  const std::string root = std::string(SLUICE_SOURCE_DIR) + "/scenes/";
  const std::string plate = "boundaries.1.points=[[0.407,0.1],[0.407,0.4]]";
  const Simulation sampled(
      load_scene(root + "hard/thin_plate.json", {"time.settle=0", "time.relax_start=false", plate}));
  const Simulation relaxed(load_scene(root + "hard/thin_plate.json", {"time.settle=auto", plate}));
  double largest = 0;
  for (const double rho : sampled.fluid().rho) largest = std::max(largest, 100 * (rho / 1000.0 - 1));
  std::printf("[ measured ] plate at x+0.2h: largest compression %.2f %% as sampled, %.2f %% after %d rounds\n",
              largest, relaxed.relax_stats().largest_after_percent, relaxed.relax_stats().rounds);
  EXPECT_EQ(sampled.relax_stats().rounds, 0);
  EXPECT_EQ(sampled.settled_seconds(), 0.0);
  EXPECT_GT(largest, 10.0);
  EXPECT_NEAR(relaxed.relax_stats().largest_before_percent, largest, 1e-9);
  EXPECT_GT(relaxed.relax_stats().rounds, 0);
  EXPECT_LE(relaxed.relax_stats().rounds, kRelaxStartRounds);
  EXPECT_LE(relaxed.relax_stats().largest_after_percent, kRelaxStartPercent);
  EXPECT_EQ(relaxed.settled_seconds(), kAutoSettleSeconds);
  ASSERT_EQ(relaxed.fluid().size(), sampled.fluid().size());
  for (const Vec2& v : relaxed.fluid().v) EXPECT_EQ(v, Vec2::Zero());

  const Simulation dam(load_scene(root + "dam_break.json"));
  const Simulation dam_off(load_scene(root + "dam_break.json", {"time.relax_start=false"}));
  EXPECT_EQ(dam.relax_stats().rounds, 0);
  EXPECT_EQ(dam.fluid().x, dam_off.fluid().x);
  const Simulation walls(load_scene(root + "hard/thin_walls.json"));
  EXPECT_GT(walls.relax_stats().rounds, 0);
  EXPECT_EQ(walls.settled_seconds(), 0.0);
  // A fluid that starts moving keeps its velocity through the relaxation, and is not at rest.
  const Simulation moving(
      load_scene(root + "hard/thin_plate.json", {"time.settle=auto", plate, "fluid.0.velocity=[0.5,0]"}));
  EXPECT_GT(moving.relax_stats().rounds, 0);
  EXPECT_EQ(moving.settled_seconds(), 0.0);
  for (const Vec2& v : moving.fluid().v) EXPECT_EQ(v, Vec2(0.5, 0.0));
}

// A compressed start next to a moving object is relaxed like any other: the relaxation's
// solve books the walls' work in the per-particle array that each step sizes, and wrote past
// its end before the relaxation sized it too (the rotor on Wendland's C2 crashed at its
// construction; found by running the suite with Wendland's C2 as the default).
TEST(ThinObjects, RelaxedStartNextToAMovingObjectRuns) {
  const std::string root = std::string(SLUICE_SOURCE_DIR) + "/scenes/";
  Simulation sim(load_scene(
      root + "hard/thin_plate.json",
      {"boundaries.1.points=[[0.407,0.1],[0.407,0.4]]",
       R"(boundaries.1.motion={"type": "rotation", "pivot": [0.407, 0.25], "angular_velocity": 1})", "time.settle=0"}));
  EXPECT_GT(sim.relax_stats().rounds, 0);
  EXPECT_LE(sim.relax_stats().largest_after_percent, kRelaxStartPercent);
  for (int s = 0; s < 5; ++s) sim.step();
  EXPECT_GT(sim.time(), 0.0);
}

// time.settle "auto", the default, settles every start at rest, on the lattice too: the tank
// starts from the lattice without the pressure that holds it up, and the first steps' ring
// lasts seconds (docs/validation.md, "Every start at rest settles"). A number is kept as
// given: 0 is none. Neither a dam break's column nor a fluid without gravity is at rest.
TEST(StillStart, AutoSettleTakesEveryStartAtRestAndNothingElse) {
  const std::string root = std::string(SLUICE_SOURCE_DIR) + "/scenes/";
  const std::vector<std::string> tank{"time.settle=auto", "spacing=0.02"};
  EXPECT_EQ(Simulation(load_scene(root + "hydrostatic.json", tank)).settled_seconds(), kAutoSettleSeconds);
  EXPECT_EQ(Simulation(load_scene(root + "hydrostatic.json", {"time.settle=0", "spacing=0.02"})).settled_seconds(),
            0.0);
  EXPECT_EQ(Simulation(load_scene(root + "hydrostatic.json", {"time.settle=0.05", "spacing=0.02"})).settled_seconds(),
            0.05);
  std::vector<std::string> weightless = tank;
  weightless.push_back("solver.gravity=[0,0]");
  EXPECT_EQ(Simulation(load_scene(root + "hydrostatic.json", weightless)).settled_seconds(), 0.0);
  const Scene dam = load_scene(root + "dam_break.json", {"spacing=0.02"});
  EXPECT_TRUE(dam.time.auto_settle);
  EXPECT_EQ(Simulation(dam).settled_seconds(), 0.0);
}

// The mean vertical pressure acceleration of each fluid row of the shipped tank at its
// lattice start (rows more than 3 h from the side walls), in units of g, under the linear
// hydrostatic field p = rho0 g d on the fluid and on the samples (Eq. 24 through the
// probe). 1 is the balance that a tank at rest needs.
std::vector<double> linear_field_balance(const std::vector<std::string>& set) {
  std::vector<std::string> all = {"time.settle=0"};
  all.insert(all.end(), set.begin(), set.end());
  const Scene scene = load_scene(kTank, all);
  Simulation sim(scene);
  SolverProbe probe(sim);
  probe.prepare_pressure_system(scene.time.dt);
  const double h = scene.spacing, rho0 = scene.solver.rest_density, g = scene.solver.gravity.norm();
  const FluidParticles& f = sim.fluid();
  const BoundaryParticles& b = sim.boundary();
  const double top = top_of(f), surface = top + 0.5 * h;
  std::vector<double> p(static_cast<std::size_t>(f.size())), pb(static_cast<std::size_t>(b.size()));
  for (Index i = 0; i < f.size(); ++i) p[i] = rho0 * g * (surface - f.x[i].y());
  for (Index k = 0; k < b.size(); ++k) pb[k] = rho0 * g * (surface - b.x[k].y());
  std::vector<double> ap, apb;
  probe.apply(p, pb, ap, apb);
  const std::vector<Vec2>& a = probe.pressure_acceleration();
  const auto rows = static_cast<std::size_t>(std::lround(top / h - 0.5)) + 1;
  std::vector<double> sum(rows, 0.0), count(rows, 0.0);
  for (Index i = 0; i < f.size(); ++i) {
    const Vec2 x = f.x[i];
    if (!away_from_side_walls(x, h)) continue;
    const auto row = static_cast<std::size_t>(x.y() / h);
    sum[row] += a[i].y() / g;
    count[row] += 1;
  }
  for (std::size_t r = 0; r < rows; ++r)
    if (count[r] > 0) sum[r] /= count[r];
  return sum;
}

// Whether the walls' discretisation lets the tank rest on the hydrostatic field: with
// Akinci's volumes V_b = gamma1 / sum_b' W_bb' and gamma1 the lattice's own wall share
// (lattice_wall_share: 0.840753 on the thesis' kernel), a floor sample has the fluid's
// m / rho0 and continues the lattice, so p = rho0 g d balances every row to round-off on
// either kernel. With the thesis' 0.84 the floor samples' volume is 0.09 % short, so the
// own-pressure terms of the bottom row no longer cancel: row 0 gets 0.963 g and row 1
// 1.014 g at 0.5 m depth (an error that grows with depth / h). The solve then has to
// bend the pressure at the floor, on top of the odd-even mode of the tests above
// (docs/validation.md, "The floor's balance").
TEST(WallPressure, LinearFieldBalancesEveryRowWithTheLatticeWallShare) {
  const double share = lattice_wall_share(Kernel2D(0.5 * 2.0 * 0.01), 0.01);
  EXPECT_NEAR(share, 0.840753, 1e-6);
  for (const char* kernel : {"cubic_spline", "wendland_c2"}) {
    SCOPED_TRACE(kernel);
    const std::string k = std::string("solver.kernel=") + kernel;
    char g1[64];
    std::snprintf(g1, sizeof g1, "solver.gamma1=%.17g", share);
    const std::vector<double> exact = linear_field_balance({k, g1});
    const std::vector<double> thesis = linear_field_balance({k});
    std::printf(
        "[ measured ] %s, linear field, rows 0-2 in g: gamma1 = lattice share %.6f %.6f %.6f, 0.84 %.6f %.6f %.6f\n",
        kernel, exact[0], exact[1], exact[2], thesis[0], thesis[1], thesis[2]);
    // Every row but the top two (the free surface of a lattice start, where the field is
    // one-sided: 0.89 / 1.11 g) balances.
    ASSERT_EQ(exact.size(), 50u);
    for (std::size_t r = 0; r + 2 < exact.size(); ++r) EXPECT_NEAR(exact[r], 1.0, 1e-4) << "row " << r;
    EXPECT_GT(std::abs(thesis[0] - 1.0), 0.01);  // the thesis' gamma1 does not: 3.7 % short
  }
}

}  // namespace
}  // namespace sluice
