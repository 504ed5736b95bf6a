// The machine's reference loops of `sluice experiment parallel` (analysis/machine.h): the
// stream computes the triad it times, and the arithmetic loop runs the chains it claims,
// checked against the closed form of x <- m x + a rather than a copy of the loop.
#include <gtest/gtest.h>

#include <cmath>

#include "analysis/machine.h"

namespace sluice::analysis {
namespace {

TEST(MachineLoops, StreamComputesTheTriadOverArraysOfTheGivenSize) {
  StreamArrays arrays(std::size_t(1) << 20);
  ASSERT_EQ(arrays.a.size(), (std::size_t(1) << 20) / sizeof(double));
  stream_triad_ms(arrays, 0.5, 2, 3);
  for (std::size_t i : {std::size_t(0), std::size_t(1), std::size_t(12345), arrays.a.size() - 1})
    EXPECT_EQ(arrays.a[i], arrays.b[i] + 0.5 * arrays.c[i]) << i;
}

// Eight chains per thread, x_k(0) = 1 + 1e-3 k + thread, each stepped n times by
// x <- m x + a: x(n) = m^n x(0) + a (1 - m^n) / (1 - m). The checksum is their sum.
double closed_form(int threads, long iterations) {
  const double m = 0.9999999, a = 1e-9;
  const long n = iterations / threads;
  const double mn = std::pow(m, static_cast<double>(n));
  double sum = 0.0;
  for (int t = 0; t < threads; ++t)
    for (int k = 0; k < 8; ++k) sum += mn * (1.0 + 1e-3 * k + t) + a * (1.0 - mn) / (1.0 - m);
  return sum;
}

TEST(MachineLoops, ArithmeticChecksumIsTheClosedFormOfItsChains) {
  for (int threads : {1, 2}) {
    double checksum = 0.0;
    compute_ms(threads, 200000, &checksum);
    EXPECT_NEAR(checksum, closed_form(threads, 200000), 1e-9 * checksum) << threads << " threads";
  }
  // The iterations are split between the threads, not repeated: 2 threads at 2n run the
  // chains of 1 thread at n twice over, the second thread's starting 1 higher (each of
  // its 8 chains then ends m^n higher).
  double one = 0.0, two = 0.0;
  compute_ms(1, 100000, &one);
  compute_ms(2, 200000, &two);
  EXPECT_NEAR(two, 2 * one + 8 * std::pow(0.9999999, 100000.0), 1e-9 * two);
}

}  // namespace
}  // namespace sluice::analysis
