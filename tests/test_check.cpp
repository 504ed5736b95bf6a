// SLUICE_ASSERT (core/check.h), the channel for program invariants: compiled in here
// whatever the build type, it aborts with the condition, file:line and message; with
// asserts off it does not evaluate its arguments.
#define SLUICE_ENABLE_ASSERTS 1
#include "core/check.h"

#include <gtest/gtest.h>

namespace {

int calls = 0;
bool counted(bool value) {
  ++calls;
  return value;
}

TEST(CheckDeathTest, AFailedAssertAbortsNamingTheConditionAndTheMessage) {
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_DEATH(SLUICE_ASSERT(1 + 1 == 3, "arithmetic holds"),
               "internal error .*test_check.cpp:[0-9]+: 1 \\+ 1 == 3 failed: arithmetic holds");
}

TEST(Check, AHoldingAssertEvaluatesItsConditionOnce) {
  calls = 0;
  SLUICE_ASSERT(counted(true), "never printed");
  EXPECT_EQ(calls, 1);
}

}  // namespace
