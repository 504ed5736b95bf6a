// Fluid blocks and boundary objects of a scene, and what a boundary would cost.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "scene/sample_file.h"
#include "scene/sections.h"

namespace sluice::scene_detail {

namespace {

// One entry of a per-segment spacing array: a number (uniform), or a pair [s_start, s_end]
// for a spacing that varies linearly from the segment's first vertex to its second (dense
// samples at a tip, sparse ones along a long flat wall).
shapes::SegmentSpacing read_spacing_entry(const json& v, const std::string& path, const Context& ctx) {
  const Range range = Range::positive("[m]");
  if (v.is_number()) {
    const double s = ctx.number(v, path, range);
    return {s, s};
  }
  if (!v.is_array() || v.size() != 2)
    ctx.fail(path,
             "expected a spacing > 0 [m] or a pair [s_start, s_end] of spacings > 0 [m] (graded from the segment's "
             "first point to its second), got " +
                 show(v));
  return {ctx.number(v[0], path + "/0", range), ctx.number(v[1], path + "/1", range)};
}

// Per-segment spacing: one number for all, or an array with one entry per segment, each a
// number or a graded pair [s_start, s_end].
std::vector<shapes::SegmentSpacing> read_segment_spacing(Reader& r, const Context& ctx, std::size_t segments,
                                                         double def, bool allow_array, const std::string& order) {
  const json* v = r.find("spacing");
  if (!v) {
    r.resolved()["spacing"] = def;
    return std::vector<shapes::SegmentSpacing>(segments, {def, def});
  }
  r.resolved()["spacing"] = *v;
  if (v->is_array() && allow_array) {
    if (v->size() != segments) {
      // Two numbers for one segment are most likely a graded pair without its brackets.
      const std::string hint = segments == 1 && v->size() == 2
                                   ? "; a graded spacing is a pair inside the array: [[s_start, s_end]]"
                                   : "; each entry is a number or a pair [s_start, s_end]";
      ctx.fail(r.at("spacing"), "expected " + std::to_string(segments) + " spacings (one per segment" + order +
                                    "), got " + std::to_string(v->size()) + hint);
    }
    std::vector<shapes::SegmentSpacing> out;
    for (std::size_t i = 0; i < segments; ++i)
      out.push_back(read_spacing_entry((*v)[i], r.at("spacing") + "/" + std::to_string(i), ctx));
    return out;
  }
  if (!v->is_number())
    ctx.fail(r.at("spacing"), allow_array
                                  ? "expected a number or an array with one entry per segment (a number or a pair "
                                    "[s_start, s_end]), got " +
                                        show(*v)
                                  : "expected a number, got " + show(*v) +
                                        "; circles and ellipses are sampled uniformly in arc length, with one spacing");
  const double s = ctx.number(*v, r.at("spacing"), Range::positive("[m]"));
  return std::vector<shapes::SegmentSpacing>(segments, {s, s});
}

// A path given in the scene, relative to the scene file's directory (absolute ones as they are).
std::filesystem::path relative_to_scene(const std::string& scene_file, const std::string& path) {
  const std::filesystem::path p(path);
  return (p.is_absolute() ? p : std::filesystem::path(scene_file).parent_path() / p).lexically_normal();
}

// "points": boundary samples used exactly as given, from an inline list or a file. They
// have no curve, no layers and no solid side; fluid lattice points within half a spacing
// of a sample are removed like for any other boundary.
shapes::BoundaryShape read_point_samples(Reader& r, const Context& ctx) {
  shapes::BoundaryShape b;
  b.kind = shapes::BoundaryShape::Kind::Points;
  const json* file = r.find("file");
  const json* samples = r.find("samples");
  r.finish();  // a misspelt key before any file is read
  if ((file != nullptr) == (samples != nullptr))
    ctx.fail(r.path(),
             std::string(file ? "both \"file\" and" : "neither \"file\" nor") +
                 " \"samples\" given; give exactly one: " +
                 "\"file\" (a text file of x,y lines, relative to the scene file) or \"samples\" (an array of [x, y])");
  if (samples) {
    if (samples->is_array() && samples->empty())
      ctx.fail(r.at("samples"), "the list is empty; give at least one sample [x, y]");
    b.points = ctx.points(*samples, r.at("samples"), 1);
    r.resolved()["samples"] = *samples;
  } else {
    const std::filesystem::path path = relative_to_scene(ctx.file, ctx.string(*file, r.at("file")));
    b.points = read_sample_file(path, r.at("file"), ctx);
    // Absolute, so that the resolved scene (written next to the outputs) still finds it.
    std::error_code ec;
    const std::filesystem::path absolute = std::filesystem::absolute(path, ec);
    r.resolved()["file"] = (ec ? path : absolute.lexically_normal()).string();
  }
  return b;
}

// A count that is not finite (coordinates near the range of double) is as bad as a huge one.
double finite_or_inf(double x) { return std::isfinite(x) ? x : kInf; }

std::string about(double count) { return std::isfinite(count) ? "about " + num(std::round(count)) : "too many"; }

}  // namespace

shapes::FluidShape read_fluid_block(Reader& r, const Context& ctx) {
  shapes::FluidShape f;
  const std::string shape = r.choice("shape", {"rectangle", "ellipse", "polygon"}, nullptr);
  if (shape == "rectangle") {
    f.kind = shapes::FluidShape::Kind::Rectangle;
    f.min = r.vec2("min");
    f.max = r.vec2("max");
    if (f.max.x() < f.min.x() || f.max.y() < f.min.y())
      ctx.fail(r.at("max"), "max [" + num(f.max.x()) + ", " + num(f.max.y()) + "] is below min [" + num(f.min.x()) +
                                ", " + num(f.min.y()) + "]; need min <= max in x and y");
  } else if (shape == "ellipse") {
    f.kind = shapes::FluidShape::Kind::Ellipse;
    f.center = r.vec2("center");
    f.radii = r.vec2("radii");
    if (f.radii.minCoeff() < 0) ctx.fail(r.at("radii"), "radii must be >= 0 [m], got " + show(r.resolved()["radii"]));
  } else {
    f.kind = shapes::FluidShape::Kind::Polygon;
    f.points = r.points("points", 3);
    // Points on one line hold no fluid (the no-fluid error follows); such edges fold back
    // over each other, which is not what the self-intersection message is about.
    const bool on_a_line = std::all_of(f.points.begin(), f.points.end(), [&](const Vec2& p) {
      const Vec2 a = f.points[1] - f.points[0], b = p - f.points[0];
      return a.x() * b.y() - a.y() * b.x() == 0;
    });
    if (on_a_line) {
    } else if (const int seg = shapes::self_intersection(f.points, true); seg >= 0)
      ctx.fail(r.at("points"), "the polygon intersects itself (edge " + std::to_string(seg) +
                                   " crosses another edge); the points must form a simple polygon");
  }
  f.velocity = r.vec2("velocity", Vec2::Zero());
  r.finish();
  return f;
}

BoundaryCost boundary_cost(const shapes::BoundaryShape& b, double h) {
  using Kind = shapes::BoundaryShape::Kind;
  BoundaryCost c;
  if (b.kind == Kind::Points) {
    c.samples = static_cast<double>(b.points.size());
    return c;
  }
  const bool ellipse = b.kind == Kind::Ellipse;
  for (int k = 0; k < b.layers; ++k) {
    const double d = (k + b.surface_offset) * b.layer_spacing;
    if (ellipse) {
      const Vec2 radii = b.radii + Vec2::Constant(b.fluid_inside ? d : -d);
      if (radii.minCoeff() <= 0) break;
      c.samples += std::max(3.0, finite_or_inf(shapes::ellipse_perimeter(radii.x(), radii.y()) / b.spacing));
      continue;
    }
    const std::vector<Vec2> pts = d == 0 ? b.points : shapes::offset_chain(b.points, b.closed, b.fluid_left ? -d : d);
    const std::size_t n = pts.size(), segs = b.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i)
      c.samples += std::max(1.0, finite_or_inf(std::round(shapes::spacing_integral((pts[(i + 1) % n] - pts[i]).norm(),
                                                                                   b.segment_spacing[i]))));
    c.samples += b.closed ? 0 : 1;
  }
  if (ellipse) {  // curve(h) samples the ellipse at a quarter spacing
    c.curve_pieces = std::max(64.0, finite_or_inf(4 * shapes::ellipse_perimeter(b.radii.x(), b.radii.y()) / h));
  } else {
    const std::size_t n = b.points.size(), segs = b.closed ? n : n - 1;
    for (std::size_t i = 0; i < segs; ++i)
      c.curve_pieces += std::max(1.0, finite_or_inf(std::ceil((b.points[(i + 1) % n] - b.points[i]).norm() / h)));
  }
  return c;
}

shapes::BoundaryShape read_boundary(Reader& r, const Context& ctx, std::size_t index, double h, BoundaryObject& obj) {
  std::string& name = obj.name;
  std::string& shape = obj.shape;
  shapes::BoundaryShape b;
  shape = r.choice("shape", {"box", "polyline", "polygon", "circle", "ellipse", "points"}, nullptr);
  name = r.string("name", shape + std::to_string(index));
  obj.no_slip = r.choice("wall", {"free_slip", "no_slip"}, "free_slip") == "no_slip";
  const double default_viscosity = obj.wall_viscosity;
  obj.wall_viscosity = r.number("wall_viscosity", default_viscosity, Range::at_least(0, "[m^2/s]"));
  if (!obj.no_slip && obj.wall_viscosity != default_viscosity)
    ctx.fail(r.at("wall_viscosity"), "applies to a no-slip wall only; add \"wall\": \"no_slip\" or remove it");
  if (shape == "points") {
    read_object_motion(r, ctx, obj);
    return read_point_samples(r, ctx);
  }
  bool fluid_inside = false;
  auto side = [&](std::vector<std::string> allowed, const char* def) { return r.choice("fluid_side", allowed, def); };

  if (shape == "box") {
    const Vec2 lo = r.vec2("min"), hi = r.vec2("max");
    if (!(hi.x() > lo.x() && hi.y() > lo.y()))
      ctx.fail(r.at("max"), "max [" + num(hi.x()) + ", " + num(hi.y()) + "] must be above min [" + num(lo.x()) + ", " +
                                num(lo.y()) + "] in x and y");
    b.fluid_left = side({"inside", "outside"}, "inside") == "inside";  // inside is on the left of a CCW walk
    // A container is open at the top by default; an obstacle is a closed solid (a box
    // without its top would be a cup that fills with water).
    const bool lid = r.boolean("lid", !b.fluid_left);
    b.kind = shapes::BoundaryShape::Kind::Box;
    b.min = lo;
    b.max = hi;
    b.lid = lid;
    // spacing entries: bottom, right, top, left (top unused without a lid)
    const auto s = read_segment_spacing(r, ctx, 4, h, true, ": bottom, right, top, left");
    if (lid) {  // counter-clockwise loop from min: bottom, right, top, left
      b.points = {lo, {hi.x(), lo.y()}, hi, {lo.x(), hi.y()}};
      b.segment_spacing = s;
      b.closed = true;
    } else {  // open cup: left wall down, bottom, right wall up
      b.points = {{lo.x(), hi.y()}, lo, {hi.x(), lo.y()}, hi};
      b.segment_spacing = {s[3], s[0], s[1]};
    }
  } else if (shape == "polyline" || shape == "polygon") {
    const bool polygon = shape == "polygon";
    b.points = r.points("points", polygon ? 3 : 2);
    b.closed = polygon ? true : r.boolean("closed", false);
    const std::size_t segs = b.closed ? b.points.size() : b.points.size() - 1;
    for (std::size_t i = 0; i < segs; ++i)
      if ((b.points[(i + 1) % b.points.size()] - b.points[i]).norm() == 0)
        ctx.fail(r.at("points") + "/" + std::to_string((i + 1) % b.points.size()),
                 "repeats the previous point; segments must have a length > 0");
    if (const int seg = shapes::self_intersection(b.points, b.closed); seg >= 0)
      ctx.fail(r.at("points"), "segment " + std::to_string(seg) + " crosses or runs along another segment; the " +
                                   shape + " must not intersect or overlap itself");
    if (polygon && shapes::signed_area(b.points) == 0) ctx.fail(r.at("points"), "the polygon has zero area");
    b.segment_spacing = read_segment_spacing(r, ctx, segs, h, true, "");
    if (polygon) {
      fluid_inside = side({"inside", "outside"}, "outside") == "inside";
      b.fluid_left = fluid_inside == (shapes::signed_area(b.points) > 0);
    } else {
      b.fluid_left = side({"left", "right"}, "left") == "left";
    }
  } else {  // circle, ellipse
    b.kind = shapes::BoundaryShape::Kind::Ellipse;
    b.center = r.vec2("center");
    if (shape == "circle") {
      const double radius = r.number("radius", Range::positive("[m]"));
      b.radii = {radius, radius};
    } else {
      b.radii = r.vec2("radii");
      if (b.radii.minCoeff() <= 0) ctx.fail(r.at("radii"), "radii must be > 0 [m], got " + show(r.resolved()["radii"]));
    }
    b.spacing = read_segment_spacing(r, ctx, 1, h, false, "")[0].start;
    b.fluid_inside = side({"inside", "outside"}, "outside") == "inside";
  }
  b.layers = r.integer("layers", 2, 1, 1000);
  b.layer_spacing = r.number("layer_spacing", h, Range::positive("[m]"));
  b.surface_offset = r.number("surface_offset", 0.5, Range::at_least(0, "(in layer spacings)"));
  read_object_motion(r, ctx, obj);
  r.finish();
  return b;
}

void check_boundary_cost(const Context& ctx, const std::string& path, const BoundaryCost& cost,
                         const BoundaryCost& total) {
  if (!(cost.samples <= kMaxParticles))
    ctx.fail(path, "would create " + about(cost.samples) + " boundary samples; the limit is " + num(kMaxParticles) +
                       " (check spacing, layers and layer_spacing)");
  if (!(cost.curve_pieces <= kMaxParticles))
    ctx.fail(path, "the curve would be cut into " + about(cost.curve_pieces) +
                       " pieces of at most one fluid spacing (to clear the fluid next to it); the limit is " +
                       num(kMaxParticles) + " (check the coordinates and /spacing)");
  if (!(total.samples <= kMaxParticles) || !(total.curve_pieces <= kMaxParticles))
    ctx.fail(path, "the boundaries up to this one would create " + about(total.samples) + " samples and " +
                       about(total.curve_pieces) + " curve pieces; the limit is " + num(kMaxParticles) +
                       " of each (check spacing and layers)");
}

}  // namespace sluice::scene_detail
