#pragma once
// Reference loops that show what a machine's threads can give at all, timed beside a
// solver's runs so that its parallel speed-up can be read against them (`sluice
// experiment parallel`): a memory stream over arrays larger than any cache, whose
// speed-up is what extra threads give a loop that waits on memory, and an arithmetic
// loop that touches no memory, whose speed-up is what extra cores give at best.
#include <cstddef>
#include <vector>

namespace sluice::analysis {

// Arrays of the memory stream: a = b + s c over three arrays of `bytes_each` bytes.
struct StreamArrays {
  std::vector<double> a, b, c;
  explicit StreamArrays(std::size_t bytes_each);
};

// Wall milliseconds of `passes` passes of a[i] = b[i] + s c[i] with `threads` threads
// (static schedule; the arrays are first touched by the same schedule).
double stream_triad_ms(StreamArrays& arrays, double s, int threads, int passes);

// Wall milliseconds of `iterations` rounds of eight independent multiply-add chains,
// shared out among `threads` threads (iterations / threads each, so that t threads on t
// free cores take 1/t of one thread's time). *checksum receives the sum of the chains'
// final values (it keeps the compiler from dropping the loop).
double compute_ms(int threads, long iterations, double* checksum);

}  // namespace sluice::analysis
