#include "core/shapes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <unordered_map>

namespace sluice::shapes {

namespace {

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }
Vec2 left_normal(const Vec2& d) { return Vec2(-d.y(), d.x()); }

// Uniform grid over items with a bounding box; a cell is a hash-map bucket so the grid
// costs nothing where there are no items. Items may be listed in several cells.
class CellGrid {
 public:
  explicit CellGrid(double cell) : inv_(1.0 / cell) {}

  void insert(const Vec2& lo, const Vec2& hi, Index item) {
    const auto [x0, y0] = cell_of(lo);
    const auto [x1, y1] = cell_of(hi);
    for (std::int64_t y = y0; y <= y1; ++y)
      for (std::int64_t x = x0; x <= x1; ++x) cells_[key(x, y)].push_back(item);
  }
  void insert(const Vec2& p, Index item) { insert(p, p, item); }

  // Calls f(item) for the items of the 3 x 3 cells around p; f returns true to stop.
  template <class F>
  bool any_near(const Vec2& p, F&& f) const {
    const auto [cx, cy] = cell_of(p);
    for (std::int64_t y = cy - 1; y <= cy + 1; ++y)
      for (std::int64_t x = cx - 1; x <= cx + 1; ++x) {
        const auto it = cells_.find(key(x, y));
        if (it == cells_.end()) continue;
        for (const Index item : it->second)
          if (f(item)) return true;
      }
    return false;
  }

 private:
  std::pair<std::int64_t, std::int64_t> cell_of(const Vec2& p) const {
    auto c = [&](double v) { return static_cast<std::int64_t>(std::clamp(std::floor(v * inv_), -1e15, 1e15)); };
    return {c(p.x()), c(p.y())};
  }
  static std::uint64_t key(std::int64_t x, std::int64_t y) {
    return static_cast<std::uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<std::uint64_t>(y);
  }
  double inv_;
  std::unordered_map<std::uint64_t, std::vector<Index>> cells_;
};

bool segments_cross(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const double d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  return ((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0));
}

// Collinear segments sharing a stretch of positive length (a polyline running back over
// itself): segments_cross() sees no sign change there.
bool segments_overlap(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Vec2 ab = b - a;
  if (cross(ab, c - a) != 0 || cross(ab, d - a) != 0) return false;
  const double len2 = ab.squaredNorm();
  if (!(len2 > 0)) return false;
  const double tc = (c - a).dot(ab) / len2, td = (d - a).dot(ab) / len2;
  return std::min(std::max(tc, td), 1.0) - std::max(std::min(tc, td), 0.0) > 0;
}

std::size_t segment_count(std::size_t points, bool closed) { return closed ? points : (points > 0 ? points - 1 : 0); }

// Where sample k of n lies on a segment, as a fraction of its length: k / n when uniform.
// Graded: the integral of dv / s(v) up to u is (L / (s1 - s0)) ln(s(u) / s0), so it reaches
// k / n of its total where s(u) = s0 (s1 / s0)^(k / n), i.e. at u / L = ((1 + d)^(k / n) - 1) / d.
double sample_fraction(long long k, long long n, const SegmentSpacing& spacing) {
  const double t = static_cast<double>(k) / static_cast<double>(n);
  if (spacing.start == spacing.end) return t;
  const double d = (spacing.end - spacing.start) / spacing.start;
  return std::expm1(t * std::log1p(d)) / d;
}

}  // namespace

// --- geometry helpers -------------------------------------------------------------------

double signed_area(const std::vector<Vec2>& poly) {
  double a = 0;
  for (std::size_t i = 0, n = poly.size(); i < n; ++i) a += cross(poly[i], poly[(i + 1) % n]);
  return 0.5 * a;
}

bool point_in_polygon(const std::vector<Vec2>& poly, const Vec2& p) {
  bool inside = false;
  for (std::size_t i = 0, n = poly.size(), j = n - 1; i < n; j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      inside = !inside;
  }
  return inside;
}

int self_intersection(const std::vector<Vec2>& points, bool closed) {
  const std::size_t n = points.size(), segs = segment_count(n, closed);
  for (std::size_t i = 0; i < segs; ++i)
    for (std::size_t j = i + 1; j < segs; ++j) {
      const Vec2 &a = points[i], &b = points[(i + 1) % n], &c = points[j], &d = points[(j + 1) % n];
      // Segments that share a corner (neighbours, or the first and last of a closed chain)
      // may only overlap by folding back; any other pair must neither cross nor overlap.
      const bool adjacent = j == i + 1 || (closed && i == 0 && j == segs - 1);
      if (segments_overlap(a, b, c, d) || (!adjacent && segments_cross(a, b, c, d))) return static_cast<int>(i);
    }
  return -1;
}

double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

double ellipse_perimeter(double a, double b) {
  const double h = (a - b) * (a - b) / ((a + b) * (a + b));
  return std::numbers::pi * (a + b) * (1 + 3 * h / (10 + std::sqrt(4 - 3 * h)));
}

// --- fluid ------------------------------------------------------------------------------

void FluidShape::bounding_box(Vec2& lo, Vec2& hi) const {
  switch (kind) {
    case Kind::Rectangle:
      lo = min;
      hi = max;
      return;
    case Kind::Ellipse:
      lo = center - radii;
      hi = center + radii;
      return;
    case Kind::Polygon:
      lo = hi = points.front();
      for (const Vec2& p : points) {
        lo = lo.cwiseMin(p);
        hi = hi.cwiseMax(p);
      }
      return;
  }
}

bool FluidShape::contains(const Vec2& p) const {
  switch (kind) {
    case Kind::Rectangle:
      return true;  // the lattice covers exactly [min, max]
    case Kind::Ellipse: {
      const Vec2 q = (p - center).cwiseQuotient(radii);
      return q.squaredNorm() <= 1.0;
    }
    case Kind::Polygon:
      return point_in_polygon(points, p);
  }
  return false;
}

long long lattice_count(double lo, double hi, double h) {
  const double v = (hi - lo) / h - 0.5;  // largest i with lo + (i + 0.5) h <= hi
  if (!(v >= -1e-9)) return 0;
  return static_cast<long long>(std::min(std::floor(v + 1e-9), 1e15)) + 1;  // callers reject huge counts
}

std::vector<Vec2> fill_lattice(const FluidShape& shape, double h) {
  Vec2 lo, hi;
  shape.bounding_box(lo, hi);
  const long long nx = lattice_count(lo.x(), hi.x(), h), ny = lattice_count(lo.y(), hi.y(), h);
  std::vector<Vec2> out;
  // A polygon without area (all points on one line) holds no fluid; the crossing test
  // would count lattice points on its edges as inside.
  if (shape.kind == FluidShape::Kind::Polygon && signed_area(shape.points) == 0) return out;
  if (shape.kind == FluidShape::Kind::Rectangle) out.reserve(static_cast<std::size_t>(nx * ny));
  for (long long j = 0; j < ny; ++j)
    for (long long i = 0; i < nx; ++i) {
      const Vec2 p(lo.x() + (static_cast<double>(i) + 0.5) * h, lo.y() + (static_cast<double>(j) + 0.5) * h);
      if (shape.contains(p)) out.push_back(p);
    }
  return out;
}

// --- boundaries -------------------------------------------------------------------------

std::vector<Vec2> offset_chain(const std::vector<Vec2>& points, bool closed, double distance) {
  const std::size_t n = points.size(), segs = segment_count(n, closed);
  std::vector<Vec2> normal(segs);
  for (std::size_t i = 0; i < segs; ++i) normal[i] = left_normal((points[(i + 1) % n] - points[i]).normalized());
  std::vector<Vec2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool has_prev = closed || i > 0, has_next = closed || i + 1 < n;
    const Vec2 n1 = normal[has_prev ? (i + segs - 1) % segs : i];
    const Vec2 n2 = normal[has_next ? i : i - 1];
    const Vec2 sum = n1 + n2;
    Vec2 dir = n1;
    double scale = 1.0;
    if (sum.norm() > 1e-12) {
      dir = sum.normalized();
      scale = 1.0 / std::max(dir.dot(n1), 0.25);  // miter, clamped for very sharp corners
    }
    out[i] = points[i] + distance * scale * dir;
  }
  return out;
}

double spacing_integral(double length, const SegmentSpacing& spacing) {
  const double s0 = spacing.start, s1 = spacing.end;
  if (s0 == s1) return length / s0;
  // s(u) = s0 + (s1 - s0) u / L integrates to L ln(s1 / s0) / (s1 - s0) = (L / s0) ln(1 + d) / d
  // with d = s1 / s0 - 1; log1p keeps nearly equal spacings accurate.
  const double d = (s1 - s0) / s0;
  return length / s0 * (std::log1p(d) / d);
}

void sample_chain(const std::vector<Vec2>& points, bool closed, const std::vector<SegmentSpacing>& spacing,
                  std::vector<Vec2>& out) {
  const std::size_t n = points.size(), segs = segment_count(n, closed);
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2& a = points[i];
    const Vec2 ab = points[(i + 1) % n] - a;
    const long long m = std::max(1LL, std::llround(spacing_integral(ab.norm(), spacing[i])));
    for (long long k = 0; k < m; ++k) out.push_back(a + ab * sample_fraction(k, m, spacing[i]));
  }
  if (!closed && n > 0) out.push_back(points.back());
}

void sample_ellipse(const Vec2& center, const Vec2& radii, double spacing, std::vector<Vec2>& out) {
  const double a = radii.x(), b = radii.y(), two_pi = 2 * std::numbers::pi;
  auto at = [&](double t) { return Vec2(center.x() + a * std::cos(t), center.y() + b * std::sin(t)); };
  const long long n_est = std::max(3LL, std::llround(ellipse_perimeter(a, b) / spacing));
  if (std::abs(a - b) <= 1e-12 * std::max(a, b)) {  // circle: uniform in angle is uniform in length
    for (long long k = 0; k < n_est; ++k)
      out.push_back(at(two_pi * static_cast<double>(k) / static_cast<double>(n_est)));
    return;
  }
  // Arc-length table over the parameter angle, then equal arc-length steps. 16 entries
  // per sample, at most 2^22 (32 MiB; the same table as before up to 262 144 samples):
  // linear interpolation over 1.5e-6 rad is accurate far below a sample spacing, and a
  // hostile ellipse at the sample limit no longer asks for gigabytes.
  const std::size_t table = static_cast<std::size_t>(std::max(1024LL, 16 * std::min(n_est, 1LL << 18)));
  std::vector<double> length(table + 1, 0.0);
  for (std::size_t j = 1; j <= table; ++j)
    length[j] = length[j - 1] + (at(two_pi * static_cast<double>(j) / static_cast<double>(table)) -
                                 at(two_pi * static_cast<double>(j - 1) / static_cast<double>(table)))
                                    .norm();
  const long long n = std::max(3LL, std::llround(length[table] / spacing));
  std::size_t j = 0;
  for (long long k = 0; k < n; ++k) {
    const double target = length[table] * static_cast<double>(k) / static_cast<double>(n);
    while (j + 1 < table && length[j + 1] < target) ++j;
    const double f = (target - length[j]) / (length[j + 1] - length[j]);
    out.push_back(at(two_pi * (static_cast<double>(j) + f) / static_cast<double>(table)));
  }
}

std::vector<Vec2> BoundaryShape::sample() const {
  if (kind == Kind::Points) return points;
  std::vector<Vec2> out;
  for (int k = 0; k < layers; ++k) {
    const double d = (k + surface_offset) * layer_spacing;
    if (kind != Kind::Ellipse) {
      // Layers go away from the fluid: to the right of travel when the fluid is on the left.
      sample_chain(d == 0 ? points : offset_chain(points, closed, fluid_left ? -d : d), closed, segment_spacing, out);
    } else {
      const Vec2 r = radii + Vec2::Constant(fluid_inside ? d : -d);
      if (r.minCoeff() <= 0) break;
      sample_ellipse(center, r, spacing, out);
    }
  }
  return out;
}

std::vector<std::pair<Vec2, Vec2>> BoundaryShape::curve(double max_length) const {
  if (kind == Kind::Points) return {};  // the samples are all there is; they clear the fluid themselves
  std::vector<Vec2> pts = points;
  bool loop = closed;
  if (kind == Kind::Ellipse) {
    pts.clear();
    loop = true;
    sample_ellipse(center, radii, std::min(0.25 * max_length, ellipse_perimeter(radii.x(), radii.y()) / 64), pts);
  }
  std::vector<std::pair<Vec2, Vec2>> out;
  const std::size_t n = pts.size(), segs = segment_count(n, loop);
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2 a = pts[i], ab = pts[(i + 1) % n] - a;
    const long long m = std::max(1LL, static_cast<long long>(std::ceil(ab.norm() / max_length)));
    for (long long k = 0; k < m; ++k)
      out.emplace_back(a + ab * (static_cast<double>(k) / static_cast<double>(m)),
                       a + ab * (static_cast<double>(k + 1) / static_cast<double>(m)));
  }
  return out;
}

bool BoundaryShape::on_solid_side(const Vec2& p, double extra) const {
  if (kind == Kind::Points) return false;
  if (kind == Kind::Ellipse) {
    const double q = (p - center).cwiseQuotient(radii).squaredNorm();
    return fluid_inside ? q > 1.0 : q < 1.0;
  }
  if (kind == Kind::Box) {
    const bool fluid_inside_box = fluid_left;  // the box is walked counter-clockwise
    const bool in_x = p.x() >= min.x() && p.x() <= max.x();
    if (fluid_inside_box) return !(in_x && p.y() >= min.y() && (!lid || p.y() <= max.y()));
    return p.x() > min.x() && p.x() < max.x() && p.y() > min.y() && p.y() < max.y();
  }
  if (closed) {
    const bool interior_left = signed_area(points) > 0;
    const bool fluid_inside_loop = fluid_left == interior_left;
    return point_in_polygon(points, p) != fluid_inside_loop;
  }
  // Open chain: behind a segment (within its length) or behind a corner, inside the band.
  const double band = (layers - 1 + surface_offset) * layer_spacing + extra;
  const std::size_t segs = points.size() - 1;
  auto depth = [&](std::size_t i) {  // signed distance behind the line of segment i
    const Vec2 d = (points[i + 1] - points[i]).normalized();
    const Vec2 solid = fluid_left ? Vec2(-left_normal(d)) : left_normal(d);
    return (p - points[i]).dot(solid);
  };
  for (std::size_t i = 0; i < segs; ++i) {
    const Vec2 ab = points[i + 1] - points[i];
    const double t = (p - points[i]).dot(ab) / ab.squaredNorm();
    const double h = depth(i);
    if (t >= 0 && t <= 1 && h > 0 && h <= band) return true;
  }
  for (std::size_t i = 1; i < segs; ++i)  // the wedge behind an interior corner
    if (depth(i - 1) > 0 && depth(i) > 0 && (p - points[i]).norm() <= 4 * band) return true;
  return false;
}

Index remove_covered_fluid(std::vector<Vec2>& x, std::vector<Vec2>& v, const std::vector<BoundaryShape>& boundaries,
                           const std::vector<Vec2>& samples, double h, Index* near_samples) {
  // Closer than 0.9 h to a sample, a particle starts compressed (its density overshoots
  // rho0) and is blown off the wall at the first step.
  const double r = 0.5 * h * (1 - 1e-6), rs = kMinSampleDistance * h * (1 - 1e-6), rs2 = rs * rs;
  CellGrid sample_grid(h), curve_grid(h);
  for (std::size_t i = 0; i < samples.size(); ++i) sample_grid.insert(samples[i], static_cast<Index>(i));
  std::vector<std::pair<Vec2, Vec2>> pieces;
  for (const BoundaryShape& b : boundaries) {
    const auto c = b.curve(h);
    pieces.insert(pieces.end(), c.begin(), c.end());
  }
  for (std::size_t i = 0; i < pieces.size(); ++i)
    curve_grid.insert(pieces[i].first.cwiseMin(pieces[i].second), pieces[i].first.cwiseMax(pieces[i].second),
                      static_cast<Index>(i));

  std::size_t kept = 0;
  Index near = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec2 p = x[i];
    const bool covered = std::any_of(boundaries.begin(), boundaries.end(),
                                     [&](const BoundaryShape& b) { return b.on_solid_side(p, 0.5 * h); }) ||
                         curve_grid.any_near(p, [&](Index k) {
                           return point_segment_distance(p, pieces[k].first, pieces[k].second) < r;
                         });
    const bool close =
        !covered && sample_grid.any_near(p, [&](Index k) { return (samples[k] - p).squaredNorm() < rs2; });
    near += close ? 1 : 0;
    if (covered || close) continue;
    x[kept] = x[i];
    v[kept] = v[i];
    ++kept;
  }
  const auto removed = static_cast<Index>(x.size() - kept);
  x.resize(kept);
  v.resize(kept);
  if (near_samples) *near_samples = near;
  return removed;
}

Index merge_duplicates(std::vector<Vec2>& x, std::vector<Vec2>& v, double cell, double tol) {
  CellGrid grid(cell);
  std::size_t kept = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Vec2 p = x[i];
    if (grid.any_near(p, [&](Index k) { return (x[k] - p).norm() <= tol; })) continue;
    x[kept] = p;
    v[kept] = v[i];
    grid.insert(p, static_cast<Index>(kept));
    ++kept;
  }
  const auto removed = static_cast<Index>(x.size() - kept);
  x.resize(kept);
  v.resize(kept);
  return removed;
}

}  // namespace sluice::shapes
