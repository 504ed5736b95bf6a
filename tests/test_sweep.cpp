// `sluice bench --sweep`: combinations, the Pareto front, the CSV round trip used by
// --collect, and runs that do not depend on the sweep's order.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "analysis/sweep.h"
#include "io/csv.h"
#include "test_process.h"
#include "test_util.h"

namespace sluice {
namespace {

TEST(Sweep, ParsesAxes) {
  const auto a = analysis::parse_sweep("solver.type=iisph,wcsph");
  EXPECT_EQ(a.key, "solver.type");
  EXPECT_EQ(a.values, (std::vector<std::string>{"iisph", "wcsph"}));
  for (const char* bad : {"solver.type", "=iisph", "time.dt=", "time.dt=1e-3,,2e-3", "time.dt=1e-3,"})
    EXPECT_THROW(analysis::parse_sweep(bad), SceneError) << bad;
}

TEST(Sweep, CombinationsFirstAxisSlowest) {
  const auto c = analysis::sweep_combinations({analysis::parse_sweep("a=1,2"), analysis::parse_sweep("b=x,y,z")});
  ASSERT_EQ(c.size(), 6u);
  EXPECT_EQ(c[0], (std::vector<std::string>{"a=1", "b=x"}));
  EXPECT_EQ(c[2], (std::vector<std::string>{"a=1", "b=z"}));
  EXPECT_EQ(c[3], (std::vector<std::string>{"a=2", "b=x"}));
  EXPECT_EQ(analysis::sweep_combinations({}).size(), 1u);  // the scene as it is
}

analysis::SweepRun point(double wall, double error, bool stable = true) {
  analysis::SweepRun r;
  r.simulated = 1.0;
  r.wall_seconds = wall;
  r.avg_density_error = error;
  r.stable = stable;
  return r;
}

TEST(Sweep, ParetoFront) {
  std::vector<analysis::SweepRun> runs{point(1, 0.5), point(2, 0.1),           point(3, 0.2),
                                       point(2, 0.1), point(0.5, 0.01, false), point(4, 0.05)};
  analysis::mark_pareto_front(runs);
  EXPECT_TRUE(runs[0].pareto);   // fastest stable run
  EXPECT_TRUE(runs[1].pareto);   // ties with run 4: neither is better in one and not worse in the other
  EXPECT_FALSE(runs[2].pareto);  // slower and less accurate than run 2
  EXPECT_TRUE(runs[3].pareto);
  EXPECT_FALSE(runs[4].pareto);  // unstable runs are never on the front, nor hide others
  EXPECT_TRUE(runs[5].pareto);   // most accurate
}

TEST(Sweep, CsvRoundTrip) {
  auto r = point(1.5, 0.25);
  r.scene = "dam \"break\", small";
  r.set = {"solver.type=wcsph", "boundaries.0.max=[1, 2]"};
  r.solver = "wcsph";
  r.stable = false;
  r.message = "unstable at step 3, t = 0.1 s: x, y";
  r.ms_phase[2] = 0.125;
  const sluice::test::TempDir dir;
  const auto path = dir.path() / "sweep_roundtrip.csv";
  std::ofstream(path) << analysis::sweep_csv({r, point(2, 0.1)});
  const auto back = analysis::read_sweep_csv(path.string());
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0].scene, r.scene);
  EXPECT_EQ(back[0].set, r.set);
  EXPECT_EQ(back[0].message, r.message);
  EXPECT_FALSE(back[0].stable);
  EXPECT_DOUBLE_EQ(back[0].ms_phase[2], 0.125);
  EXPECT_DOUBLE_EQ(back[1].avg_density_error, 0.1);
  std::ofstream(path) << "not,a,bench,csv\n";
  EXPECT_THROW(analysis::read_sweep_csv(path.string()), io::InputError);
  std::filesystem::remove(path);
}

TEST(Sweep, CsvHasStepSizesAndLabelsAndReadsOldFiles) {
  auto r = point(1.5, 0.25);
  r.set = {"solver.type=iisph", "time.dt_max=0.002"};
  r.avg_dt = 0.00196;
  r.min_dt = 0.0015;
  r.dt_of_max_percent = 98;
  const sluice::test::TempDir dir;
  const auto path = dir.path() / "sweep_dt.csv";
  std::ofstream(path) << analysis::sweep_csv({r});
  const auto back = analysis::read_sweep_csv(path.string());
  ASSERT_EQ(back.size(), 1u);
  EXPECT_DOUBLE_EQ(back[0].avg_dt, 0.00196);
  EXPECT_DOUBLE_EQ(back[0].dt_of_max_percent, 98);
  EXPECT_EQ(back[0].label(), "iisph, 0.002");
  // A bench.csv from before these columns is still collected.
  std::ofstream(path) << "scene,set,solver,particles,threads,stable,message,steps,simulated_s,wall_s,s_per_simulated_s,"
                         "avg_iterations,avg_density_error_percent,max_density_error_percent,ms_neighbors,"
                         "ms_nonpressure,ms_pressure,ms_integrate,ms_total,ms_moving_boundaries,pareto\n"
                         "\"c\",\"solver.type=iisph\",iisph,300,2,1,\"\",10,0.2,0.1,0.5,6,0.07,0.1,1,1,1,1,4,0,1\n";
  EXPECT_EQ(analysis::read_sweep_csv(path.string()).size(), 1u);
  std::filesystem::remove(path);
}

TEST(Sweep, PlotHasNoEmptyLegendEntriesAndLabelsItsPoints) {
  auto a = point(1, 0.5), b = point(2, 0.1);
  a.solver = b.solver = "iisph";
  a.set = {"time.dt_max=0.004"};
  b.set = {"time.dt_max=0.002"};
  std::vector<analysis::SweepRun> runs{a, b};
  analysis::mark_pareto_front(runs);
  std::string gp = analysis::sweep_plot_script(runs, "column");
  EXPECT_NE(gp.find("title \"IISPH\""), std::string::npos) << gp;
  EXPECT_EQ(gp.find("WCSPH"), std::string::npos) << gp;  // no series without points
  EXPECT_NE(gp.find("\"0.004\""), std::string::npos) << gp;
  EXPECT_NE(gp.find("with labels"), std::string::npos) << gp;
  EXPECT_NE(gp.find("Pareto front"), std::string::npos) << gp;
  runs[1].stable = false;  // one drawable point: no front line, no WCSPH
  analysis::mark_pareto_front(runs);
  gp = analysis::sweep_plot_script(runs, "column");
  EXPECT_EQ(gp.find("Pareto front"), std::string::npos) << gp;
  EXPECT_EQ(gp.find("0.002"), std::string::npos) << gp;  // unstable runs are not drawn
}

// Each run starts from the scene's initial state: the same combination gives the same
// numbers whether it runs first or after another.
TEST(Sweep, RunsDoNotDependOnOrder) {
  const char* json = R"({"spacing": 0.04, "time": {"duration": 0.1, "dt": 1e-3},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 0.8]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [1.2, 1.2]}]})";
  const std::vector<std::string> a{"solver.type=iisph"}, b{"solver.type=wcsph", "time.dt=2e-4"};
  const auto a1 = analysis::run_sweep_point(test::scene_from_json(json, a), a);
  const auto b1 = analysis::run_sweep_point(test::scene_from_json(json, b), b);
  const auto a2 = analysis::run_sweep_point(test::scene_from_json(json, a), a);
  EXPECT_EQ(a1.avg_density_error, a2.avg_density_error);
  EXPECT_EQ(a1.max_density_error, a2.max_density_error);
  EXPECT_EQ(a1.steps, a2.steps);
  EXPECT_GT(b1.steps, a1.steps);
  EXPECT_TRUE(a1.stable && b1.stable);
}

// A settle with a fixed step that does not divide its time in floating point (4000 x
// 2.5e-4 s falls 1e-13 s short of 1 s) ends without a last sliver of a step, whose dt^2
// in the pressure solve blew the fluid up (`bench --sweep time.dt=2.5e-4,...` on every
// shipped scene with a settle).
TEST(Sweep, FixedStepSettleEndsWithoutASliverStep) {
  const char* json = R"({"spacing": 0.05, "time": {"duration": 0.01, "dt": 2.5e-4, "settle": 1},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]}]})";
  const std::vector<std::string> set{"solver.type=iisph"};
  const auto r = analysis::run_sweep_point(test::scene_from_json(json, set), set);
  EXPECT_TRUE(r.stable) << r.message;
  EXPECT_EQ(r.steps, 40);
}

// A run whose settle goes unstable is recorded like one that goes unstable later, not
// thrown out of the sweep.
TEST(Sweep, UnstableSettleIsRecorded) {
  const char* json = R"({"spacing": 0.05, "time": {"duration": 0.01, "dt": 0.05, "settle": 1},
    "stability": {"max_error_percent": 1e-6},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]}]})";
  const std::vector<std::string> set;
  analysis::SweepRun r;
  ASSERT_NO_THROW(r = analysis::run_sweep_point(test::scene_from_json(json, set), set));
  EXPECT_FALSE(r.stable);
  EXPECT_NE(r.message.find("settling"), std::string::npos) << r.message;
  EXPECT_EQ(r.simulated, 0.0);
}

// --- the program's sweeps, run as a process -------------------------------------------

const std::string kRoot = std::string(SLUICE_SOURCE_DIR) + "/";

// `bench --sweep solver.type=iisph,wcsph` on the column (a fixed 0.5 ms, IISPH's): IISPH
// keeps the scene's step, WCSPH, above its acoustic limit with it, takes the adaptive one
// and says so; bench.csv gives each run's step and the overrides it ran with.
TEST(SweepCommand, SolverSweepGivesEachSolverItsStep) {
  test::CaseDir dir;
  const test::Result r = test::run_sluice(dir, {"bench", kRoot + "scenes/column.json", "--sweep",
                                                "solver.type=iisph,wcsph", "--duration", "0.02", "-o", "out"});
  ASSERT_EQ(r.status, 0) << r.err << r.out;
  EXPECT_NE(r.out.find("run 2: the scene's time.dt 0.0005 s exceeds WCSPH's acoustic limit"), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("avg_dt_s"), std::string::npos) << r.out;
  const io::CsvTable t = io::read_csv_table((dir.work() / "out" / "bench.csv").string());
  ASSERT_EQ(t.rows.size(), 2u);
  const int set = t.column("set"), dt = t.column("avg_dt_s"), stable = t.column("stable");
  EXPECT_EQ(t.rows[0][set], "solver.type=iisph");
  EXPECT_EQ(t.rows[1][set], "solver.type=wcsph;time.dt=null");
  EXPECT_NEAR(std::stod(t.rows[0][dt]), 5e-4, 1e-5);
  EXPECT_LT(std::stod(t.rows[1][dt]), 6.4e-5);  // 0.4 h / c, c = 20 sqrt(g H) = 62.6 m/s
  EXPECT_EQ(t.rows[0][stable], "1");
  EXPECT_EQ(t.rows[1][stable], "1");
}

// A step the user gives is used as given: every run takes it, and WCSPH refuses one above
// its acoustic limit with the scene error that names it.
TEST(SweepCommand, SolverSweepKeepsAStepTheUserSets) {
  test::CaseDir dir;
  const std::string column = kRoot + "scenes/column.json";
  const test::Result ok = test::run_sluice(dir, {"bench", column, "--sweep", "solver.type=iisph,wcsph", "--duration",
                                                 "0.002", "--set", "time.dt=5e-5", "-o", "a"});
  ASSERT_EQ(ok.status, 0) << ok.err << ok.out;
  EXPECT_EQ(ok.out.find("adaptive step"), std::string::npos) << ok.out;
  const test::Result bad = test::run_sluice(dir, {"bench", column, "--sweep", "solver.type=iisph,wcsph", "--duration",
                                                  "0.002", "--set", "time.dt=5e-4", "-o", "b"});
  EXPECT_EQ(bad.status, 2) << bad.out;
  EXPECT_NE(bad.err.find("/time/dt: WCSPH step 0.0005 s exceeds the acoustic limit"), std::string::npos) << bad.err;
}

// The README's speed-against-error recipe (`bench SCENE --duration 1 --sweep
// time.dt=2.5e-4,5e-4,1e-3`) and the solver sweep run on every shipped scene, shortened
// to 2 ms (and a settle of 0.02 s where the scene settles; the full settles are covered by
// Sweep.FixedStepSettleEndsWithoutASliverStep).
TEST(SweepCommand, ReadmeRecipeRunsOnEveryShippedScene) {
  std::size_t scenes = 0;
  for (const auto& e : std::filesystem::directory_iterator(kRoot + "scenes")) {
    if (e.path().extension() != ".json") continue;
    ++scenes;
    const bool settles = test::read_text(e.path()).find("\"settle\"") != std::string::npos;
    for (const char* sweep : {"time.dt=2.5e-4,5e-4,1e-3", "solver.type=iisph,wcsph"}) {
      test::CaseDir dir;
      std::vector<std::string> args{"bench", e.path().string(), "--duration", "0.002", "--sweep", sweep, "-o", "out"};
      if (settles) args.insert(args.end(), {"--set", "time.settle=0.02"});
      const auto t0 = std::chrono::steady_clock::now();
      const test::Result r = test::run_sluice(dir, args);
      std::printf("[ measured ] %-20s --sweep %-26s %5.1f s\n", e.path().filename().c_str(), sweep,
                  std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
      EXPECT_EQ(r.status, 0) << e.path() << " --sweep " << sweep << "\n" << r.err << r.out;
      if (r.status != 0) continue;
      const io::CsvTable t = io::read_csv_table((dir.work() / "out" / "bench.csv").string());
      EXPECT_EQ(t.rows.size(), std::string(sweep).starts_with("time.dt") ? 3u : 2u) << e.path() << " " << sweep;
      for (const auto& row : t.rows) EXPECT_EQ(row[t.column("stable")], "1") << e.path() << ": " << r.out;
    }
  }
  EXPECT_GE(scenes, 8u);
}

}  // namespace
}  // namespace sluice
