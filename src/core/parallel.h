#pragma once
// The one parallel-for helper of the library, and reductions that give the same
// bits for any thread count: partial results over fixed blocks of indices, combined
// in block order on one thread (never float atomics or OpenMP reductions).
#include <omp.h>

#include <algorithm>
#include <atomic>
#include <utility>
#include <vector>

#include "core/types.h"

namespace sluice {

inline constexpr Index kReduceBlock = 1024;
// Particles per scheduling chunk (for_each_chunk).
inline constexpr Index kForChunk = 256;
// Loops over fewer items run on one thread. A parallel region costs a few microseconds,
// and on a machine whose cores are busy with other work every barrier can wait a whole
// time slice for a descheduled thread, which small scenes cannot amortise. Results do
// not change: the work is split the same way whatever the thread count.
inline constexpr Index kParallelMin = 2048;

// Deals the chunks [0, chunks) to the threads of a parallel region by affinity: thread t
// owns the t-th contiguous share of them and takes its own in order; a thread whose share
// is done takes what is left of the others' shares, in turn. So a thread works on the same
// particles from loop to loop and their cache lines stay on its core (with chunks dealt
// first come, first served, about half of every array moved between the cores at each
// loop), while the work of a thread that the host deschedules still moves to the other.
// Set up before the region (shares: the threads it is planned for; any other count of
// threads still runs every chunk once); every thread of the region calls run(). Which
// thread runs a chunk never changes a result where each chunk writes only its own.
class ChunkDealer {
 public:
  static constexpr int kMaxShares = 64;
  ChunkDealer(Index chunks, int shares) : shares_(std::clamp(shares, 1, kMaxShares)) {
    for (int s = 0; s < shares_; ++s) {
      share_[s].next.store(chunks * s / shares_, std::memory_order_relaxed);
      share_[s].end = chunks * (s + 1) / shares_;
    }
  }
  template <class Body>
  void run(Body&& body) {
    const int t = omp_get_thread_num();
    for (int k = 0; k < shares_; ++k) {  // its own share first, then the others' leftovers
      Share& sh = share_[(t + k) % shares_];
      for (Index c; (c = sh.next.fetch_add(1, std::memory_order_relaxed)) < sh.end;) body(c);
    }
  }

 private:
  struct alignas(64) Share {
    std::atomic<Index> next{0};
    Index end = 0;
  };
  int shares_;
  Share share_[kMaxShares];
};

// Runs body(c) once for every c in [0, chunks), in one parallel region (on one thread
// when `parallel` is false), dealt by ChunkDealer.
template <class Body>
void for_each_chunk(Index chunks, bool parallel, Body&& body) {
  const int threads = parallel ? omp_get_max_threads() : 1;
  if (threads <= 1) {
    for (Index c = 0; c < chunks; ++c) body(c);
    return;
  }
  ChunkDealer dealer(chunks, threads);
#pragma omp parallel
  dealer.run(body);
}

template <class F>
void parallel_for(Index n, F&& f) {
  for_each_chunk((n + kForChunk - 1) / kForChunk, n >= kParallelMin, [&](Index c) {
    const Index end = std::min(n, (c + 1) * kForChunk);
    for (Index i = c * kForChunk; i < end; ++i) f(i);
  });
}

// The fixed-block reduction behind the three below: each block of kReduceBlock indices is
// folded from `init` in index order (acc = fold(acc, i)), and the blocks' results are merged
// in block order on one thread (acc = merge(acc, block)): the same bits for any thread count.
template <class T, class Fold, class Merge>
T parallel_reduce(Index n, const T& init, Fold&& fold, Merge&& merge) {
  const Index blocks = (n + kReduceBlock - 1) / kReduceBlock;
  std::vector<T> partial(static_cast<size_t>(blocks), init);
  for_each_chunk(blocks, n >= kParallelMin, [&](Index b) {
    const Index end = std::min(n, (b + 1) * kReduceBlock);
    T acc = init;
    for (Index i = b * kReduceBlock; i < end; ++i) acc = fold(acc, i);
    partial[static_cast<size_t>(b)] = acc;
  });
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
