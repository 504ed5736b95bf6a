#include "solver/simulation.h"

#include <omp.h>
#include <algorithm>
#include <cstdint>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure_kernels.h"

namespace sluice {

namespace {

// Particles per block of the fused Jacobi sweep (see jacobi_sweep): a block's pairs
// (about 2 MB at 16384) stay in cache until its updates read them again.
constexpr Index kSweepBlock = 16384;
// An update waits for at most this many blocks after its own; particles with a
// neighbour further ahead are deferred.
constexpr int kMaxSweepLag = 2;
// The fused sweep is used when the iteration's arrays exceed this many bytes, three
// quarters of the 32 MB L3 of the machine it was measured on (see jacobi_block_size).
// Elsewhere the crossover moves with the cache; either way the bits are the same.
constexpr double kFuseAboveBytes = 24.0 * 1024 * 1024;

}  // namespace

// The fused Jacobi sweep pays only when the solver's arrays crowd the last-level cache;
// well inside it, the two plain passes are as fast or faster (docs/performance.md,
// "Design decisions of the solve", has the measurements). Returns the block size, 0 for
// the two plain passes.
Index Simulation::jacobi_block_size() const {
  if (jacobi_block_ != 0) return std::max<Index>(jacobi_block_, 0);
  // Bytes the iteration streams: 12 per fluid pair (index and float gradient) and about
  // 160 per particle (pressures, accelerations, source, diagonal, boundary sums).
  const double bytes = 12.0 * static_cast<double>(ff_.pairs()) + 160.0 * fluid_.size();
  return bytes < kFuseAboveBytes ? 0 : kSweepBlock;
}

// The schedule of this step's Jacobi sweeps: the block size (0: two plain passes) and,
// for the fused sweep, its ranges, each particle's lag (sweep_lag_of) and the deferred
// particles. Only the speed depends on it, never the bits.
Index Simulation::plan_jacobi_sweep() {
  const Index block = jacobi_block_size();
  scratch_->deferred.clear();
  if (block == 0) return 0;
  const Index n = fluid_.size();
  plan_jacobi_ranges();
  SLUICE_ASSERT(scratch_->sweep_range.front() == 0 && scratch_->sweep_range.back() == n &&
                    std::is_sorted(scratch_->sweep_range.begin(), scratch_->sweep_range.end()),
                "the sweep's ranges cover the particles in order");
  scratch_->sweep_lag.resize(n);
  parallel_for(n, [&](Index i) {
    Index jmin = i, jmax = i;
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      jmin = std::min(jmin, ff_.j[k]);
      jmax = std::max(jmax, ff_.j[k]);
    }
    scratch_->sweep_lag[i] = sweep_lag_of(i, jmin, jmax, block);
  });
  for (Index i = 0; i < n; ++i)
    if (scratch_->sweep_lag[i] < 0) scratch_->deferred.push_back(i);
  return block;
}

// Ranges of the fused sweep: one contiguous index range per thread, cut so that each
// holds about the same work (fluid pairs, plus 4 per particle for the per-particle part).
void Simulation::plan_jacobi_ranges() {
  const Index n = fluid_.size();
  const Index ranges = jacobi_ranges_ > 0 ? jacobi_ranges_ : static_cast<Index>(omp_get_max_threads());
  auto work = [&](Index i) { return static_cast<double>(ff_.offset[i]) + 4.0 * i; };
  const double total = work(n);
  std::vector<Index>& range = scratch_->sweep_range;
  range.assign(static_cast<size_t>(ranges) + 1, n);
  range[0] = 0;
  for (Index r = 1; r < ranges; ++r) {
    const double target = total * r / ranges;
    Index lo = range[r - 1], hi = n;  // first i in [lo, n] with work(i) >= target
    while (lo < hi) {
      const Index mid = lo + (hi - lo) / 2;
      if (work(mid) < target)
        lo = mid + 1;
      else
        hi = mid;
    }
    range[r] = lo;
  }
}

// How many blocks after its own particle i's update must wait for in the fused sweep:
// the block of its last fluid neighbour jmax (earlier blocks of the same range are
// done by then). -1 (deferred) when a neighbour lies in another range, whose thread may
// not have computed its acceleration yet, or more than kMaxSweepLag blocks ahead, by
// when i's data have left the cache. jmin, jmax: i's smallest and largest neighbour
// index (i itself when it has none).
std::int8_t Simulation::sweep_lag_of(Index i, Index jmin, Index jmax, Index block) const {
  const std::vector<Index>& range = scratch_->sweep_range;
  const Index r = static_cast<Index>(std::upper_bound(range.begin(), range.end(), i) - range.begin()) - 1;
  const Index begin = range[r], end = range[r + 1];
  if (jmin < begin || jmax >= end) return -1;
  const Index lag = (jmax - begin) / block - (i - begin) / block;
  return lag <= kMaxSweepLag ? static_cast<std::int8_t>(std::max<Index>(lag, 0)) : std::int8_t(-1);
}

// One Jacobi iteration over all fluid particles: the accelerations of Eq. 24 from the
// current pressures, then the updates of Eq. 20, 21 and 23; returns the sum of Eq. 23.
//
// With block = 0, two plain passes. Otherwise fused: each thread sweeps its own range
// (sweep_range) block by block, computing a block's accelerations and at once updating
// the particles whose last fluid neighbour lies in that block, while their pairs and
// accelerations are still in cache; after all ranges are done, the deferred particles
// (see sweep_lag_of) are updated. The result is the same as two full passes, bit for
// bit: an update reads only accelerations, and every one it reads is computed before
// it, whatever the thread count. And no acceleration reads a pressure updated in the
// same iteration: a particle updated early has all its neighbours in its own range and
// in blocks already done (neighbour lists are symmetric).
double Simulation::jacobi_sweep(Index block, const PressureTerms& t) {
  const Index n = fluid_.size();
  if (block == 0) {
    // Two plain passes: all accelerations (and the stabilisation's means), then all
    // updates (summed as they go).
    compute_pressure_acceleration(t);
    return parallel_sum(n, [&](Index i) {
      jacobi_update_of(i, t);
      return scratch_->err[i];
    });
  }
  const std::vector<Index>& range = scratch_->sweep_range;
  const Index ranges = static_cast<Index>(range.size()) - 1;
  const Index nd = static_cast<Index>(scratch_->deferred.size());
  // Sum of Eq. 23 over fixed blocks of kReduceBlock particles, added in block order as
  // in parallel_sum: the same bits whatever the sweep's blocks, ranges and threads.
  const Index sum_blocks = (n + kReduceBlock - 1) / kReduceBlock;
  std::vector<double>& partial = scratch_->err_partial;
  partial.assign(static_cast<size_t>(sum_blocks), 0.0);
  // A thread may sweep several ranges one after the other (fewer threads than ranges):
  // a range's early updates touch no particle of another range, so that is safe too.
  // Dealt by affinity (ChunkDealer): thread r sweeps range r, iteration after iteration.
  const int threads = omp_get_max_threads();
  ChunkDealer range_dealer(ranges, threads), deferred_dealer((nd + kForChunk - 1) / kForChunk, threads),
      sum_dealer(sum_blocks, threads);
#pragma omp parallel if (n >= kParallelMin)
  {
    range_dealer.run([&](Index r) { sweep_range(range[r], range[r + 1], block, t); });
#pragma omp barrier
    deferred_dealer.run([&](Index c) {
      for (Index k = c * kForChunk; k < std::min(nd, (c + 1) * kForChunk); ++k)
        jacobi_update_of(scratch_->deferred[k], t);
    });
#pragma omp barrier
    sum_dealer.run([&](Index b) {
      const Index end = std::min(n, (b + 1) * kReduceBlock);
      double sum = 0.0;
      for (Index i = b * kReduceBlock; i < end; ++i) sum += scratch_->err[i];
      partial[static_cast<size_t>(b)] = sum;
    });
  }
  double total = 0.0;
  for (double sum : partial) total += sum;
  return total;
}

// One range of the fused sweep, blocks in order: block c's accelerations, then the
// updates of the particles of blocks c - kMaxSweepLag .. c that waited for block c.
void Simulation::sweep_range(Index begin, Index end, Index block, const PressureTerms& t) {
  const std::vector<std::int8_t>& lag = scratch_->sweep_lag;
  // (Bounds computed so that no sum exceeds end: a block may be as large as Index allows.)
  for (Index c = begin, c_end = begin; c < end; c = c_end) {
    c_end = end - c > block ? c + block : end;
    for (Index i = c; i < c_end; ++i) scratch_->a_p[i] = pressure_acceleration_of(i, t);
    for (int d = kMaxSweepLag; d >= 0; --d) {
      if (static_cast<std::int64_t>(d) * block > c - begin) continue;  // d blocks back is before the range
      const Index b0 = c - d * block, b1 = d == 0 ? c_end : b0 + block;
      for (Index i = b0; i < b1; ++i)
        if (lag[i] == d) jacobi_update_of(i, t);
    }
  }
}

// Flags `to` with the particles flagged in `from` and their fluid neighbours. The lists are
// symmetric, so spreading each flag to its neighbours gives the same set as a gather over
// every particle's list, and reads only the lists of the flagged few (next to the walls).
// Serial: a few thousand lists.
void Simulation::grow_by_neighbours(const std::vector<std::uint8_t>& from, std::vector<std::uint8_t>& to) const {
  const Index n = fluid_.size();
  to.assign(from.begin(), from.begin() + n);
  for (Index i = 0; i < n; ++i) {
    if (!from[i]) continue;
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) to[ff_.j[k]] = 1;
  }
}

// Flags the wall band: the fluid particles with a boundary neighbour and their fluid
// neighbours (`wall` is scratch: those with a boundary neighbour).
void Simulation::mark_wall_band(std::vector<std::uint8_t>& band, std::vector<std::uint8_t>& wall) const {
  const Index n = fluid_.size();
  wall.resize(static_cast<size_t>(n));
  parallel_for(n, [&](Index i) { wall[i] = fb_.count(i) > 0; });
  grow_by_neighbours(wall, band);
}

// This step's wall band (mark_wall_band) as flags: the stabilisation's rows when it is on,
// which prepare_stabilisation marked at the step's set-up, else marked here into
// wall_flag_b. (Flag arrays are kept between steps: fresh ones would be faulted in every
// step.)
const std::vector<std::uint8_t>& Simulation::wall_band_flags() {
  if (stabilisation_kappa(settings_) > 0.0) {
    SLUICE_ASSERT(scratch_->stab_on.size() == static_cast<size_t>(fluid_.size()), "the stabilisation's band is marked");
    return scratch_->stab_on;
  }
  mark_wall_band(scratch_->wall_flag_b, scratch_->wall_flag_a);
  return scratch_->wall_flag_b;
}

// The band of smooth_wall_band (wall_band_flags); and the reach, the band with its fluid
// neighbours, whose accelerations the band's updates read. Both ascending. (A band one hop
// narrower moved the largest error to its edge; docs/performance.md, "Smoothing next to
// the walls".)
void Simulation::plan_wall_band() {
  const Index n = fluid_.size();
  const std::vector<std::uint8_t>& band = wall_band_flags();
  std::vector<std::uint8_t>& reach = scratch_->wall_flag_a;
  grow_by_neighbours(band, reach);
  scratch_->wall_band.clear();
  scratch_->wall_reach.clear();
  for (Index i = 0; i < n; ++i) {
    if (band[i]) scratch_->wall_band.push_back(i);
    if (reach[i]) scratch_->wall_reach.push_back(i);
  }
}

// One Jacobi iteration restricted to the band and the samples: Eq. 24 over the reach from
// the current pressures, then Eq. 20, 21, 23 for the band and Eq. 21 for the samples. Reads
// only accelerations computed before it writes, so the bits do not depend on the threads.
void Simulation::smooth_wall_band(const PressureTerms& terms) {
  PressureTerms t = terms;
  t.chebyshev = 0.0;  // plain relaxed Jacobi, whatever the scheme around it
  const std::vector<Index>& band = scratch_->wall_band;
  const std::vector<Index>& reach = scratch_->wall_reach;
  update_boundary_pressure();
  parallel_for(static_cast<Index>(reach.size()),
               [&](Index k) { scratch_->a_p[reach[k]] = pressure_acceleration_of(reach[k], t); });
  parallel_for(static_cast<Index>(band.size()), [&](Index k) { jacobi_update_of(band[k], t); });
  if (settings_.boundary_pressure == BoundaryPressure::Solved) jacobi_update_boundary(t);
}

}  // namespace sluice
