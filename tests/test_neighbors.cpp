// Neighbour search (src/sph/neighbors.h): the spatial hash grid against the O(n m)
// reference on many point sets, pair caches, spatial order, transpose, and thread
// independence.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "sph/kernel.h"
#include "sph/neighbors.h"
#include "test_util.h"

namespace sluice {
namespace {

using Points = std::vector<Vec2>;

Points uniform_points(int n, Vec2 lo, Vec2 hi, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(lo.x(), hi.x()), uy(lo.y(), hi.y());
  Points p(static_cast<size_t>(n));
  for (auto& x : p) x = Vec2(ux(rng), uy(rng));
  return p;
}

// A few tight Gaussian clusters (many particles per cell, many empty cells).
Points clustered_points(int n, double h, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uc(-1.0, 1.0);
  std::normal_distribution<double> g(0.0, 1.5 * h);
  std::vector<Vec2> centers(5);
  for (auto& c : centers) c = Vec2(uc(rng), uc(rng));
  Points p(static_cast<size_t>(n));
  for (size_t i = 0; i < p.size(); ++i) p[i] = centers[i % centers.size()] + Vec2(g(rng), g(rng));
  return p;
}

// Lists of the grid search, each particle's neighbours sorted by index (the grid's own
// order is bucket order; the reference is sorted).
NeighborLists grid_search(const Points& query, const Points& points, const Kernel2D& k, bool exclude_self,
                          PairCache cache = {}) {
  SpatialHashGrid grid;
  grid.build(points, k.support());
  NeighborLists out;
  find_neighbors(query, grid, k, exclude_self, cache, out);
  return out;
}

// Compares grid and brute-force neighbour sets of every query point.
void expect_same_sets(const Points& query, const Points& points, double h, bool exclude_self) {
  const Kernel2D k(h);
  const NeighborLists g = grid_search(query, points, k, exclude_self);
  NeighborLists b;
  find_neighbors_brute_force(query, points, k.support(), exclude_self, b);
  ASSERT_EQ(g.offset.size(), query.size() + 1);
  ASSERT_EQ(b.offset.size(), query.size() + 1);
  size_t total = 0;
  for (Index i = 0; i < static_cast<Index>(query.size()); ++i) {
    std::vector<Index> gs(g.j.begin() + g.offset[i], g.j.begin() + g.offset[i + 1]);
    const std::vector<Index> bs(b.j.begin() + b.offset[i], b.j.begin() + b.offset[i + 1]);
    std::sort(gs.begin(), gs.end());
    ASSERT_TRUE(std::is_sorted(bs.begin(), bs.end()));
    ASSERT_EQ(gs, bs) << "query " << i << " at (" << query[i].x() << ", " << query[i].y() << ")";
    ASSERT_EQ(std::adjacent_find(gs.begin(), gs.end()), gs.end()) << "duplicate neighbour of " << i;
    total += bs.size();
  }
  EXPECT_EQ(g.pairs(), static_cast<Index>(total));
}

void expect_same_sets_both(const Points& pts, double h) {
  {
    SCOPED_TRACE("exclude_self = true");
    expect_same_sets(pts, pts, h, true);
  }
  {
    SCOPED_TRACE("exclude_self = false");
    expect_same_sets(pts, pts, h, false);
  }
}

TEST(Neighbors, GridEqualsBruteForceUniform) {
  const double h = 0.02;
  const Points p = uniform_points(3000, {0, 0}, {1, 1}, 1);
  expect_same_sets_both(p, h);
}

TEST(Neighbors, GridEqualsBruteForceClustered) {
  const double h = 0.02;
  const Points p = clustered_points(3000, h, 2);
  expect_same_sets_both(p, h);
}

TEST(Neighbors, GridEqualsBruteForceNegativeCoordinates) {
  const double h = 0.03;
  const Points p = uniform_points(2000, {-1.3, -0.9}, {-0.1, 0.2}, 3);  // crosses y = 0
  expect_same_sets_both(p, h);
}

TEST(Neighbors, GridEqualsBruteForceFarCoordinates) {
  const double h = 0.05;
  for (double c : {1e6, -1e6}) {
    SCOPED_TRACE(c);
    const Points p = uniform_points(2000, {c - 0.8, c - 0.8}, {c + 0.8, c + 0.8}, 4);
    expect_same_sets_both(p, h);
  }
  // Both far regions at once, and a mix of signs: x near +1e6, y near -1e6.
  Points mix = uniform_points(1000, {1e6 - 0.5, -1e6 - 0.5}, {1e6 + 0.5, -1e6 + 0.5}, 5);
  const Points other = uniform_points(1000, {-1e6 - 0.5, 1e6 - 0.5}, {-1e6 + 0.5, 1e6 + 0.5}, 6);
  mix.insert(mix.end(), other.begin(), other.end());
  expect_same_sets_both(mix, h);
}

// A bulk of points plus a few strays far away (a splash flung out of the tank): the
// grid boxes the bulk and keeps the strays in its outlier cell. Strays in small groups
// (so they have neighbours among themselves) and one right at the bulk's edge.
TEST(Neighbors, GridEqualsBruteForceBulkWithFarStrays) {
  const double h = 0.02;
  Points p = uniform_points(4000, {0, 0}, {2, 1}, 11);
  for (const Vec2& c : {Vec2(0.5, 40.0), Vec2(-30.0, -25.0), Vec2(2.0 + 3 * h, 0.5)}) {
    const Points group = uniform_points(3, c, c + Vec2(1.5 * h, 1.5 * h), 12);
    p.insert(p.end(), group.begin(), group.end());
  }
  SpatialHashGrid grid;
  grid.build(p, 2 * h);
  EXPECT_TRUE(grid.dense());  // the strays did not force the hashed grid
  expect_same_sets_both(p, h);
  // Many strays (more than 1% of the points) make the grid hash instead: same sets.
  Points spread = uniform_points(2000, {0, 0}, {1, 1}, 13);
  const Points far = uniform_points(100, {-500, -500}, {500, 500}, 14);
  spread.insert(spread.end(), far.begin(), far.end());
  grid.build(spread, 2 * h);
  EXPECT_FALSE(grid.dense());
  expect_same_sets_both(spread, h);
}

TEST(Neighbors, GridEqualsBruteForceCoincident) {
  const double h = 0.02;
  Points p = uniform_points(500, {0, 0}, {0.5, 0.5}, 7);
  // Groups of 2..6 particles at exactly the same position.
  for (int g = 0; g < 40; ++g)
    for (int c = 0; c < 2 + g % 5; ++c) p.push_back(p[static_cast<size_t>(g * 7)]);
  expect_same_sets_both(p, h);
  // All at one point: each sees every other one.
  const Points same(50, Vec2(0.123, -4.56));
  const Kernel2D k(h);
  const NeighborLists g = grid_search(same, same, k, true);
  for (Index i = 0; i < 50; ++i) EXPECT_EQ(g.count(i), 49);
  const NeighborLists g2 = grid_search(same, same, k, false);
  for (Index i = 0; i < 50; ++i) EXPECT_EQ(g2.count(i), 50);
}

TEST(Neighbors, ExactSupportDistanceIsExcluded) {
  // h = 2.5: 2h = 5 and the 3-4-5 triangle are exact in binary, so these distances are
  // exactly 2h.
  const double h = 2.5;
  const Points p = {{0, 0}, {5, 0}, {0, -5}, {3, 4}, {std::nextafter(5.0, 0.0), 30.0}, {0, 30.0}, {-5, 30.0}};
  const Kernel2D k(h);
  const NeighborLists g = grid_search(p, p, k, true);
  auto set_of = [&](Index i) {
    std::set<Index> s(g.j.begin() + g.offset[i], g.j.begin() + g.offset[i + 1]);
    return s;
  };
  EXPECT_EQ(set_of(0), (std::set<Index>{}));   // (5,0), (0,-5), (3,4) all at exactly 2h
  EXPECT_EQ(set_of(1), (std::set<Index>{3}));  // |(5,0) - (3,4)| = sqrt(20) < 5
  EXPECT_EQ(set_of(2), (std::set<Index>{}));
  EXPECT_EQ(set_of(3), (std::set<Index>{1}));
  EXPECT_EQ(set_of(5), (std::set<Index>{4}));  // 2h minus one ulp is inside; (-5,30) is at 2h
  EXPECT_EQ(set_of(4), (std::set<Index>{5}));
  EXPECT_EQ(set_of(6), (std::set<Index>{}));
  expect_same_sets_both(p, h);

  // The same on a lattice of a non-binary spacing: points of a lattice with pitch 2h
  // (every neighbour at distance ~2h, some just below, some just above by round-off),
  // compared against the reference that uses the same comparison.
  for (double hh : {0.02, 0.01, 0.0039}) {
    SCOPED_TRACE(hh);
    Points l;
    for (int a = -20; a < 20; ++a)
      for (int b = -20; b < 20; ++b) l.emplace_back(a * 2 * hh + 0.1, b * 2 * hh - 0.3);
    expect_same_sets_both(l, hh);
  }
}

// Regression: the committed grid (acbc771) binned a point with floor(x * (1 / cell));
// rounding could put a point lying on (or an ulp past) a cell edge into the cell before
// it while a partner just under 2h away landed beyond the searched block, so that pair
// was missed. Physically negligible (W and grad W vanish like (2 - q)^2 there), but the
// grid must equal the brute-force search, which the rest of this file relies on.
TEST(Neighbors, PointsOnCellBoundaries) {
  // Coordinates at or a few ulps around multiples of h (edges of cells of size h or 2h),
  // each paired with points just under one support radius 2h away along x and y.
  for (double h : {0.02, 0.01, 0.05, 0.0039, 0.03}) {
    for (double base : {0.0, 1e3, -1e6}) {
      SCOPED_TRACE(::testing::Message() << "h = " << h << ", base = " << base);
      const double r = 2.0 * h;
      std::mt19937_64 rng(11);
      std::uniform_int_distribution<int> ui(-400, 400), ul(-4, 4);
      Points p;
      for (int n = 0; n < 600; ++n) {
        const double pitch = (n % 2 ? 2.0 : 1.0) * h;  // edges of cells of size h and 2h
        double x = base + ui(rng) * pitch, y = ui(rng) * pitch;
        for (int s = ul(rng); s != 0; s += (s > 0 ? -1 : 1)) x = std::nextafter(x, s > 0 ? INFINITY : -INFINITY);
        p.emplace_back(x, y);
        p.emplace_back(x + r * (1.0 - 1e-15), y);
        p.emplace_back(std::nextafter(x + r, -INFINITY), y);
        p.emplace_back(x, std::nextafter(y + r, -INFINITY));
      }
      expect_same_sets_both(p, h);
    }
  }
}

// Regression for the rounding above: pairs found by scanning cell edges, each at a
// distance just under 2h (q = 2 - 7e-15), where x * (1/cell) rounded the lower point down
// into the previous cell and the upper one up onto the next cell edge (missed by both the
// committed hashed grid and the first version of the dense grid).
TEST(Neighbors, PairJustInsideSupportAcrossCellEdges) {
  struct Case {
    double h, x0, x1;
  };
  const Case cases[] = {
      {0.05, 0x1.9999999999999p+3, 0x1.9ccccccccccccp+3},    // 12.799999999999999, 12.899999999999999
      {0.03, 0x1.eb851eb851eb7p+10, 0x1.eb88f5c28f5c1p+10},  // 1966.0799999999997, 1966.1399999999996
      {0.03, 0x1.eb83333333332p+10, 0x1.eb870a3d70a3cp+10},  // 1966.0499999999997, 1966.1099999999997
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(::testing::Message() << "h = " << c.h << ", x0 = " << c.x0 << ", x1 = " << c.x1);
    const Kernel2D k(c.h);
    const Points p = {{c.x0, 0.5}, {c.x1, 0.5}};
    ASSERT_LT((p[1] - p[0]).squaredNorm(), k.support() * k.support());  // a neighbour by definition
    const NeighborLists g = grid_search(p, p, k, true);
    EXPECT_EQ(g.count(0), 1);
    EXPECT_EQ(g.count(1), 1);
  }
}

TEST(Neighbors, EmptyAndSinglePoint) {
  const double h = 0.02;
  const Kernel2D k(h);
  const Points none;
  NeighborLists g = grid_search(none, none, k, true, {true, true});
  ASSERT_EQ(g.offset.size(), 1u);
  EXPECT_EQ(g.pairs(), 0);
  NeighborLists b;
  find_neighbors_brute_force(none, none, k.support(), true, b);
  EXPECT_EQ(b.offset.size(), 1u);
  EXPECT_EQ(b.pairs(), 0);

  const Points one = {{0.5, -0.25}};
  g = grid_search(one, one, k, true);
  ASSERT_EQ(g.offset.size(), 2u);
  EXPECT_EQ(g.count(0), 0);
  g = grid_search(one, one, k, false);
  ASSERT_EQ(g.count(0), 1);
  EXPECT_EQ(g.j[0], 0);
  expect_same_sets_both(one, h);

  // Query points against an empty grid, and no query against a filled grid.
  g = grid_search(one, none, k, false);
  ASSERT_EQ(g.offset.size(), 2u);
  EXPECT_EQ(g.count(0), 0);
  g = grid_search(none, one, k, false);
  EXPECT_EQ(g.offset.size(), 1u);
  EXPECT_EQ(g.pairs(), 0);
}

TEST(Neighbors, QuerySetDifferentFromPoints) {
  const double h = 0.025;
  // A fluid-like query set against a boundary-like point set (a ring of samples).
  const Points q = uniform_points(2000, {-0.6, -0.6}, {0.6, 0.6}, 8);
  Points ring;
  for (int layer = 0; layer < 2; ++layer)
    for (int a = 0; a < 300; ++a) {
      const double t = 2 * M_PI * a / 300, r = 0.5 + layer * h;
      ring.emplace_back(r * std::cos(t), r * std::sin(t));
    }
  expect_same_sets(q, ring, h, false);
  expect_same_sets(ring, q, h, false);
  // Different sizes and exclude_self: index i of the query set is skipped in the point set.
  expect_same_sets(q, ring, h, true);
}

// Walls queried by every fluid particle (mark_reachable_cells): a query from a cell with
// no wall point within reach skips its cells at once; every list stays what it was, in
// the same order, for queries inside the box, at its edges and outside it.
TEST(Neighbors, ReachableCellsLeaveTheListsUnchanged) {
  const double h = 0.02;
  const Kernel2D k(h);
  // A box outline of two layers (enough points that the two strays fall outside the
  // 0.1 % quantiles: they sit in the outlier cell).
  Points walls;
  for (int i = 0; i <= 500; ++i)
    for (int layer = 0; layer < 2; ++layer) {
      const double t = i * 0.002, d = -layer * 0.002;
      walls.insert(walls.end(), {{t, d}, {t, 1.0 - d}, {d, t}, {1.0 - d, t}});
    }
  walls.emplace_back(40.0, 40.0);
  walls.emplace_back(40.01, 40.0);
  Points query = uniform_points(3000, {-0.2, -0.2}, {1.2, 1.2}, 21);
  query.emplace_back(40.005, 40.0);  // among the strays
  query.emplace_back(-7.0, 3.0);     // far outside the box
  SpatialHashGrid plain, marked;
  plain.build(walls, k.support(), 1024.0);
  marked.build(walls, k.support(), 1024.0);
  marked.mark_reachable_cells();
  ASSERT_TRUE(marked.dense());
  NeighborLists a, b;
  find_neighbors(query, plain, k, false, {}, a);
  find_neighbors(query, marked, k, false, {}, b);
  EXPECT_EQ(a.offset, b.offset);
  EXPECT_EQ(a.j, b.j);
  Index skipped_inside = 0;  // queries inside the tank, away from the walls, with no pairs
  for (Index i = 0; i < static_cast<Index>(query.size()); ++i)
    skipped_inside +=
        query[i].x() > 0.2 && query[i].x() < 0.8 && query[i].y() > 0.2 && query[i].y() < 0.8 && a.count(i) == 0;
  EXPECT_GT(skipped_inside, 0);
  expect_same_sets(query, walls, h, false);
}

TEST(Neighbors, PairCacheMatchesKernel) {
  const double h = 0.02;
  const Kernel2D k(h);
  const Points p = uniform_points(2000, {0, 0}, {0.6, 0.6}, 9);
  const Points q = uniform_points(500, {0.1, 0.1}, {0.5, 0.5}, 10);
  for (bool self : {true, false}) {
    const Points& query = self ? p : q;
    const NeighborLists g = grid_search(query, p, k, self, {.grad = true, .w = true});
    ASSERT_EQ(g.grad.size(), static_cast<size_t>(g.pairs()));
    ASSERT_EQ(g.w.size(), static_cast<size_t>(g.pairs()));
    ASSERT_GT(g.pairs(), 0);
    // Cached values may be computed by an optimised formula (e.g. from |r|^2), so allow
    // a few ulps of the kernel's scale: 1e-12 of W(0); gradients are stored in single
    // precision: 1e-7 of max |grad W| (~1.4/h^3), a few float ulps.
    const double wtol = 1e-12 * k.W(0.0), gtol = 1e-7 * 1.5 / (h * h * h);
    for (Index i = 0; i < static_cast<Index>(query.size()); ++i)
      for (Index e = g.offset[i]; e < g.offset[i + 1]; ++e) {
        const Vec2 r = query[i] - p[g.j[e]];
        ASSERT_NEAR(g.w[e], k.W(r), wtol);
        ASSERT_LE((g.grad[e].cast<double>() - k.gradW(r)).norm(), gtol);
      }
    // fill_pair_cache on the reference lists gives the same values.
    NeighborLists b;
    find_neighbors_brute_force(query, p, k.support(), self, b);
    fill_pair_cache(query, p, k, {.grad = true, .w = true}, b);
    for (Index i = 0; i < static_cast<Index>(query.size()); ++i)
      for (Index e = b.offset[i]; e < b.offset[i + 1]; ++e) {
        const Vec2 r = query[i] - p[b.j[e]];
        ASSERT_NEAR(b.w[e], k.W(r), wtol);
        ASSERT_LE((b.grad[e].cast<double>() - k.gradW(r)).norm(), gtol);
      }
  }
  // Only W requested: no gradients are stored.
  const NeighborLists w_only = grid_search(p, p, k, true, {.grad = false, .w = true});
  EXPECT_EQ(w_only.w.size(), static_cast<size_t>(w_only.pairs()));
}

TEST(Neighbors, SpatialOrderIsAPermutation) {
  const double h = 0.02, cell = 2 * h;
  for (const Points& p : {uniform_points(3000, {-0.5, -0.5}, {0.5, 0.5}, 12), clustered_points(2000, h, 13),
                          uniform_points(500, {1e6, -1e6}, {1e6 + 1, -1e6 + 1}, 14), Points{}, Points{{1, 2}}}) {
    const std::vector<Index> order = spatial_order(p, cell);
    ASSERT_EQ(order.size(), p.size());
    std::vector<Index> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<Index> iota(p.size());
    std::iota(iota.begin(), iota.end(), 0);
    ASSERT_EQ(sorted, iota);
  }
}

TEST(Neighbors, SpatialOrderCellsContiguousAndStable) {
  // Points at cell centres of a lattice whose lowest point is a cell centre, so the
  // cells that spatial_order forms (relative to the lowest point) are unambiguous.
  const double cell = 0.5;  // binary-exact
  std::mt19937_64 rng(15);
  std::uniform_int_distribution<int> ui(0, 15);
  Points p;
  for (int n = 0; n < 2000; ++n) p.emplace_back(ui(rng) * cell + 0.25, ui(rng) * cell + 0.25);
  p.emplace_back(0.25, 0.25);  // make sure the lowest cell is occupied
  const std::vector<Index> order = spatial_order(p, cell);
  auto cell_of = [&](Index i) {
    return std::pair<int, int>{static_cast<int>(p[i].x() / cell), static_cast<int>(p[i].y() / cell)};
  };
  std::vector<std::pair<int, int>> runs;
  for (size_t k = 0; k < order.size(); ++k) {
    const auto c = cell_of(order[k]);
    if (k > 0 && c == cell_of(order[k - 1])) {
      ASSERT_LT(order[k - 1], order[k]) << "not stable inside a cell";
    } else {
      runs.push_back(c);
    }
  }
  // Each cell is a single run.
  std::set<std::pair<int, int>> seen(runs.begin(), runs.end());
  ASSERT_EQ(seen.size(), runs.size()) << "a cell is split into several runs";
  EXPECT_EQ(seen.size(), 256u);
  EXPECT_EQ(runs.front(), (std::pair<int, int>{0, 0}));
  // Z-order: at every level the 2^l x 2^l blocks are contiguous too.
  for (int level = 1; level <= 3; ++level) {
    std::vector<std::pair<int, int>> blocks;
    for (const auto& c : runs) {
      const std::pair<int, int> b{c.first >> level, c.second >> level};
      if (blocks.empty() || blocks.back() != b) blocks.push_back(b);
    }
    std::set<std::pair<int, int>> bs(blocks.begin(), blocks.end());
    EXPECT_EQ(bs.size(), blocks.size()) << "level " << level;
  }
}

TEST(Neighbors, TransposeNeighbors) {
  const double h = 0.02;
  const Kernel2D k(h);
  const Points fluid = uniform_points(1500, {0, 0}, {0.5, 0.5}, 16);
  Points boundary;
  for (int a = 0; a <= 60; ++a) {
    boundary.emplace_back(a * 0.01 - 0.05, -0.005);
    boundary.emplace_back(a * 0.01 - 0.05, -0.015);
  }
  const NeighborLists fb = grid_search(fluid, boundary, k, false, {.grad = true, .w = true});
  NeighborLists bf;
  const Index nb = static_cast<Index>(boundary.size());
  transpose_neighbors(fb, nb, bf);
  ASSERT_EQ(bf.offset.size(), boundary.size() + 1);
  ASSERT_EQ(bf.pairs(), fb.pairs());
  ASSERT_GT(fb.pairs(), 100);
  std::multiset<std::tuple<Index, Index, double>> a, b;
  for (Index i = 0; i < static_cast<Index>(fluid.size()); ++i)
    for (Index e = fb.offset[i]; e < fb.offset[i + 1]; ++e) a.emplace(fb.j[e], i, fb.w[e]);
  for (Index j = 0; j < nb; ++j) {
    ASSERT_TRUE(std::is_sorted(bf.j.begin() + bf.offset[j], bf.j.begin() + bf.offset[j + 1]));
    for (Index e = bf.offset[j]; e < bf.offset[j + 1]; ++e) b.emplace(j, bf.j[e], bf.w[e]);
  }
  EXPECT_EQ(a, b);
  // The transpose of the fluid->boundary lists is the boundary->fluid search.
  const NeighborLists direct = grid_search(boundary, fluid, k, false);
  for (Index j = 0; j < nb; ++j) {
    std::vector<Index> d(direct.j.begin() + direct.offset[j], direct.j.begin() + direct.offset[j + 1]);
    std::sort(d.begin(), d.end());
    const std::vector<Index> t(bf.j.begin() + bf.offset[j], bf.j.begin() + bf.offset[j + 1]);
    ASSERT_EQ(d, t) << "boundary " << j;
  }
  // Boundary particles without fluid neighbours and an empty input.
  NeighborLists empty_fb, empty_bf;
  empty_fb.offset = {0};
  transpose_neighbors(empty_fb, 3, empty_bf);
  EXPECT_EQ(empty_bf.offset, (std::vector<Index>{0, 0, 0, 0}));
}

TEST(Neighbors, SameResultForOneAndTwoThreads) {
  const double h = 0.02;
  const Kernel2D k(h);
  const Points p = clustered_points(4000, h, 17);
  NeighborLists r1, r2;
  {
    test::ThreadCount t(1);
    r1 = grid_search(p, p, k, true, {.grad = true, .w = true});
  }
  {
    test::ThreadCount t(2);
    r2 = grid_search(p, p, k, true, {.grad = true, .w = true});
  }
  EXPECT_EQ(r1.offset, r2.offset);
  EXPECT_EQ(r1.j, r2.j);  // same order, not only the same sets
  EXPECT_EQ(r1.w, r2.w);
  EXPECT_TRUE(r1.grad == r2.grad);
}

}  // namespace
}  // namespace sluice
