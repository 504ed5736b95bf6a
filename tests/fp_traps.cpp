// Floating-point exceptions (invalid, divide by zero, overflow) trap in the physics
// tests: a NaN or Inf born anywhere in a step stops the test with SIGFPE at the line
// that made it, instead of surfacing later as a failed comparison (or not at all).
// The traps are per thread, so they are set in every OpenMP worker too (the pool's
// threads persist between parallel regions). Not for the renderer's tests (Mesa's
// llvmpipe is not ours) nor the hard cases, whose WCSPH runs are meant to blow up until
// the detector stops them.
#include <fenv.h>
#include <gtest/gtest.h>
#include <omp.h>

#include <string>

namespace {

bool traps_wanted(const ::testing::TestInfo& test) {
  // Exact suite names: the parser's error tests (SamplingErrors, Scene*) parse "1e999"
  // on purpose. Parametrised suites read "Physics/Hydrostatic" and the like.
  const std::string suite = test.test_suite_name();
  for (const char* name : {"Physics", "PhysicsFloatingPointTraps", "Kernel", "Neighbors", "Motion", "MovingBoundaries",
                           "Sampling", "GradedSpacing", "PointSamples", "TankAtRest", "Validation"})
    if (suite == name) return true;
  return suite.rfind("Physics/", 0) == 0 || suite.rfind("Sampling/", 0) == 0;
}

void set_traps(bool on) {
  constexpr int kTraps = FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW;
#pragma omp parallel
  {
    feclearexcept(FE_ALL_EXCEPT);
    if (on) feenableexcept(kTraps);
    else fedisableexcept(kTraps);
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
