#include "analysis/machine.h"

#include <omp.h>

#include <chrono>

namespace sluice::analysis {

namespace {

double elapsed_ms(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

StreamArrays::StreamArrays(std::size_t bytes_each) {
  const std::size_t n = bytes_each / sizeof(double);
  a.resize(n);
  b.resize(n);
  c.resize(n);
  const auto count = static_cast<long>(n);
  // First touch by the same static schedule as the stream.
#pragma omp parallel for schedule(static)
  for (long i = 0; i < count; ++i) {
    a[i] = 0.0;
    b[i] = 1.0 + static_cast<double>(i % 7);
    c[i] = 0.5 * static_cast<double>(i % 3);
  }
}

double stream_triad_ms(StreamArrays& arrays, double s, int threads, int passes) {
  double* a = arrays.a.data();
  const double* b = arrays.b.data();
  const double* c = arrays.c.data();
  const auto count = static_cast<long>(arrays.a.size());
  const auto t0 = std::chrono::steady_clock::now();
  for (int p = 0; p < passes; ++p) {
#pragma omp parallel for schedule(static) num_threads(threads)
    for (long i = 0; i < count; ++i) a[i] = b[i] + s * c[i];
  }
  return elapsed_ms(t0);
}

double compute_ms(int threads, long iterations, double* checksum) {
  double total = 0.0;
  const auto t0 = std::chrono::steady_clock::now();
#pragma omp parallel num_threads(threads) reduction(+ : total)
  {
    double x[8];
    for (int k = 0; k < 8; ++k) x[k] = 1.0 + 1e-3 * k + omp_get_thread_num();
    const double m = 0.9999999, add = 1e-9;
    const long own = iterations / threads;
    for (long it = 0; it < own; ++it)
      for (int k = 0; k < 8; ++k) x[k] = x[k] * m + add;
    for (int k = 0; k < 8; ++k) total += x[k];
  }
  const double ms = elapsed_ms(t0);
  if (checksum) *checksum = total;
  return ms;
}

}  // namespace sluice::analysis
