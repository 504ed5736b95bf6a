// The dam break against Martin & Moyce (1952): the surge front of the 1 m x 2 m column
// (scenes/validation/dam_break_martin_moyce.json, h = 0.02, in a 16 m channel) over the
// experiment's 15 points, as `sluice validate dam-break` prints it.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "analysis/validation.h"
#include "scene/scene.h"
#include "test_process.h"

namespace sluice {
namespace {

// The simulated front leads the experiment by 10-20 % at every point (measured RMS 13.0 %
// for IISPH at h = 0.02), as SPH and other simulations of this experiment commonly do: the
// simulation releases the column instantly, the experiment by removing a gate. 20 % bounds
// that systematic lead with margin.
constexpr double kMaxRms = 0.20;

const std::string kScene = std::string(SLUICE_SOURCE_DIR) + "/scenes/validation/dam_break_martin_moyce.json";

TEST(Validation, MartinMoyceDataIsMonotone) {
  const auto d = analysis::martin_moyce_n2_a225();
  ASSERT_EQ(d.size(), 15u);
  for (std::size_t i = 1; i < d.size(); ++i) {
    EXPECT_GT(d[i].first, d[i - 1].first);
    EXPECT_GT(d[i].second, d[i - 1].second);
  }
}

void check_front(const analysis::DamBreakResult& r, double bound, const char* solver) {
  std::printf(
      "[ measured ] dam break %s: a = %.3f m, n^2 = %.2f, %zu points, RMS relative error %.4f, %ld steps, %.1f s\n",
      solver, r.a, r.height / r.a, r.compared.size(), r.rms_relative_error, r.steps, r.wall_seconds);
  for (const auto& p : r.compared)
    std::printf("  T %.3f  Z exp %.3f  sim %.3f  (%+.1f %%)\n", p.T, p.Z_experiment, p.Z_simulated,
                100 * p.relative_error);
  EXPECT_NEAR(r.a, 1.0, 1e-9);
  EXPECT_NEAR(r.height / r.a, 2.0, 1e-9);
  // The channel is long enough for every measured point.
  EXPECT_EQ(r.compared.size(), 15u);
  EXPECT_LT(r.rms_relative_error, bound);
  // The front starts at the column's width and only advances.
  ASSERT_FALSE(r.front.empty());
  EXPECT_NEAR(r.front.front().Z, 1.0, 1e-9);
  for (std::size_t i = 1; i < r.front.size(); ++i) EXPECT_GE(r.front[i].Z, r.front[i - 1].Z - 0.02) << "frame " << i;
}

TEST(Validation, DamBreakFrontIisph) {
  const Scene scene = load_scene(kScene, {"solver.type=iisph"});
  check_front(analysis::run_dam_break_front(scene), kMaxRms, "iisph");
}

// Issue 35's convergence target: IISPH's fronts at h = 0.04, 0.02 and 0.01 differ less, by
// at least 1.5x, at each halving (the observed order of `validate dam-break`, p >= 0.58).
// Measured 2.19 % then 1.40 % (1.56x) with steps proportional to h; 2.29 % then 1.11 %
// while dt_max capped the two coarse levels' steps; 2.04 % then 2.01 % while the
// artificial viscosity rubbed along the floor. About 30 s.
TEST(Validation, DamBreakFrontsConvergeIisph) {
  std::vector<analysis::DamBreakResult> r;
  for (const char* h : {"0.04", "0.02", "0.01"})
    r.push_back(analysis::run_dam_break_front(load_scene(kScene, {"solver.type=iisph", std::string("spacing=") + h})));
  const double d12 = analysis::front_difference(r[0], r[1]), d23 = analysis::front_difference(r[1], r[2]);
  std::printf(
      "[ measured ] dam break fronts, IISPH: differences %.3f %% (0.04/0.02), %.3f %% (0.02/0.01), ratio %.2f\n",
      100 * d12, 100 * d23, d12 / d23);
  EXPECT_GE(d12 / d23, 1.5);
  for (const auto& x : r) EXPECT_LT(x.rms_relative_error, kMaxRms);
  // The bulk front (5 % of the fluid ahead) converges too: 1.09 % then 0.66 % (1.64x).
  const double b12 = analysis::front_difference(r[0], r[1], analysis::Front::Bulk);
  const double b23 = analysis::front_difference(r[1], r[2], analysis::Front::Bulk);
  std::printf("[ measured ] bulk fronts: differences %.3f %%, %.3f %%, ratio %.2f\n", 100 * b12, 100 * b23, b12 / b23);
  EXPECT_GE(b12 / b23, 1.5);
  // Why the tip cannot converge faster than order 1/2 (analysis::ritter_depth): late in the
  // surge it runs as Ritter's surge at a depth of about half a spacing (measured 0.50, 0.47,
  // 0.56 h), slower than the ideal tip's dZ/dT = 2 by 3 sqrt(d / 2a), a lag that shrinks
  // by about sqrt 2 per halving (measured 1.45, 1.30).
  double lag_before = 0;
  for (size_t k = 0; k < r.size(); ++k) {
    const double h = 0.04 / static_cast<double>(1 << k);
    const double lag = 2 - r[k].late_tip_speed, depth = analysis::ritter_depth(r[k].late_tip_speed, 1.0, 2.0);
    std::printf("[ measured ] h %.3f: late tip dZ/dT %.3f, lag %.3f, Ritter depth %.2f h\n", h, r[k].late_tip_speed,
                lag, depth / h);
    EXPECT_GT(lag, 0) << h;
    EXPECT_GT(depth / h, 0.25) << h;
    EXPECT_LT(depth / h, 0.75) << h;
    if (k > 0) {
      EXPECT_GT(lag_before / lag, 1.15) << h;
      EXPECT_LT(lag_before / lag, 1.7) << h;
    }
    lag_before = lag;
  }
}

// A 10 x 10 block of cells h = 0.1 wide: 10 % of it lies ahead of x = 0.9, the edge between
// the last two columns, and all of it ahead of the block's back edge.
TEST(Validation, VolumeFrontIsWhereTheShareOfCellsAheadIs) {
  std::vector<double> x;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) x.push_back(0.1 * (i + 0.5));
  EXPECT_NEAR(analysis::volume_front(x, 0.1, 0.1), 0.9, 1e-12);
  EXPECT_NEAR(analysis::volume_front(x, 0.1, 0.25), 0.75, 1e-12);  // half of the third column
  EXPECT_NEAR(analysis::volume_front(x, 0.1, 1.0), 0.0, 1e-12);
  std::vector<double> none;
  EXPECT_TRUE(std::isnan(analysis::volume_front(none, 0.1, 0.1)));
}

// Ritter's surge point at depth d runs at 2 c0 - 3 sqrt(g d): in Martin & Moyce's units
// (n^2 = 2) dZ/dT = 2 - 3 sqrt(d / 2a); the ideal tip (dZ/dT = 2) has no depth.
TEST(Validation, RitterDepthInvertsTheSurgeSpeed) {
  for (double d : {0.001, 0.005, 0.02})
    EXPECT_NEAR(analysis::ritter_depth(2 - 3 * std::sqrt(d / 2), 1.0, 2.0), d, 1e-12) << d;
  EXPECT_EQ(analysis::ritter_depth(2.0, 1.0, 2.0), 0.0);
  EXPECT_EQ(analysis::ritter_depth(2.1, 1.0, 2.0), 0.0);
  EXPECT_TRUE(std::isnan(analysis::ritter_depth(std::nan(""), 1.0, 2.0)));
  // Another column: a = 0.5, H0 = 2 (n^2 = 4): the tip at 2 sqrt(H0 / 2a) = 2 sqrt 2.
  EXPECT_NEAR(analysis::ritter_depth(2 * std::sqrt(2.0) - 3 * std::sqrt(0.004 / 1.0), 0.5, 2.0), 0.004, 1e-12);
}

TEST(Validation, ShortChannelIsRefused) {
  EXPECT_THROW(analysis::run_dam_break_front(load_scene(kScene, {"boundaries.0.max=[1.2, 3]"})), SceneError);
}

}  // namespace
}  // namespace sluice

namespace sluice {
namespace {

const std::string kRoot = std::string(SLUICE_SOURCE_DIR) + "/";

// The shipped tank (`sluice validate hydrostatic`) with `set` on its defaults, pressures
// averaged over its last 0.5 s; prints what it measured.
analysis::HydrostaticResult shipped_tank(const char* label, const std::vector<std::string>& set) {
  const Scene scene = load_scene(kRoot + "scenes/hydrostatic.json", set);
  const analysis::HydrostaticResult r = analysis::run_hydrostatic(scene, 0.4, scene.time.duration - 0.5, false);
  std::printf("[ measured ] shipped tank, %s: median speed %.5f m/s, lower half %+.2f %%, bottom row %+.2f %%\n", label,
              r.median_speed_end, 100 * (r.lower_half_ratio - 1), 100 * (r.bottom_row_ratio - 1));
  return r;
}

// IISPH: at rest (median speed at 3 s at most 5 mm/s; before pressure boundaries 0.149),
// the lower half within 1 % of rho0 g d (+1.75 % before the gradient correction) and the
// bottom row within 3 % (before: +22 %).
TEST(Validation, ShippedTankStaysAtRest) {
  const analysis::HydrostaticResult r = shipped_tank("IISPH", {});
  const analysis::RestBounds bounds;
  EXPECT_LE(r.median_speed_end, bounds.median_speed);
  EXPECT_LE(std::abs(r.bottom_row_ratio - 1), bounds.bottom_row);
  EXPECT_LE(std::abs(r.lower_half_ratio - 1), bounds.lower_half);
}

// WCSPH (its default stiffness, the acoustic step): the same bounds. With the fixed
// k = 1e6 of before the bottom row read +3.64 % (docs/validation.md, "Rest").
TEST(Validation, ShippedTankStaysAtRestWcsph) {
  const analysis::HydrostaticResult r = shipped_tank("WCSPH", {"solver.type=wcsph", "time.dt=null"});
  const analysis::RestBounds bounds;
  EXPECT_LE(r.median_speed_end, bounds.median_speed);
  EXPECT_LE(std::abs(r.bottom_row_ratio - 1), bounds.bottom_row);
  EXPECT_LE(std::abs(r.lower_half_ratio - 1), bounds.lower_half);
}

// WCSPH in the same tank (h = 0.02 to keep CI short) with its default stiffness and the
// acoustic step stays bounded for 10 s and loses energy (before: 1 m/s at 0.7 s).
TEST(Validation, WcsphTankAtRestStaysBounded) {
  const Scene scene = load_scene(kRoot + "scenes/hydrostatic.json",
                                 {"solver.type=wcsph", "time.dt=null", "spacing=0.02", "time.duration=10"});
  const analysis::AtRestResult r = analysis::run_at_rest(scene);
  std::printf("[ measured ] WCSPH tank, 10 s: median %.5f m/s, max %.5f m/s, energy drift %.4f J/m, %ld steps\n",
              r.median_speed_end, r.max_speed_end, r.energy_drift, r.steps);
  EXPECT_LE(r.median_speed_end, 0.005);
  EXPECT_LE(r.max_speed_end, 0.05);
  EXPECT_LE(r.energy_drift, 0.0);
}

// scenes/hard/thin_plate.json: the plate sampled on its curve leaves still water still
// with either solver (median speed at 2 s at most 5 mm/s; before: a cavity and spray
// above 1 m/s).
TEST(Validation, ThinPlateLeavesWaterStill) {
  for (const char* solver : {"iisph", "wcsph"}) {
    std::vector<std::string> set{std::string("solver.type=") + solver};
    if (std::string(solver) == "wcsph") set.push_back("time.dt=null");
    const analysis::AtRestResult r = analysis::run_at_rest(load_scene(kRoot + "scenes/hard/thin_plate.json", set));
    std::printf("[ measured ] thin plate, %s: median %.5f m/s, max %.5f m/s, energy drift %.4f J/m\n", solver,
                r.median_speed_end, r.max_speed_end, r.energy_drift);
    EXPECT_LE(r.median_speed_end, 0.005) << solver;
    EXPECT_LE(r.energy_drift, 0.0) << solver;
  }
}

// Still water without settling (issue 35 item 3): the tank of thin_plate.json with the
// plate lifted out and time.settle 0 (no settling at all, not even the automatic one: the
// lattice itself is under test). On Wendland's C2 the square lattice the fluid starts on
// stays still under its hydrostatic pressure with either solver; on the thesis' cubic
// spline it does not (median 0.0092 / 0.0076 m/s at 2 s: disordered motion that grows from
// the first steps, docs/validation.md), which is why the shipped scenes settle first.
TEST(Validation, TankWithoutSettlingStaysStillOnWendlandC2) {
  for (const char* solver : {"iisph", "wcsph"}) {
    std::vector<std::string> set{std::string("solver.type=") + solver, "solver.kernel=wendland_c2", "time.settle=0",
                                 "boundaries.1.points=[[0.405,0.56],[0.405,0.59]]"};
    if (std::string(solver) == "wcsph") set.push_back("time.dt=null");
    const analysis::AtRestResult r = analysis::run_at_rest(load_scene(kRoot + "scenes/hard/thin_plate.json", set));
    std::printf("[ measured ] tank without settling, Wendland C2, %s: median %.5f m/s, max %.5f m/s\n", solver,
                r.median_speed_end, r.max_speed_end);
    EXPECT_LE(r.median_speed_end, 0.005) << solver;
  }
}

// Issue 35 item 3, the part that holds: on Wendland's C2 (whose lattice stays still, the
// test above) a one-layer plate on a fluid column, submerged or piercing the surface,
// leaves the water still without settling, since each sample's wall share and volume
// come from the fluid it starts with (Simulation::compute_sample_wall_shares). Before:
// IISPH 0.0076 / 0.0070, WCSPH 0.0116 / 0.0158 m/s (submerged / piercing); after
// 0.0020 / 0.0022 and 0.0020 / 0.0023 (docs/validation.md, "Thin objects at rest"). Off the
// lattice (0.2 spacings right of a fluid column, the column next to it 13.8 % compressed as
// sampled) the start's relaxation brings it to rest density, and as the tank is at rest it
// then settles for 0.1 s, as every start at rest does with time.settle "auto", the default
// (Simulation::relax_start, starts_at_rest): IISPH 0.0028, WCSPH 0.0027 m/s; relaxed only
// 0.0038 / 0.0042; as sampled 0.0066 / 0.0095. The plates on the column start 1.4 % compressed
// at their ends and are relaxed and settled too: IISPH 0.0022 / 0.0021, WCSPH 0.0011 / 0.0011
// (docs/validation.md, "The start relaxed" and the sections after it). The last two are the
// plate sweep's cases that failed until every start at rest settled (within 1 % as sampled,
// so not relaxed): 30 degrees 0.2 spacings off, IISPH 0.00532 -> 0.00306 m/s; piercing 0.4
// spacings off, WCSPH 0.00544 -> 0.00143 (docs/validation.md, "Every start at rest settles").
TEST(Validation, PlateWithoutSettlingStaysStillOnWendlandC2) {
  const std::pair<const char*, const char*> plates[] = {
      {"submerged", "[[0.405,0.1],[0.405,0.4]]"},
      {"piercing", "[[0.405,0.3],[0.405,0.58]]"},
      {"submerged off the lattice", "[[0.407,0.1],[0.407,0.4]]"},
      {"submerged at 30 degrees", "[[0.332,0.120096],[0.482,0.379904]]"},
      {"piercing off the lattice", "[[0.409,0.3],[0.409,0.58]]"}};
  for (const char* solver : {"iisph", "wcsph"})
    for (const auto& [where, points] : plates) {
      std::vector<std::string> set{std::string("solver.type=") + solver, "solver.kernel=wendland_c2",
                                   "time.settle=auto", std::string("boundaries.1.points=") + points};
      if (std::string(solver) == "wcsph") set.push_back("time.dt=null");
      const analysis::AtRestResult r = analysis::run_at_rest(load_scene(kRoot + "scenes/hard/thin_plate.json", set));
      std::printf("[ measured ] plate %s without settling, Wendland C2, %s: median %.5f m/s, max %.5f m/s\n", where,
                  solver, r.median_speed_end, r.max_speed_end);
      EXPECT_LE(r.median_speed_end, 0.005) << solver << ", " << where;
    }
}

// --- `sluice validate`, run as a process -----------------------------------------------
// Each subcommand as a user runs it, in a folder holding the shipped scenes (its default
// scene files), shortened with its own flags where the full run takes minutes. A
// shortened run need not meet bounds meant for the full length (the tests above hold
// those); it must run to its end: a row per solver or case, its CSV, and exit 1 exactly
// when a row reads FAILED. A scene or flag error (2: what `validate elliptical-drop`
// gave when WCSPH's default stiffness could not see the drop's motion), an output error
// (3) or an instability (4) fails the test.

test::Result run_validate(const test::CaseDir& dir, const std::vector<std::string>& args) {
  std::filesystem::create_directory_symlink(kRoot + "scenes", dir.work() / "scenes");
  std::vector<std::string> all{"validate"};
  all.insert(all.end(), args.begin(), args.end());
  const auto t0 = std::chrono::steady_clock::now();
  test::Result r = test::run_sluice(dir, all);
  std::printf("[ measured ] validate %s: %.1f s, exit %d\n", args.front().c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(), r.status);
  std::printf("%s", r.out.c_str());
  return r;
}

// The run ended with its verdict, a row for each of `rows` (a solver or a case) and
// `csv` under renders/validation with one line per row after its header.
void expect_verdict(const test::CaseDir& dir, const test::Result& r, const std::vector<std::string>& rows,
                    const std::map<std::string, std::size_t>& csv) {
  const bool failed = r.out.find("FAILED") != std::string::npos;
  EXPECT_EQ(r.status, failed ? 1 : 0) << r.err;
  EXPECT_EQ(r.err.find("error"), std::string::npos) << r.err;
  for (const std::string& row : rows) EXPECT_NE(r.out.find("\n" + row + " "), std::string::npos) << row;
  for (const auto& [file, lines] : csv) {
    const std::string text = test::read_text(dir.work() / "renders" / "validation" / file);
    EXPECT_EQ(static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')), lines + 1) << file;
  }
}

// With its defaults, in full (a few seconds): both solvers within the 1 % bound.
TEST(ValidateCommand, EllipticalDrop) {
  test::CaseDir dir;
  const test::Result r = run_validate(dir, {"elliptical-drop"});
  EXPECT_EQ(r.status, 0) << r.err;
  expect_verdict(dir, r, {"iisph", "wcsph"}, {{"elliptical_drop.csv", 2}});
  EXPECT_EQ(r.out.find("FAILED"), std::string::npos);
}

// One spacing, 0.04 (the default runs 0.04, 0.02 and 0.01), both solvers and releases:
// all four within the 20 % bound.
TEST(ValidateCommand, DamBreak) {
  test::CaseDir dir;
  const test::Result r = run_validate(dir, {"dam-break", "--spacing", "0.04"});
  EXPECT_EQ(r.status, 0) << r.err;
  expect_verdict(dir, r, {"iisph   instant", "iisph   gate", "wcsph   instant", "wcsph   gate"},
                 {{"dam_break_points.csv", 4 * 15}});
}

// Three spacings, coarse to fine (IISPH, the instant release, h = 0.16, 0.08 and 0.04):
// the observed order from the two differences, printed and in dam_break_convergence.csv,
// the same numbers as the differences' CSV.
TEST(ValidateCommand, DamBreakObservedOrder) {
  test::CaseDir dir;
  const test::Result r =
      run_validate(dir, {"dam-break", "--solver", "iisph", "--scene",
                         std::string(SLUICE_SOURCE_DIR) + "/scenes/validation/dam_break_martin_moyce.json", "--spacing",
                         "0.16,0.08,0.04"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("observed order of convergence"), std::string::npos) << r.out;
  const std::string csv = test::read_text(dir.work() / "renders/validation/dam_break_convergence.csv");
  const std::string diffs = test::read_text(dir.work() / "renders/validation/dam_break_differences.csv");
  for (const std::string front : {"tip", "bulk"}) {
    double h1, h2, h3, d12, d23, ratio, order;
    const std::string prefix = "\n" + front + ",iisph,";
    const std::size_t row = csv.find(prefix);
    ASSERT_NE(row, std::string::npos) << csv;
    ASSERT_EQ(std::sscanf(csv.c_str() + row + prefix.size(), "%lf,%lf,%lf,%lf,%lf,%lf,%lf", &h1, &h2, &h3, &d12, &d23,
                          &ratio, &order),
              7)
        << csv;
    EXPECT_EQ(h1, 0.16);
    EXPECT_EQ(h2, 0.08);
    EXPECT_EQ(h3, 0.04);
    EXPECT_GT(d12, 0);
    EXPECT_GT(d23, 0);
    EXPECT_DOUBLE_EQ(ratio, d12 / d23);
    EXPECT_NEAR(order, std::log2(ratio), 1e-12);
  }
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 3) << csv;  // header and one triple per front
  EXPECT_NE(r.out.find("tip extrapolated to h -> 0 at order 1/2"), std::string::npos) << r.out;
  // The differences' CSV holds the same numbers.
  EXPECT_NE(diffs.find("resolution,iisph_instant_h0.16,iisph_instant_h0.08,"), std::string::npos) << diffs;
  EXPECT_NE(diffs.find("resolution,iisph_instant_h0.08,iisph_instant_h0.04,"), std::string::npos) << diffs;
}

// The shipped tank and the eight boundary cases at h = 0.02, settled 0.1 s, run 0.6 s
// (the defaults: h = 0.01 and 0.02, 1 and 0.5 s of settling, 3 and 2 s).
TEST(ValidateCommand, Hydrostatic) {
  test::CaseDir dir;
  const test::Result r =
      run_validate(dir, {"hydrostatic", "--set", "spacing=0.02", "time.settle=0.1", "time.duration=0.6"});
  std::vector<std::string> rows{"iisph", "wcsph"};
  for (const auto& c : analysis::hydrostatic_cases()) rows.push_back(c.name);
  expect_verdict(dir, r, rows, {{"hydrostatic_shipped.csv", 2}, {"hydrostatic.csv", 8}});
}

// The plate, settled 0.1 s, run 0.1 s (the defaults: 1 s and 2 s).
TEST(ValidateCommand, ThinPlate) {
  test::CaseDir dir;
  const test::Result r = run_validate(dir, {"thin-plate", "--set", "time.settle=0.1", "time.duration=0.1"});
  expect_verdict(dir, r, {"iisph", "wcsph"}, {{"thin_plate.csv", 2}});
}

// A relaxed start is said and kept: `simulate` prints its rounds and compressions, and
// summary.json holds them as start_relaxation (the plate 0.2 spacings off a fluid column,
// 13.8 % compressed as sampled); the automatic settle that follows is printed and kept as
// settle. A start on the lattice has no relaxation's record, and with time.settle 0 no settle.
TEST(SimulateCommand, RelaxedStartIsRecorded) {
  test::CaseDir dir;
  const std::string scene = kRoot + "scenes/hard/thin_plate.json";
  const test::Result r = test::run_sluice(dir, {"simulate", scene, "-o", "relaxed", "--duration", "0.01", "--set",
                                                "time.settle=auto", "boundaries.1.points=[[0.407,0.1],[0.407,0.4]]"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("sluice: relaxed the start in "), std::string::npos) << r.err;
  const nlohmann::json summary = nlohmann::json::parse(test::read_text(dir.work() / "relaxed" / "summary.json"));
  ASSERT_TRUE(summary.contains("start_relaxation")) << summary.dump();
  EXPECT_GT(summary["start_relaxation"]["rounds"].get<int>(), 0);
  EXPECT_GT(summary["start_relaxation"]["largest_compression_before_percent"].get<double>(), 10.0);
  EXPECT_LE(summary["start_relaxation"]["largest_compression_after_percent"].get<double>(), 1.0);
  EXPECT_EQ(summary["settle"]["seconds"].get<double>(), 0.1);
  EXPECT_TRUE(summary["settle"]["automatic"].get<bool>());
  EXPECT_NE(r.err.find("sluice: settled for 0.1 s before t = 0, as the fluid starts at rest"), std::string::npos)
      << r.err;
  const test::Result lattice = test::run_sluice(dir, {"simulate", kRoot + "scenes/hydrostatic.json", "-o", "lattice",
                                                      "--duration", "0.01", "--set", "time.settle=0"});
  ASSERT_EQ(lattice.status, 0) << lattice.err;
  EXPECT_EQ(lattice.err.find("relaxed the start"), std::string::npos) << lattice.err;
  const nlohmann::json lattice_summary =
      nlohmann::json::parse(test::read_text(dir.work() / "lattice" / "summary.json"));
  EXPECT_FALSE(lattice_summary.contains("start_relaxation"));
  EXPECT_FALSE(lattice_summary.contains("settle"));
}

// The plate sweep (issue 35 item 3), one case for 0.1 s (the default: 30 cases of 2 s per
// solver): a row per solver, its CSV, and a case name that is not one of the sweep's is a
// flag error (exit 1, nothing run) naming the form of the allowed ones; so are two
// spacings, and a case for thin-plate.
TEST(ValidateCommand, PlateSweep) {
  test::CaseDir dir;
  const test::Result r =
      run_validate(dir, {"plate-sweep", "--case", "piercing_30deg_x+0.4h", "--set", "time.duration=0.1"});
  expect_verdict(dir, r, {"iisph  piercing_30deg_x+0.4h", "wcsph  piercing_30deg_x+0.4h"}, {{"plate_sweep.csv", 2}});
  test::CaseDir bad;
  const test::Result e = run_validate(bad, {"plate-sweep", "--case", "sideways"});
  EXPECT_EQ(e.status, 1);
  EXPECT_NE(e.err.find("--case sideways: a case name such as submerged_30deg_x+0.4h"), std::string::npos) << e.err;
  EXPECT_FALSE(std::filesystem::exists(bad.work() / "renders" / "validation" / "plate_sweep.csv"));
  // Flags the plate's commands do not read are refused, not ignored.
  test::CaseDir two, cases;
  const test::Result s = run_validate(two, {"plate-sweep", "--spacing", "0.02,0.01"});
  EXPECT_EQ(s.status, 1);
  EXPECT_NE(s.err.find("--spacing 0.02,0.01: plate-sweep runs one spacing"), std::string::npos) << s.err;
  const test::Result c = run_validate(cases, {"thin-plate", "--case", "submerged_0deg_x+0.0h"});
  EXPECT_EQ(c.status, 1);
  EXPECT_NE(c.err.find("thin-plate runs one case per solver"), std::string::npos) << c.err;
}

}  // namespace
}  // namespace sluice
