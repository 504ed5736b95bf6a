// The machine's reference loops of `sluice experiment parallel` (analysis/machine.h): the
// stream computes what it says, and the arithmetic loop's checksum is its arithmetic.
#include <gtest/gtest.h>

#include "analysis/machine.h"

namespace sluice::analysis {
namespace {

TEST(MachineLoops, StreamComputesTheTriadOverArraysOfTheGivenSize) {
  StreamArrays arrays(std::size_t(1) << 20);
  ASSERT_EQ(arrays.a.size(), (std::size_t(1) << 20) / sizeof(double));
  EXPECT_GE(stream_triad_ms(arrays, 0.5, 2, 3), 0.0);
  for (std::size_t i : {std::size_t(0), std::size_t(1), std::size_t(12345), arrays.a.size() - 1})
    EXPECT_EQ(arrays.a[i], arrays.b[i] + 0.5 * arrays.c[i]) << i;
}

TEST(MachineLoops, ArithmeticChecksumIsTheChainsFinalValues) {
  double checksum = 0.0;
  EXPECT_GE(compute_ms(1, 1000, &checksum), 0.0);
  double expected = 0.0;
  for (int k = 0; k < 8; ++k) {
    double x = 1.0 + 1e-3 * k;
    for (int it = 0; it < 1000; ++it) x = x * 0.9999999 + 1e-9;
    expected += x;
  }
  EXPECT_NEAR(checksum, expected, 1e-12 * expected);  // near: a build may fuse the multiply-add
  double two = 0.0;  // 500 rounds on each of two threads; the second thread's chains start at 1 more
  compute_ms(2, 1000, &two);
  double expected_two = 0.0;
  for (int thread = 0; thread < 2; ++thread)
    for (int k = 0; k < 8; ++k) {
      double x = 1.0 + 1e-3 * k + thread;
      for (int it = 0; it < 500; ++it) x = x * 0.9999999 + 1e-9;
      expected_two += x;
    }
  EXPECT_NEAR(two, expected_two, 1e-12 * expected_two);
}

}  // namespace
}  // namespace sluice::analysis
