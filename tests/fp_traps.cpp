// Floating-point exceptions (invalid, divide by zero, overflow) trap in every test but
// those of the suites listed below: a NaN or Inf born anywhere in a step stops the test
// with SIGFPE at the line that made it, instead of surfacing later as a failed
// comparison (or not at all).
// The traps are per thread, so they are set in every OpenMP worker too (the pool's
// threads persist between parallel regions). Linked into every test binary
// (CMakeLists.txt).
#include <fenv.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <string>

namespace {

// Suites that run without traps, each for its reason. Every other test traps, so a new
// suite is covered without being listed. Names are exact; a parametrised suite reads
// "Prefix/Suite", and is listed by the part after the slash.
constexpr const char* kWithoutTraps[] = {
    // The test that an opted-out suite runs without traps (tests/test_fp_traps.cpp).
    "FloatingPointTrapsElsewhere",
    // The parser's error tests overflow on purpose: a sample file's "1e999" (strtod
    // overflows to Inf, refused as "not a finite point"), and finite coordinates near
    // the range of double whose offset layers overflow in shapes::offset_chain (refused
    // instead of sampled at infinity).
    "SamplingErrors",
    "SceneLimits",
    // The renderer's tests that draw in this process: Mesa's llvmpipe (swrast_dri.so) is
    // not ours, and traps (SIGFPE) inside its rasteriser.
    "RenderGolden",
    "RenderLayout",
    "RenderOptions",
};

bool traps_wanted(const ::testing::TestInfo& test) {
  std::string suite = test.test_suite_name();
  if (const auto slash = suite.find('/'); slash != std::string::npos) suite = suite.substr(slash + 1);
  for (const char* name : kWithoutTraps)
    if (suite == name) return false;
  return true;
}

void set_traps(bool on) {
  constexpr int kTraps = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;
#pragma omp parallel
  {
    feclearexcept(FE_ALL_EXCEPT);
    if (on)
      feenableexcept(kTraps);
    else
      fedisableexcept(kTraps);
  }
}

class FloatingPointTraps : public ::testing::EmptyTestEventListener {
  void OnTestStart(const ::testing::TestInfo& test) override {
    if (traps_wanted(test)) set_traps(true);
  }
  void OnTestEnd(const ::testing::TestInfo&) override { set_traps(false); }
};

// Registered before RUN_ALL_TESTS (gtest_main) starts: listeners added at static
// initialisation take part in the whole run.
const bool registered = [] {
  ::testing::UnitTest::GetInstance()->listeners().Append(new FloatingPointTraps);
  return true;
}();

}  // namespace
