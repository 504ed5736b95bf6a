#pragma once
// Neighbour search (thesis appendix 7): particles binned into a uniform grid of cell
// size h (half the kernel support 2h), built by a counting sort in O(n). The grid is
// dense over the points' bounding box when that box holds few cells per point, and
// each of the five cell rows around a query is then one contiguous range of entries.
// When a few points far away blow the box up, the box covers the bulk and those points
// sit in one extra cell every query scans; when many do, cells are hashed into 2^k
// buckets. Any coordinates work, without a domain box.
#include <cmath>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace sluice {

// Neighbour lists in compressed-row form: the neighbours of particle i are
// j[offset[i] .. offset[i+1]). Order is deterministic (grid order of the points, whatever
// the thread count). Per pair, W and grad W(x_i - x_j) can be cached.
//
// The gradient is stored in single precision (computed in double, rounded once: a
// relative error below 6e-8, far under SPH's discretisation error). The pressure solve
// streams every pair twice per Jacobi iteration, and beyond the last-level cache its
// speed is the bytes per pair: 12 instead of 20 made the 1M-particle layer's step 12 %
// and the 130k dam break's 2-thread step about 20 % faster (docs/performance.md). Sums stay
// in double. grad W_ij = -grad W_ji still holds exactly (rounding is symmetric).
struct NeighborLists {
  std::vector<Index> offset;  // size n + 1
  std::vector<Index> j;
  std::vector<Vec2f> grad;  // grad W(x_i - x_j), filled when requested
  std::vector<double> w;    // W(|x_i - x_j|), filled when requested

  Index count(Index i) const { return offset[i + 1] - offset[i]; }
  Index pairs() const { return offset.empty() ? 0 : offset.back(); }

  // Per-thread scratch of find_neighbors (pairs of a contiguous chunk of queries).
  struct Chunk {
    std::vector<Index> j;  // size is capacity; the first `used` entries are valid
    size_t used = 0;
  };
  std::vector<Chunk> chunks;
};

class SpatialHashGrid {
 public:
  // Bins `points` for queries of radius up to `radius`. The points are copied in cell
  // order so that queries read memory linearly. The grid keeps a reference to `points`
  // (see points()); it is valid while they are neither moved nor destroyed.
  // The grid is dense when its box holds at most cells_per_point * n + 4096 cells (and
  // 16M at most): a grid rebuilt every step wants few cells per point, a grid built
  // once (walls that never move) may afford many for faster queries.
  void build(const std::vector<Vec2>& points, double radius, double cells_per_point = 16.0);
  const std::vector<Vec2>& points() const { return *points_; }
  // For a dense grid that many queries will find empty (walls, queried by every fluid
  // particle): marks the cells with a point within kReach cells, so that a query from an
  // unmarked cell skips its 5 x 5 cells at once. Kept until the next build. The lists do
  // not change, only their cost.
  void mark_reachable_cells();

  // Appends to out[used..] every point j != skip with |p - x_j| < radius, growing `out`
  // as needed (its size is capacity; `used` counts the valid entries); returns the new
  // count. Branch-free inner loop: every candidate is written, only hits advance.
  size_t gather_within(const Vec2& p, double radius, Index skip, std::vector<Index>& out, size_t used) const {
    if (entries_.empty()) return used;
    const double r2 = radius * radius;
    auto visit = [&](std::uint32_t begin, std::uint32_t end) {
      if (out.size() < used + (end - begin)) out.resize(2 * (used + (end - begin)) + 64);
      Index* o = out.data();
      for (std::uint32_t e = begin; e < end; ++e) {
        const Vec2& q = pos_[e];
        const double dx = p.x() - q.x(), dy = p.y() - q.y();
        const Index j = entries_[e];
        o[used] = j;
        used += static_cast<size_t>((dx * dx + dy * dy < r2) & (j != skip));
      }
    };
    const std::int64_t cx = cell_coord(p.x()), cy = cell_coord(p.y());
    if (dense_) {
      const std::int64_t qx = cx - x0_, qy = cy - y0_;
      const bool none_near =
          !reach_.empty() && qx >= 0 && qx < nx_ && qy >= 0 && qy < ny_ && !reach_[static_cast<size_t>(qy * nx_ + qx)];
      const std::int64_t c0 = std::max<std::int64_t>(cx - kReach - x0_, 0);
      const std::int64_t c1 = std::min<std::int64_t>(cx + kReach - x0_, nx_ - 1);
      const std::int64_t r0 = std::max<std::int64_t>(cy - kReach - y0_, 0);
      const std::int64_t r1 = std::min<std::int64_t>(cy + kReach - y0_, ny_ - 1);
      for (std::int64_t row = r0; !none_near && c0 <= c1 && row <= r1; ++row)
        visit(start_[row * nx_ + c0], start_[row * nx_ + c1 + 1]);
      const std::int64_t outlier_cell = nx_ * ny_;
      visit(start_[outlier_cell], start_[outlier_cell + 1]);
      return used;
    }
    for_each_bucket(cx, cy, visit);
    return used;
  }

  Index size() const { return static_cast<Index>(entries_.size()); }
  bool dense() const { return dense_; }

 private:
  static constexpr std::int64_t kReach = 2;  // cells of size radius/2 on each side

  // Hashed grid: calls visit(begin, end) once for each distinct bucket of the
  // (2 kReach + 1)^2 cells around cell (cx, cy) (two cells may share a bucket).
  template <class V>
  void for_each_bucket(std::int64_t cx, std::int64_t cy, V&& visit) const {
    constexpr int kCells = (2 * kReach + 1) * (2 * kReach + 1);
    std::uint32_t seen[kCells];
    int nseen = 0;
    for (std::int64_t dy = -kReach; dy <= kReach; ++dy) {
      for (std::int64_t dx = -kReach; dx <= kReach; ++dx) {
        const std::uint32_t b = bucket(cx + dx, cy + dy);
        bool dup = false;
        for (int s = 0; s < nseen; ++s) dup |= (seen[s] == b);
        if (dup) continue;
        seen[nseen++] = b;
        visit(start_[b], start_[b + 1]);
      }
    }
  }
  // floor(v * inv_cell_) without a libm call (baseline x86-64 has no inline floor).
  std::int64_t cell_coord(double v) const {
    const double s = v * inv_cell_;
    const auto t = static_cast<std::int64_t>(s);
    return t - (s < static_cast<double>(t));
  }
  std::uint32_t bucket(std::int64_t cx, std::int64_t cy) const {
    const std::uint64_t h = static_cast<std::uint64_t>(cx) * 73856093ULL ^ static_cast<std::uint64_t>(cy) * 19349663ULL;
    return static_cast<std::uint32_t>((h ^ (h >> 29)) & mask_);
  }

  const std::vector<Vec2>* points_ = nullptr;
  double inv_cell_ = 1.0;
  bool dense_ = false;
  std::int64_t x0_ = 0, y0_ = 0, nx_ = 0, ny_ = 0;  // dense grid: first cell and size
  size_t outliers_ = 0;                             // dense grid: points outside the box (cell nx_ * ny_)
  std::uint32_t mask_ = 0;                          // hashed grid: buckets - 1
  std::vector<std::uint32_t> start_;                // cell (or bucket) c holds entries [start_[c], start_[c+1])
  std::vector<Index> entries_;                      // point indices in cell order
  std::vector<Vec2> pos_;                           // their positions, same order
  std::vector<std::uint32_t> key_;                  // scratch: cell of each point
  std::vector<std::uint32_t> fill_;                 // scratch: next free entry of each cell
  std::vector<double> coord_;                       // scratch: coordinates for the quantile box
  std::vector<std::uint8_t> reach_;                 // dense grid: a point within kReach cells (mark_reachable_cells)
};

// Resizes a per-pair array to n, growing its capacity by an eighth more than needed. The
// pair count drifts from step to step; a vector grown from size 0 allocates exactly n,
// so each new largest count would reallocate it and fault in every page again (a
// 130k-particle step faulted in about 1.3 MB of pair gradients this way on average).
template <class T>
void resize_pairs(std::vector<T>& v, size_t n) {
  if (n > v.capacity()) {
    v.clear();
    v.reserve(n + n / 8);
  }
  v.resize(n);
}

// Options of a neighbour list build.
struct PairCache {
  bool grad = false;
  bool w = false;
};

class Kernel2D;

// Lists, for every query point i, the grid points within the kernel support.
// With exclude_self, the point with the same index is skipped (fluid against itself).
void find_neighbors(const std::vector<Vec2>& query, const SpatialHashGrid& grid, const Kernel2D& kernel,
                    bool exclude_self, PairCache cache, NeighborLists& out);

// O(n m) reference search, same output format (neighbours sorted by index).
void find_neighbors_brute_force(const std::vector<Vec2>& query, const std::vector<Vec2>& points, double radius,
                                bool exclude_self, NeighborLists& out);

// Cell-ordered permutation of points (Morton order of grid cells, stable inside a
// cell), used to reorder particle arrays for cache locality.
std::vector<Index> spatial_order(const std::vector<Vec2>& points, double cell_size);

}  // namespace sluice

namespace sluice {
// Fills lists.grad / lists.w of existing lists from the positions (used after a
// brute-force search, and by tests).
void fill_pair_cache(const std::vector<Vec2>& query, const std::vector<Vec2>& points, const Kernel2D& kernel,
                     PairCache cache, NeighborLists& lists);

// lists of boundary -> fluid pairs from fluid -> boundary pairs, keeping W and grad W.
void transpose_neighbors(const NeighborLists& fb, Index boundary_count, NeighborLists& bf);
}  // namespace sluice
