#include "sph/neighbors.h"

#include <algorithm>
#include <bit>
#include <numeric>

#include <omp.h>

#include "core/parallel.h"
#include "sph/kernel.h"

namespace sluice {

void SpatialHashGrid::build(const std::vector<Vec2>& points, double radius, double cells_per_point) {
  const size_t n = points.size();
  points_ = &points;
  reach_.clear();
  const bool parallel = n >= static_cast<size_t>(kParallelMin);
  // Cells slightly larger than radius / kReach: x * inv_cell_ is rounded, and two points
  // closer than `radius` must never land kReach + 1 cells apart (e.g. 12.8 and 12.9 with
  // radius 0.1: 255.99999999999997 and 258 after scaling by 20).
  inv_cell_ = static_cast<double>(kReach) / (radius * (1.0 + 1e-6));
  key_.resize(n);
  std::uint32_t cells = 0;  // buckets of the counting sort
  dense_ = false;
  const double budget = std::min(cells_per_point * static_cast<double>(n) + 4096.0, 16777216.0);
  // Sets a dense box over [lo, hi] when it fits the budget.
  auto fit_box = [&](double minx, double maxx, double miny, double maxy) {
    x0_ = cell_coord(minx);
    y0_ = cell_coord(miny);
    const double nx = static_cast<double>(cell_coord(maxx) - x0_ + 1),
                 ny = static_cast<double>(cell_coord(maxy) - y0_ + 1);
    if (!(nx * ny <= budget)) return false;
    nx_ = static_cast<std::int64_t>(nx);
    ny_ = static_cast<std::int64_t>(ny);
    return true;
  };
  if (n > 0) {
    // Minima and maxima are exact: the same box for any thread count.
    double minx = points[0].x(), maxx = minx, miny = points[0].y(), maxy = miny;
    // clang-format off
#pragma omp parallel for reduction(min : minx, miny) reduction(max : maxx, maxy) if (parallel)
    // clang-format on
    for (size_t i = 0; i < n; ++i) {
      minx = std::min(minx, points[i].x());
      maxx = std::max(maxx, points[i].x());
      miny = std::min(miny, points[i].y());
      maxy = std::max(maxy, points[i].y());
    }
    dense_ = fit_box(minx, maxx, miny, maxy);
    if (!dense_ && n >= 64) {
      // A few points flung far away make the box huge: box the 0.1% to 99.9% quantiles
      // of each coordinate instead (plus a margin) and keep the points outside it in one
      // extra "outlier" cell that every query scans.
      const size_t k = n / 1000;
      auto quantiles = [&](int axis, double& lo, double& hi) {
        std::vector<double>& c = coord_;
        c.resize(n);
        for (size_t i = 0; i < n; ++i) c[i] = points[i][axis];
        std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(k), c.end());
        lo = c[k];
        std::nth_element(c.begin(), c.begin() + static_cast<std::ptrdiff_t>(n - 1 - k), c.end());
        hi = c[n - 1 - k];
      };
      double lx, hx, ly, hy;
      quantiles(0, lx, hx);
      quantiles(1, ly, hy);
      const double margin = 4.0 / inv_cell_;
      dense_ = fit_box(lx - margin, hx + margin, ly - margin, hy + margin);
    }
  }
  if (dense_) {
    cells = static_cast<std::uint32_t>(nx_ * ny_);
    size_t outliers = 0;
#pragma omp parallel for reduction(+ : outliers) if (parallel)
    for (size_t i = 0; i < n; ++i) {
      const std::int64_t cx = cell_coord(points[i].x()) - x0_, cy = cell_coord(points[i].y()) - y0_;
      const bool inside = cx >= 0 && cx < nx_ && cy >= 0 && cy < ny_;
      key_[i] = inside ? static_cast<std::uint32_t>(cy * nx_ + cx) : cells;
      outliers += !inside;
    }
    outliers_ = outliers;
    if (outliers_ > n / 100 + 16)
      dense_ = false;  // too many: hash instead
    else
      ++cells;  // the outlier cell
  }
  if (!dense_) {
    cells = std::bit_ceil(static_cast<std::uint32_t>(std::max<size_t>(2 * n, 64)));
    mask_ = cells - 1;
#pragma omp parallel for if (parallel)
    for (size_t i = 0; i < n; ++i) key_[i] = bucket(cell_coord(points[i].x()), cell_coord(points[i].y()));
  }
  // Counting sort by cell: serial, O(n), deterministic.
  start_.assign(static_cast<size_t>(cells) + 1, 0);
  for (size_t i = 0; i < n; ++i) ++start_[key_[i] + 1];
  for (std::uint32_t c = 0; c < cells; ++c) start_[c + 1] += start_[c];
  entries_.resize(n);
  pos_.resize(n);
  fill_.assign(start_.begin(), start_.end() - 1);
  for (size_t i = 0; i < n; ++i) {
    const std::uint32_t e = fill_[key_[i]]++;
    entries_[e] = static_cast<Index>(i);
    pos_[e] = points[i];
  }
}

void SpatialHashGrid::mark_reachable_cells() {
  reach_.clear();
  if (!dense_) return;
  const size_t cells = static_cast<size_t>(nx_ * ny_);
  // Dilate the occupied cells by kReach along x, then along y.
  std::vector<std::uint8_t> along_x(cells, 0);
  for (std::int64_t y = 0; y < ny_; ++y)
    for (std::int64_t x = 0; x < nx_; ++x) {
      const std::int64_t c = y * nx_ + x;
      if (start_[c + 1] == start_[c]) continue;
      for (std::int64_t d = std::max<std::int64_t>(x - kReach, 0); d <= std::min(x + kReach, nx_ - 1); ++d)
        along_x[static_cast<size_t>(y * nx_ + d)] = 1;
    }
  reach_.assign(cells, 0);
  for (std::int64_t y = 0; y < ny_; ++y)
    for (std::int64_t x = 0; x < nx_; ++x) {
      if (!along_x[static_cast<size_t>(y * nx_ + x)]) continue;
      for (std::int64_t d = std::max<std::int64_t>(y - kReach, 0); d <= std::min(y + kReach, ny_ - 1); ++d)
        reach_[static_cast<size_t>(d * nx_ + x)] = 1;
    }
}

// One query per particle: each thread lists the pairs of a contiguous chunk of queries
// into its own buffer; the chunks are then copied into place after a prefix sum. The
// result does not depend on the number of threads.
void find_neighbors(const std::vector<Vec2>& query, const SpatialHashGrid& grid, const Kernel2D& kernel,
                    bool exclude_self, PairCache cache, NeighborLists& out) {
  const Index n = static_cast<Index>(query.size());
  const double radius = kernel.support();
  out.offset.resize(static_cast<size_t>(n) + 1);
  out.offset[0] = 0;
  // More chunks than threads, so that threads finish together (for_each_chunk: a chunk and
  // its buffer mostly stay with one thread from step to step); the output does not depend
  // on the chunking.
  const int nchunks = static_cast<int>(std::clamp<Index>(n / 512, 1, 8 * omp_get_max_threads()));
  out.chunks.resize(static_cast<size_t>(nchunks));
  auto chunk_begin = [&](Index c) { return static_cast<Index>(static_cast<long long>(n) * c / nchunks); };
  for_each_chunk(nchunks, n >= kParallelMin, [&](Index c) {
    NeighborLists::Chunk& buf = out.chunks[static_cast<size_t>(c)];
    size_t used = 0;
    for (Index i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
      const size_t before = used;
      used = grid.gather_within(query[i], radius, exclude_self ? i : Index(-1), buf.j, used);
      out.offset[i + 1] = static_cast<Index>(used - before);
    }
    buf.used = used;
  });
  for (Index i = 0; i < n; ++i) out.offset[i + 1] += out.offset[i];
  resize_pairs(out.j, static_cast<size_t>(out.offset[n]));
  for_each_chunk(nchunks, n >= kParallelMin, [&](Index c) {
    const NeighborLists::Chunk& buf = out.chunks[static_cast<size_t>(c)];
    std::copy_n(buf.j.begin(), buf.used, out.j.begin() + out.offset[chunk_begin(c)]);
  });
  fill_pair_cache(query, grid.points(), kernel, cache, out);
}

void find_neighbors_brute_force(const std::vector<Vec2>& query, const std::vector<Vec2>& points, double radius,
                                bool exclude_self, NeighborLists& out) {
  const Index n = static_cast<Index>(query.size());
  const Index m = static_cast<Index>(points.size());
  const double r2 = radius * radius;
  out.offset.assign(static_cast<size_t>(n) + 1, 0);
  out.j.clear();
  out.grad.clear();
  out.w.clear();
  for (Index i = 0; i < n; ++i) {
    for (Index j = 0; j < m; ++j) {
      if (exclude_self && i == j) continue;
      if ((query[i] - points[j]).squaredNorm() < r2) out.j.push_back(j);
    }
    out.offset[i + 1] = static_cast<Index>(out.j.size());
  }
}

namespace {
// Interleaves the bits of two 32-bit cell coordinates (Morton / Z-order).
std::uint64_t morton(std::uint32_t x, std::uint32_t y) {
  auto spread = [](std::uint64_t v) {
    v &= 0xffffffffULL;
    v = (v | (v << 16)) & 0x0000ffff0000ffffULL;
    v = (v | (v << 8)) & 0x00ff00ff00ff00ffULL;
    v = (v | (v << 4)) & 0x0f0f0f0f0f0f0f0fULL;
    v = (v | (v << 2)) & 0x3333333333333333ULL;
    v = (v | (v << 1)) & 0x5555555555555555ULL;
    return v;
  };
  return spread(x) | (spread(y) << 1);
}
}  // namespace

std::vector<Index> spatial_order(const std::vector<Vec2>& points, double cell_size) {
  const size_t n = points.size();
  std::vector<Index> order(n);
  std::iota(order.begin(), order.end(), 0);
  if (n == 0) return order;
  // Cell coordinates relative to the lowest occupied cell, so any coordinates work.
  double minx = points[0].x(), miny = points[0].y();
  for (const Vec2& p : points) {
    minx = std::min(minx, p.x());
    miny = std::min(miny, p.y());
  }
  std::vector<std::uint64_t> code(n);
  for (size_t i = 0; i < n; ++i) {
    const double cx = std::floor((points[i].x() - minx) / cell_size);
    const double cy = std::floor((points[i].y() - miny) / cell_size);
    const auto clampu = [](double v) { return static_cast<std::uint32_t>(std::min(v, 4294967295.0)); };
    code[i] = morton(clampu(cx), clampu(cy));
  }
  std::stable_sort(order.begin(), order.end(), [&](Index a, Index b) { return code[a] < code[b]; });
  return order;
}

}  // namespace sluice

namespace sluice {

void fill_pair_cache(const std::vector<Vec2>& query, const std::vector<Vec2>& points, const Kernel2D& kernel,
                     PairCache cache, NeighborLists& lists) {
  const Index n = static_cast<Index>(query.size());
  resize_pairs(lists.grad, cache.grad ? lists.j.size() : 0);
  resize_pairs(lists.w, cache.w ? lists.j.size() : 0);
  if (!cache.grad && !cache.w) return;
  parallel_for(n, [&](Index i) {
    for (Index k = lists.offset[i]; k < lists.offset[i + 1]; ++k) {
      const Vec2 r = query[i] - points[lists.j[k]];
      const double d = r.norm();
      if (cache.grad) lists.grad[k] = (r * kernel.dWdr_over_r(d)).cast<float>();
      if (cache.w) lists.w[k] = kernel.W(d);
    }
  });
}

void transpose_neighbors(const NeighborLists& fb, Index boundary_count, NeighborLists& bf) {
  const Index n = static_cast<Index>(fb.offset.size()) - 1;
  bf.offset.assign(static_cast<size_t>(boundary_count) + 1, 0);
  for (Index k = 0; k < fb.pairs(); ++k) ++bf.offset[fb.j[k] + 1];
  for (Index b = 0; b < boundary_count; ++b) bf.offset[b + 1] += bf.offset[b];
  resize_pairs(bf.j, static_cast<size_t>(fb.pairs()));
  resize_pairs(bf.w, static_cast<size_t>(fb.pairs()));
  resize_pairs(bf.grad, static_cast<size_t>(fb.pairs()));
  std::vector<Index> fill(bf.offset.begin(), bf.offset.end() - 1);
  // Serial and in fluid order: deterministic, and each boundary list sorted by fluid index.
  for (Index i = 0; i < n; ++i) {
    for (Index k = fb.offset[i]; k < fb.offset[i + 1]; ++k) {
      const Index e = fill[fb.j[k]]++;
      bf.j[e] = i;
      bf.w[e] = fb.w[k];
      bf.grad[e] = -fb.grad[k];  // grad W(x_b - x_f)
    }
  }
}

}  // namespace sluice
