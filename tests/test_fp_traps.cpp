// The floating-point traps of tests/fp_traps.cpp: on in a test, on every OpenMP thread,
// and off in a suite that opts out.
#include <fenv.h>
#include <gtest/gtest.h>
#include <omp.h>

// The traps are on in a test, on every OpenMP thread, and off in a suite that opts out.
TEST(PhysicsFloatingPointTraps, AreOnInEveryThread) {
  int missing = 0;
#pragma omp parallel reduction(+ : missing)
  missing += (fegetexcept() & (FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW)) != (FE_INVALID | FE_DIVBYZERO | FE_OVERFLOW);
  EXPECT_EQ(missing, 0);
}

TEST(FloatingPointTrapsElsewhere, AreOff) { EXPECT_EQ(fegetexcept() & FE_INVALID, 0); }
