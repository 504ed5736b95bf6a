// The short version of the hard-case suite (scenes/hard/suite.json), as CI runs it:
// every case with each of its solvers must meet its criteria (see analysis/hard_cases.h;
// the full suite is `sluice suite`).
#include <gtest/gtest.h>

#include <filesystem>

#include "analysis/hard_cases.h"
#include "scene/scene.h"

namespace sluice {
namespace {

const std::string kSuite = std::string(SLUICE_SOURCE_DIR) + "/scenes/hard/suite.json";

TEST(HardCases, SuiteLoads) {
  const auto cases = analysis::load_suite(kSuite);
  EXPECT_GE(cases.size(), 8u);
  EXPECT_THROW(analysis::load_suite(kSuite + ".missing"), SceneError);
}

class HardCaseShort : public ::testing::TestWithParam<std::string> {};

TEST_P(HardCaseShort, MeetsItsCriteria) {
  const auto cases = analysis::load_suite(kSuite);
  const std::string dir = std::filesystem::path(kSuite).parent_path().string();
  for (const auto& c : cases) {
    if (c.name != GetParam()) continue;
    for (SolverType s : c.solvers) {
      const analysis::CaseResult r = analysis::run_case(c, dir, s, /*quick=*/true);
      std::printf("%s %s: %s (steps %ld, iterations %.2f, error %.4f %%, max density error %.4f %%, leaks %ld)\n",
                  r.name.c_str(), r.solver.c_str(), r.outcome.c_str(), r.steps, r.avg_iterations, r.avg_error,
                  r.max_density_error, r.leaks);
      EXPECT_TRUE(r.passed) << r.name << " " << r.solver << ": " << r.outcome;
    }
    return;
  }
  FAIL() << "no case " << GetParam() << " in " << kSuite;
}

INSTANTIATE_TEST_SUITE_P(Suite, HardCaseShort,
                         ::testing::Values("deep_column", "dam_break_cfl1", "dam_break_130k", "dam_break_cfl1.5", "fast_rotor", "piston",
                                           "jet", "one_layer_walls", "sparse_walls", "sparse_walls_2x",
                                           "overlap_spawn"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           std::string n = info.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace sluice
