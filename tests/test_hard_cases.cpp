// The short version of the hard-case suite (scenes/hard/suite.json), as CI runs it: every
// case and solver expected to hold must hold, and every declared expected stop must stop
// (see analysis/hard_cases.h; the full suite is `sluice suite`). Known limits are not run
// here: they fail, and a test must not pass because a case failed.
#include <gtest/gtest.h>

#include <filesystem>

#include "analysis/hard_cases.h"
#include "scene/scene.h"
#include "temp_dir.h"

namespace sluice {
namespace {

const std::string kSuite = std::string(SLUICE_SOURCE_DIR) + "/scenes/hard/suite.json";
const std::string kDir = std::filesystem::path(kSuite).parent_path().string();

struct Run {
  std::string name;
  SolverType solver;
};

std::string solver_name(SolverType s) { return s == SolverType::IISPH ? "iisph" : "wcsph"; }

void PrintTo(const Run& r, std::ostream* os) { *os << r.name << " " << solver_name(r.solver); }

// Outcomes compared by name, so that a failure prints "held" and "failed", not bytes.
std::string result(const analysis::CaseResult& r) { return analysis::outcome_name(r.result); }

// The runs to test, from the suite file; empty when it does not load (SuiteLoads fails).
std::vector<Run> runs() {
  std::vector<Run> out;
  try {
    for (const auto& c : analysis::load_suite(kSuite))
      if (!c.known_limit)
        for (SolverType s : c.solvers) out.push_back({c.name, s});
  } catch (const SceneError&) {
  }
  return out;
}

analysis::HardCase find_case(const std::string& name) {
  for (const auto& c : analysis::load_suite(kSuite))
    if (c.name == name) return c;
  throw SceneError("no case " + name + " in " + kSuite);
}

void print(const analysis::CaseResult& r) {
  std::printf("%s %s: %s: %s (steps %ld, iterations %.2f, error %.4f %%, max density error %.4f %%, leaks %ld)\n",
              r.name.c_str(), r.solver.c_str(), analysis::outcome_name(r.result), r.outcome.c_str(), r.steps,
              r.avg_iterations, r.avg_error, r.max_density_error, r.leaks);
}

TEST(HardCases, SuiteLoads) {
  const auto cases = analysis::load_suite(kSuite);
  EXPECT_GE(cases.size(), 8u);
  EXPECT_GE(runs().size(), 8u);
  EXPECT_THROW(analysis::load_suite(kSuite + ".missing"), SceneError);
}

TEST(HardCases, ExpectStopNeedsWhyAndARunSolver) {
  const sluice::test::TempDir dir;
  const auto tmp = dir.path() / "suite_expect_stop.json";
  const auto load = [&](const std::string& text) {
    std::FILE* f = std::fopen(tmp.string().c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs(text.c_str(), f);
    std::fclose(f);
    analysis::load_suite(tmp.string());
  };
  EXPECT_THROW(load(R"({"cases": [{"name": "a", "scene": "x.json", "expect_stop": ["wcsph"]}]})"), SceneError);
  EXPECT_THROW(load(R"({"cases": [{"name": "a", "scene": "x.json", "solvers": ["iisph"], "expect_stop": ["wcsph"],
                        "why": "w"}]})"),
               SceneError);
  EXPECT_THROW(load(R"({"cases": [{"name": "a", "scene": "x.json", "expect_stop": ["sph"], "why": "w"}]})"),
               SceneError);
  EXPECT_NO_THROW(load(R"({"cases": [{"name": "a", "scene": "x.json", "expect_stop": ["wcsph"], "why": "w"}]})"));
  std::filesystem::remove(tmp);
}

// The judgement itself, on short runs: a stop nobody declared fails, a declared stop
// that does not come fails, and a known limit that fails is a failure.
TEST(HardCases, OutcomeIsJudgedHonestly) {
  analysis::HardCase c = find_case("dam_break_cfl1");
  c.short_set.push_back("time.duration=0.05");
  c.known_limit = false;
  c.expect_stop = {SolverType::IISPH};
  c.why = "test";
  analysis::CaseResult r = analysis::run_case(c, kDir, SolverType::IISPH, /*quick=*/true);
  print(r);
  EXPECT_EQ(result(r), "failed");
  EXPECT_NE(r.outcome.find("expected to stop but held"), std::string::npos) << r.outcome;

  // WCSPH far too soft to carry the column: the detector stops it at the bound.
  c.short_set.push_back("time.duration=0.3");
  c.wcsph_set.push_back("solver.stiffness=1e2");
  c.expect_stop = {};
  r = analysis::run_case(c, kDir, SolverType::WCSPH, /*quick=*/true);
  print(r);
  EXPECT_EQ(result(r), "failed");
  EXPECT_EQ(r.outcome.rfind("FAILED: stopped by the detector: ", 0), 0u) << r.outcome;

  c.known_limit = true;
  r = analysis::run_case(c, kDir, SolverType::WCSPH, /*quick=*/true);
  EXPECT_EQ(result(r), "failed");
  EXPECT_EQ(r.outcome.rfind("FAILED (known limit): ", 0), 0u) << r.outcome;

  c.expect_stop = {SolverType::WCSPH};
  r = analysis::run_case(c, kDir, SolverType::WCSPH, /*quick=*/true);
  EXPECT_EQ(result(r), "expected_stop");
  EXPECT_EQ(r.outcome.rfind("expected stop: ", 0), 0u) << r.outcome;
}

class HardCaseShort : public ::testing::TestWithParam<Run> {};

TEST_P(HardCaseShort, MeetsItsCriteria) {
  const analysis::HardCase c = find_case(GetParam().name);
  const SolverType s = GetParam().solver;
  const analysis::CaseResult r = analysis::run_case(c, kDir, s, /*quick=*/true);
  print(r);
  EXPECT_EQ(result(r), c.expects_stop(s) ? "expected_stop" : "held") << r.name << " " << r.solver << ": " << r.outcome;
}

INSTANTIATE_TEST_SUITE_P(Suite, HardCaseShort, ::testing::ValuesIn(runs()),
                         [](const ::testing::TestParamInfo<Run>& param_info) {
                           std::string n = param_info.param.name + "_" + solver_name(param_info.param.solver);
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

}  // namespace
}  // namespace sluice
