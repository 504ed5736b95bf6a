#pragma once
// The one parallel-for helper of the library, and reductions that give the same
// bits for any thread count: partial results over fixed blocks of indices, combined
// in block order on one thread (never float atomics or OpenMP reductions).
#include <omp.h>

#include <algorithm>
#include <utility>
#include <vector>

#include "core/types.h"

namespace sluice {

inline constexpr Index kReduceBlock = 1024;
// Particles per scheduling chunk. Chunks are dealt round-robin, so that both halves of
// a spatially sorted array (a dense pool and a thin spray, say) are shared by all threads.
inline constexpr Index kForChunk = 256;
// Loops over fewer items run on one thread. A parallel region costs a few microseconds,
// and on a machine whose cores are busy with other work every barrier can wait a whole
// time slice for a descheduled thread, which small scenes cannot amortise. Results do
// not change: the work is split the same way whatever the thread count.
inline constexpr Index kParallelMin = 2048;

template <class F>
void parallel_for(Index n, F&& f) {
#pragma omp parallel for schedule(dynamic, kForChunk) if (n >= kParallelMin)
  for (Index i = 0; i < n; ++i) f(i);
}

// The fixed-block reduction behind the three below: each block of kReduceBlock indices is
// folded from `init` in index order (acc = fold(acc, i)), and the blocks' results are merged
// in block order on one thread (acc = merge(acc, block)): the same bits for any thread count.
template <class T, class Fold, class Merge>
T parallel_reduce(Index n, const T& init, Fold&& fold, Merge&& merge) {
  const Index blocks = (n + kReduceBlock - 1) / kReduceBlock;
  std::vector<T> partial(static_cast<size_t>(blocks), init);
#pragma omp parallel for schedule(dynamic, 1) if (n >= kParallelMin)
  for (Index b = 0; b < blocks; ++b) {
    const Index end = std::min(n, (b + 1) * kReduceBlock);
    T acc = init;
    for (Index i = b * kReduceBlock; i < end; ++i) acc = fold(acc, i);
    partial[static_cast<size_t>(b)] = acc;
  }
  T total = init;
  for (const T& p : partial) total = merge(total, p);
  return total;
}

// Sum of f(i) over [0, n), deterministic for any thread count.
template <class F>
double parallel_sum(Index n, F&& f) {
  return parallel_reduce(
      n, 0.0, [&](double s, Index i) { return s + f(i); }, [](double a, double b) { return a + b; });
}

// Maximum of f(i) over [0, n) (`init` when n = 0); max is order-independent.
template <class F>
double parallel_max(Index n, double init, F&& f) {
  return parallel_reduce(
      n, init, [&](double m, Index i) { return std::max(m, f(i)); }, [](double a, double b) { return std::max(a, b); });
}

// Sum and maximum (0 when n = 0) of f(i) over [0, n) in one pass, f called once per index:
// the sum of parallel_sum's blocks and order, so the same bits as parallel_sum.
template <class F>
std::pair<double, double> parallel_sum_max(Index n, F&& f) {
  using SumMax = std::pair<double, double>;
  return parallel_reduce(
      n, SumMax{0.0, 0.0},
      [&](const SumMax& acc, Index i) {
        const double v = f(i);
        return SumMax{acc.first + v, std::max(acc.second, v)};
      },
      [](const SumMax& a, const SumMax& b) {
        return SumMax{a.first + b.first, std::max(a.second, b.second)};
      });
}

}  // namespace sluice
