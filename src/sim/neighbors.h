#pragma once
// Neighbour search (thesis appendix 7): spatial hashing of a uniform grid with cell
// size equal to the kernel support 2h. Works for any coordinates (no domain box):
// cells are hashed into a table of 2^k buckets, built by a counting sort in O(n).
// A query visits the buckets of the 3x3 cells around a point once each (two cells
// may share a bucket) and filters candidates by distance.
#include <cmath>
#include <cstdint>
#include <vector>

#include "sim/types.h"

namespace sluice {

// Neighbour lists in compressed-row form: the neighbours of particle i are
// j[offset[i] .. offset[i+1]). Order is deterministic (bucket order, then the order
// particles had when the grid was built). Per pair, W and grad W(x_i - x_j) are cached.
struct NeighborLists {
  std::vector<Index> offset;  // size n + 1
  std::vector<Index> j;
  std::vector<Vec2> grad;     // grad W(x_i - x_j), filled when requested
  std::vector<double> w;      // W(|x_i - x_j|), filled when requested

  Index count(Index i) const { return offset[i + 1] - offset[i]; }
  Index pairs() const { return offset.empty() ? 0 : offset.back(); }
};

class SpatialHashGrid {
 public:
  // Bins `points` into cells of size `cell_size`. The points are copied in bucket
  // order so that queries read memory linearly.
  void build(const std::vector<Vec2>& points, double cell_size);

  // Calls f(j, x_j) for every point j with |p - x_j| < radius (radius <= cell size).
  template <class F>
  void for_each_within(const Vec2& p, double radius, F&& f) const {
    if (entries_.empty()) return;
    const double r2 = radius * radius;
    const std::int64_t cx = cell_coord(p.x()), cy = cell_coord(p.y());
    std::uint32_t seen[9];
    int nseen = 0;
    for (std::int64_t dy = -1; dy <= 1; ++dy) {
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        const std::uint32_t b = bucket(cx + dx, cy + dy);
        bool dup = false;
        for (int s = 0; s < nseen; ++s) dup |= (seen[s] == b);
        if (dup) continue;
        seen[nseen++] = b;
        for (std::uint32_t e = start_[b]; e < start_[b + 1]; ++e) {
          const Vec2& q = pos_[e];
          const double ddx = p.x() - q.x(), ddy = p.y() - q.y();
          if (ddx * ddx + ddy * ddy < r2) f(entries_[e], q);
        }
      }
    }
  }

  std::int64_t cell_coord(double v) const { return static_cast<std::int64_t>(std::floor(v * inv_cell_)); }
  std::uint32_t bucket(std::int64_t cx, std::int64_t cy) const {
    const std::uint64_t h = static_cast<std::uint64_t>(cx) * 73856093ULL ^ static_cast<std::uint64_t>(cy) * 19349663ULL;
    return static_cast<std::uint32_t>((h ^ (h >> 29)) & mask_);
  }
  Index size() const { return static_cast<Index>(entries_.size()); }

 private:
  double inv_cell_ = 1.0;
  std::uint32_t mask_ = 0;
  std::vector<std::uint32_t> start_;  // bucket b holds entries [start_[b], start_[b+1])
  std::vector<Index> entries_;        // point indices in bucket order
  std::vector<Vec2> pos_;             // their positions, same order
  std::vector<std::uint32_t> key_;    // scratch: bucket of each point
};

// Options of a neighbour list build.
struct PairCache {
  bool grad = false;
  bool w = false;
};

class CubicSpline2D;

// Lists, for every query point i, the grid points within the kernel support.
// With exclude_self, the point with the same index is skipped (fluid against itself).
void find_neighbors(const std::vector<Vec2>& query, const SpatialHashGrid& grid,
                    const CubicSpline2D& kernel, bool exclude_self, PairCache cache,
                    NeighborLists& out);

// O(n m) reference search, same output format (neighbours sorted by index).
void find_neighbors_brute_force(const std::vector<Vec2>& query, const std::vector<Vec2>& points,
                                double radius, bool exclude_self, NeighborLists& out);

// Cell-ordered permutation of points (Morton order of grid cells, stable inside a
// cell), used to reorder particle arrays for cache locality.
std::vector<Index> spatial_order(const std::vector<Vec2>& points, double cell_size);

}  // namespace sluice

namespace sluice {
// Fills lists.grad / lists.w of existing lists from the positions (used after a
// brute-force search, and by tests).
void fill_pair_cache(const std::vector<Vec2>& query, const std::vector<Vec2>& points,
                     const CubicSpline2D& kernel, PairCache cache, NeighborLists& lists);

// lists of boundary -> fluid pairs from fluid -> boundary pairs, keeping W.
void transpose_neighbors(const NeighborLists& fb, Index boundary_count, NeighborLists& bf);
}  // namespace sluice
