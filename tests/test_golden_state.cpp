// Stored hashes of the final state (positions, velocities, pressures in id order) of
// fixed short runs, one per solver option, each checked at 1, 2 and 3 threads. A run
// against a stored constant catches a commit that changes every bit, which a
// run-against-run comparison cannot (Box2D's determinism test works the same way).
//
// A change that is meant to change the numbers refreshes the table deliberately:
//   SLUICE_UPDATE_GOLDENS=1 build/sluice_unit_tests --gtest_filter='GoldenState.*'
// rewrites tests/golden/state_hashes.txt; the commit says why the bits moved.
#include <gtest/gtest.h>

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "solver/probe.h"
#include "solver/simulation.h"
#include "test_util.h"

namespace sluice {
namespace {

const char* const kTable = SLUICE_SOURCE_DIR "/tests/golden/state_hashes.txt";

// A dam break in a small tank with an obstacle, h = 0.04 (about 120 particles).
const char* const kDamBreak = R"({"spacing": 0.04,
  "time": {"duration": 0.2, "fps": 20, "dt": 2e-3},
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.4, 0.48]}],
  "boundaries": [{"shape": "box", "min": [0, 0], "max": [1.2, 0.8], "lid": false},
                 {"shape": "circle", "center": [0.8, 0.12], "radius": 0.08}]})";

// A cylinder carried on a circle through a fluid at rest.
const char* const kMoving = R"({"spacing": 0.04,
  "time": {"duration": 0.2, "fps": 20, "cfl": 0.4, "dt_max": 2e-3},
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.8, 0.32]}],
  "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.8, 0.6], "lid": false},
                 {"shape": "circle", "center": [0.52, 0.2], "radius": 0.06,
                  "motion": {"type": "rotation", "pivot": [0.4, 0.2], "angular_velocity": 3}}]})";

struct Config {
  const char* name;
  const char* scene;
  std::vector<std::string> set;
  Index sweep_block = 0;  // > 0: the fused Jacobi sweep with blocks of this many particles, 3 ranges
};

const std::vector<Config>& configs() {
  static const std::vector<Config> c = {
      {"iisph_solved", kDamBreak, {}},
      {"iisph_chebyshev", kDamBreak, {"solver.pressure_solver=chebyshev"}},
      {"iisph_multilevel", kDamBreak, {"solver.pressure_solver=multilevel"}},
      {"iisph_extrapolation", kDamBreak, {"solver.boundary_pressure=extrapolation"}},
      {"iisph_mirroring", kDamBreak, {"solver.boundary_pressure=mirroring"}},
      {"iisph_zero", kDamBreak, {"solver.boundary_pressure=zero"}},
      {"iisph_thesis_init", kDamBreak, {"solver.pressure_init=thesis"}},
      {"iisph_plain_diagonal", kDamBreak, {"solver.boundary_pressure=extrapolation", "solver.boundary_diagonal=false"}},
      {"iisph_no_gradient_correction", kDamBreak, {"solver.gradient_correction=false"}},
      {"iisph_viscous", kDamBreak, {"solver.viscosity=1e-3", "solver.artificial_viscosity=0"}},
      {"iisph_settled", kDamBreak, {"time.settle=0.1"}},
      {"iisph_fused_sweep", kDamBreak, {}, 16},
      {"wcsph_solved", kDamBreak, {"solver.type=wcsph", "time.dt=null"}},
      {"wcsph_extrapolation",
       kDamBreak,
       {"solver.type=wcsph", "time.dt=null", "solver.boundary_pressure=extrapolation"}},
      {"iisph_moving", kMoving, {}},
      {"wcsph_moving", kMoving, {"solver.type=wcsph"}},
  };
  return c;
}

std::string hex(std::uint64_t h) {
  char b[17];
  std::snprintf(b, sizeof b, "%016" PRIx64, h);
  return b;
}

std::map<std::string, std::string> read_table() {
  std::map<std::string, std::string> t;
  std::ifstream in(kTable);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string name, h;
    if (s >> name >> h) t[name] = h;
  }
  return t;
}

std::string run_hash(const Config& c, int threads) {
  const test::ThreadCount tc(threads);
  Simulation sim(test::scene_from_json(c.scene, c.set));
  if (c.sweep_block > 0) SolverProbe(sim).set_jacobi_sweep(c.sweep_block, 3);
  while (!sim.finished()) sim.step();
  return hex(test::state_hash(sim));
}

bool updating() {
  const char* u = std::getenv("SLUICE_UPDATE_GOLDENS");
  return u && std::string(u) == "1";
}

TEST(GoldenState, FinalStateMatchesTheStoredHashAtOneTwoAndThreeThreads) {
  const std::map<std::string, std::string> table = read_table();
  std::ostringstream fresh;
  fresh << "# Final-state hashes of tests/test_golden_state.cpp (FNV-1a of x, v, p in id order).\n"
           "# Refresh: SLUICE_UPDATE_GOLDENS=1 build/sluice_unit_tests --gtest_filter='GoldenState.*'\n";
  for (const Config& c : configs()) {
    const std::string one = run_hash(c, 1);
    for (int threads : {2, 3}) EXPECT_EQ(run_hash(c, threads), one) << c.name << " at " << threads << " threads";
    fresh << c.name << ' ' << one << '\n';
    if (updating()) continue;
    const auto it = table.find(c.name);
    ASSERT_NE(it, table.end()) << c.name << " has no stored hash in " << kTable;
    EXPECT_EQ(one, it->second) << c.name << ": the final state changed; if that is intended, refresh the table";
  }
  if (updating()) {
    std::ofstream(kTable) << fresh.str();
    std::printf("[ updated  ] %s\n", kTable);
  }
}

}  // namespace
}  // namespace sluice
