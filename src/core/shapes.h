#pragma once
// Geometry of scene shapes: fluid blocks filled on a square lattice, boundary shapes
// sampled in layers, and the removal of fluid particles that overlap a boundary.
// No JSON here: the scene readers (src/scene) validate the input and build these plain structs.
#include <vector>

#include "core/types.h"

namespace sluice::shapes {

// --- small geometry helpers -------------------------------------------------------------

// The signed area of a closed polygon (> 0 when counter-clockwise).
double signed_area(const std::vector<Vec2>& poly);
// Crossing-number test; points exactly on an edge may go either way.
bool point_in_polygon(const std::vector<Vec2>& poly, const Vec2& p);
// Index i of a segment (points[i], points[i+1]) that properly crosses a non-adjacent
// segment of the chain, or -1 when the chain does not intersect itself.
int self_intersection(const std::vector<Vec2>& points, bool closed);
double point_segment_distance(const Vec2& p, const Vec2& a, const Vec2& b);
// Ramanujan's second approximation (exact for circles).
double ellipse_perimeter(double a, double b);

// --- fluid blocks -----------------------------------------------------------------------

struct FluidShape {
  enum class Kind { Rectangle, Ellipse, Polygon };
  Kind kind = Kind::Rectangle;
  Vec2 min{0, 0}, max{0, 0};       // rectangle
  Vec2 center{0, 0}, radii{0, 0};  // ellipse
  std::vector<Vec2> points;        // polygon
  Vec2 velocity{0, 0};

  void bounding_box(Vec2& lo, Vec2& hi) const;
  bool contains(const Vec2& p) const;
};

// Number of lattice points lo + (i + 0.5) h with centre <= hi along one axis.
long long lattice_count(double lo, double hi, double h);
// Lattice points lo + (i + 0.5, j + 0.5) * h over the shape's bounding box that lie in
// the shape (all of them for a rectangle).
std::vector<Vec2> fill_lattice(const FluidShape& shape, double h);

// --- boundaries -------------------------------------------------------------------------

// Sample spacing along one segment: it varies linearly from `start` at the segment's
// first vertex to `end` at its second; start == end is the uniform spacing.
struct SegmentSpacing {
  double start = 0, end = 0;
};

struct BoundaryShape {
  enum class Kind { Chain, Box, Ellipse, Points };
  Kind kind = Kind::Chain;
  // Chain and Box (box, polyline, polygon): vertices in travel order; closed joins the
  // last to the first. segment_spacing has one entry per segment. The fluid is on the
  // left of the direction of travel when fluid_left, and the layers go to the other side.
  // Points: `points` are the samples themselves, used as given (no curve, no layers).
  std::vector<Vec2> points;
  bool closed = false;
  std::vector<SegmentSpacing> segment_spacing;
  bool fluid_left = true;
  // Box only, for the solid-side test: the rectangle, open above without a lid.
  Vec2 min{0, 0}, max{0, 0};
  bool lid = false;
  // Ellipse (circle, ellipse): fluid inside (container) or outside (obstacle).
  Vec2 center{0, 0}, radii{0, 0};
  double spacing = 0;
  bool fluid_inside = false;

  int layers = 2;
  double layer_spacing = 0;
  // Layer k lies (k + surface_offset) * layer_spacing behind the curve. With 0.5 a
  // sample is the centre of a cell of the solid, as a fluid particle is of the fluid:
  // fluid half a spacing off the surface then sits one spacing from the first layer,
  // the spacing of the fluid lattice itself. 0 puts the first layer on the curve
  // (thin plates with fluid on both sides).
  double surface_offset = 0.5;

  // All samples, layer by layer from the surface into the solid (Points: as given).
  std::vector<Vec2> sample() const;
  // The curve (layer 0) as segments no longer than max_length; none for Points.
  std::vector<std::pair<Vec2, Vec2>> curve(double max_length) const;
  // True on the solid side: inside an obstacle; outside a container (closed polygon,
  // ellipse, or box: outside [min.x, max.x] x [min.y, max.y], unbounded above without a
  // lid); behind an open polyline within its layer band (depth <= (layers - 1) *
  // layer_spacing + extra, projection within a segment or behind a corner). Never for
  // Points: a point list has no inside.
  bool on_solid_side(const Vec2& p, double extra) const;
};

// Offsets an open or closed chain by `distance` along its left normal (negative: right),
// meeting at the miter point at corners (miter length clamped to 4 * |distance|).
std::vector<Vec2> offset_chain(const std::vector<Vec2>& points, bool closed, double distance);
// The number of intervals a segment of length L would need to follow the spacing law
// exactly: the integral of du / s(u) over [0, L] (L / s when uniform).
double spacing_integral(double length, const SegmentSpacing& spacing);
// Samples a chain: segment i of length L gets n = max(1, round(spacing_integral(L,
// spacing[i]))) intervals; uniform spacing gives equal intervals, a graded one puts
// sample k where the integral of du / s(u) reaches k / n of its total, so the gaps grow
// geometrically from about `start` to about `end`. Corners appear once (the end point
// of an open chain is included).
void sample_chain(const std::vector<Vec2>& points, bool closed, const std::vector<SegmentSpacing>& spacing,
                  std::vector<Vec2>& out);
// n = max(3, round(perimeter / spacing)) points, uniform in arc length, starting at angle 0.
void sample_ellipse(const Vec2& center, const Vec2& radii, double spacing, std::vector<Vec2>& out);

// Removes the fluid particles that are on a boundary's solid side, closer than
// 0.5 * h * (1 - 1e-6) to a boundary curve or closer than kMinSampleDistance * h to a
// boundary sample; returns how many. near_samples (when given) gets how many of them
// were removed only for their distance to a sample.
constexpr double kMinSampleDistance = 0.9;
Index remove_covered_fluid(std::vector<Vec2>& x, std::vector<Vec2>& v, const std::vector<BoundaryShape>& boundaries,
                           const std::vector<Vec2>& samples, double h, Index* near_samples = nullptr);

// Removes points within tol of an earlier point (keeps the first); returns how many.
Index merge_duplicates(std::vector<Vec2>& x, std::vector<Vec2>& v, double cell, double tol);

}  // namespace sluice::shapes
