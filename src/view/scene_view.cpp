#include "view/scene_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <span>

namespace sluice::view {

using namespace sluice::render;

void parse_resolution(const std::string& s, int& w, int& h, const std::string& flag) {
  char x = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 2 || h < 2 ||
      w > 16384 || h > 16384)
    throw FlagError(flag, s, "expected WxH with 2 <= W, H <= 16384, e.g. 1280x720");
}

std::string number_text(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

bool parse_pair(const std::string& s, double& a, double& b) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos) return false;
  try {
    size_t n1 = 0, n2 = 0;
    a = std::stod(s.substr(0, colon), &n1);
    b = std::stod(s.substr(colon + 1), &n2);
    return n1 == colon && n2 == s.size() - colon - 1;
  } catch (const std::exception&) {
    return false;
  }
}

namespace {

Field parse_field(const std::string& s) {
  if (s == "cfl") return Field::cfl;
  if (s == "speed") return Field::speed;
  if (s == "pressure") return Field::pressure;
  if (s == "density_error") return Field::density_error;
  throw FlagError("--color-by", s, "allowed: cfl, speed, pressure, density_error");
}

constexpr render::Rgb kWall{150, 150, 150};       // boundaries at rest: neutral grey
constexpr render::Rgb kMovingWall{84, 100, 124};  // moving boundaries: darker slate

struct NamedColor {
  const char* name;
  render::Rgb rgb;
};
constexpr NamedColor kNamedColors[] = {
    {"white", {255, 255, 255}},     {"black", {0, 0, 0}},       {"grey", {150, 150, 150}},  {"gray", {150, 150, 150}},
    {"lightgrey", {210, 210, 210}}, {"darkgrey", {90, 90, 90}}, {"slate", {84, 100, 124}},  {"red", {200, 40, 40}},
    {"green", {40, 150, 60}},       {"blue", {40, 80, 200}},    {"orange", {235, 140, 30}}, {"brown", {130, 85, 50}}};

// Object colours: NAME=COLOUR each, the name one of the scene's objects.
void resolve_object_colors(const ImageOptions& o, const Scene& scene, ImageConfig& c) {
  c.object_rgb.clear();
  for (const BoundaryObject& obj : scene.objects) c.object_rgb.push_back(obj.moving ? kMovingWall : kWall);
  for (const std::string& item : o.object_colors) {
    const size_t eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw FlagError("--object-color", item, "expected NAME=COLOUR, e.g. paddle=#d04040");
    const std::string name = item.substr(0, eq), colour = item.substr(eq + 1);
    const auto rgb = parse_color(colour);
    if (!rgb) throw FlagError("--object-color", item, kColorsAllowed);
    std::string names;
    bool found = false;
    for (size_t k = 0; k < scene.objects.size(); ++k) {
      names += (k ? ", " : "") + scene.objects[k].name;
      if (scene.objects[k].name == name) {
        c.object_rgb[k] = *rgb;
        found = true;
      }
    }
    if (!found) throw FlagError("--object-color", item, "no object " + name + " in the scene; its objects: " + names);
  }
}

}  // namespace

const char* const kColorsAllowed =
    "expected #rrggbb or one of white, black, grey, lightgrey, darkgrey, slate, red, green, blue, orange, brown";

std::optional<render::Rgb> parse_color(const std::string& text) {
  for (const NamedColor& c : kNamedColors)
    if (text == c.name) return c.rgb;
  const std::string hex = !text.empty() && text[0] == '#' ? text.substr(1) : text;
  if (hex.size() != 6 || hex.find_first_not_of("0123456789abcdefABCDEF") != std::string::npos) return std::nullopt;
  const unsigned long v = std::stoul(hex, nullptr, 16);
  return render::Rgb{static_cast<std::uint8_t>(v >> 16), static_cast<std::uint8_t>((v >> 8) & 255),
                     static_cast<std::uint8_t>(v & 255)};
}

const char* field_label(Field f) {
  switch (f) {
    case Field::cfl:
      return "CFL";
    case Field::speed:
      return "speed [m/s]";
    case Field::pressure:
      return "pressure [Pa\u00b7m]";
    case Field::density_error:
      return "density error [%]";
  }
  return "";
}

Overlay parse_overlay(const std::string& text) {
  if (text.empty() || text == "full") return Overlay::full;
  if (text == "time") return Overlay::time;
  if (text == "none") return Overlay::none;
  throw FlagError("--overlay", text, "allowed: full, time, none");
}

std::string overlay_text(Overlay mode, double time, Index frame, long step, int iterations) {
  char buf[160];
  if (mode == Overlay::time)
    std::snprintf(buf, sizeof buf, "t = %.3f s", time);
  else
    std::snprintf(buf, sizeof buf, "t = %.3f s    frame %d    step %ld    iterations %d", time, frame, step,
                  iterations);
  return mode == Overlay::none ? std::string() : std::string(buf);
}

// The automatic colour range: fixed for the whole run (no flicker between frames) and
// derived from the scene's scales. H is the fluid's height at t = 0: sqrt(2 g H) is the
// speed of a free fall from the top of the fluid, rho0 g H the hydrostatic pressure at
// its bottom (2D pressure, Pa*m). CFL: 0..1, the stability scale of Eq. 14.
void automatic_range(Field f, const Scene& scene, double& lo, double& hi) {
  double ymin = scene.fluid_x.front().y(), ymax = ymin;
  for (const Vec2& p : scene.fluid_x) {
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  const double height = ymax - ymin + scene.spacing, g = scene.solver.gravity.norm();
  double vmax0 = 0;
  for (const Vec2& v : scene.fluid_v) vmax0 = std::max(vmax0, v.norm());
  lo = 0;
  switch (f) {
    case Field::cfl:
      hi = 1;
      break;
    case Field::speed:
      hi = std::max(std::sqrt(2 * g * height), vmax0);
      break;
    case Field::pressure:
      hi = scene.solver.rest_density * g * height;
      break;
    case Field::density_error:
      hi = 1;
      break;
  }
  if (!(hi > 0)) hi = 1;  // no gravity and no motion: any scale
}

ImageConfig resolve_image(const ImageOptions& o, const Scene& scene) {
  const RenderSettings& rs = scene.render;
  ImageConfig c;
  if (o.resolution.empty()) {
    c.frame.width = rs.width;
    c.frame.height = rs.height;
  } else {
    parse_resolution(o.resolution, c.frame.width, c.frame.height);
  }
  c.field = parse_field(o.color_by.empty() ? rs.color_by : o.color_by);
  const std::string cmap_name = o.colormap.empty() ? rs.colormap : o.colormap;
  const auto cmap = parse_colormap(cmap_name);
  if (!cmap) throw FlagError("--colormap", cmap_name, "allowed: spectrum, viridis, turbo");
  c.frame.colormap = *cmap;
  const auto egl = parse_egl_platform(o.egl);
  if (!egl) throw FlagError("--egl", o.egl, "allowed: auto, surfaceless, device");
  c.frame.egl = *egl;
  if (o.msaa != 0 && o.msaa != 4) throw FlagError("--msaa", std::to_string(o.msaa), "allowed: 0 or 4");
  c.frame.msaa = o.msaa;
  if (o.range == "auto" || (o.range.empty() && !rs.fixed_range)) {
    automatic_range(c.field, scene, c.lo, c.hi);
  } else if (o.range.empty()) {
    c.lo = rs.range_lo;
    c.hi = rs.range_hi;
  } else if (!parse_pair(o.range, c.lo, c.hi) || !(c.hi > c.lo) || !std::isfinite(c.hi - c.lo)) {
    // hi - lo finite: no NaN or infinity, and the colour (v - lo) / (hi - lo) is defined.
    throw FlagError("--range", o.range,
                    "expected lo:hi, finite numbers with lo < hi and hi - lo finite, e.g. 0:1, or auto");
  }
  c.frame.field_label = field_label(c.field);
  c.frame.colorbar = !o.no_colorbar;
  c.overlay = o.no_overlay ? Overlay::none : parse_overlay(o.overlay);
  c.frame.overlay = c.overlay != Overlay::none;
  c.frame.title = o.title;
  if (!(o.particle_scale > 0 && o.particle_scale <= 10))
    throw FlagError("--particle-scale", number_text(o.particle_scale),
                    "expected a number > 0 and <= 10 (1: discs of one spacing)");
  c.frame.particle_scale = o.particle_scale;
  if (!o.background.empty()) {
    const auto bg = parse_color(o.background);
    if (!bg) throw FlagError("--background", o.background, kColorsAllowed);
    c.frame.background = *bg;
  }
  resolve_object_colors(o, scene, c);
  const Vec2 lo = rs.fixed_view ? rs.view_min : scene.bounds_min, hi = rs.fixed_view ? rs.view_max : scene.bounds_max;
  c.frame.fit_margin = !rs.fixed_view;
  c.frame.bounds_min[0] = lo.x();
  c.frame.bounds_min[1] = lo.y();
  c.frame.bounds_max[0] = hi.x();
  c.frame.bounds_max[1] = hi.y();
  return c;
}

namespace {

std::span<const double> as_doubles(const std::vector<Vec2>& v) {
  return {v.empty() ? nullptr : v.front().data(), 2 * v.size()};
}

}  // namespace

// The simulation keeps boundary samples in its own (spatial) order: the moving flags
// come from it, not from the scene's object ranges.
FrameBuilder::FrameBuilder(const ImageConfig& c, const Simulation& sim) : c_(c) {
  const std::vector<Index>& object = sim.boundary().object;
  for (size_t i = 0; i < sim.boundary().x.size(); ++i) {
    const size_t k = i < object.size() ? static_cast<size_t>(object[i]) : c_.object_rgb.size();
    boundary_rgb_.push_back(k < c_.object_rgb.size()   ? c_.object_rgb[k]
                            : sim.boundary().moving[i] ? kMovingWall
                                                       : kWall);
  }
}

FrameData FrameBuilder::build(const Simulation& sim, Index frame, const StepStats* last) {
  const SimulationSetup& scene = sim.setup();
  const FluidParticles& f = sim.fluid();
  const double dt = last ? last->dt : (scene.time.dt > 0 ? scene.time.dt : scene.time.dt_max);
  const double rho0 = scene.solver.rest_density;
  values_.resize(f.x.size());
  for (size_t i = 0; i < values_.size(); ++i) {
    double v = 0;
    switch (c_.field) {
      case Field::cfl:
        v = f.v[i].norm() * dt / scene.spacing;
        break;  // the thesis' velocity colouring
      case Field::speed:
        v = f.v[i].norm();
        break;
      case Field::pressure:
        v = f.p[i];
        break;
      case Field::density_error:
        v = std::max(f.rho[i] / rho0 - 1.0, 0.0) * 100.0;
        break;  // Eq. 15
    }
    values_[i] = static_cast<float>(v);
  }
  FrameData d;
  d.fluid_xy = as_doubles(f.x);
  d.fluid_value = values_;
  d.boundary_xy = as_doubles(sim.boundary().x);
  d.boundary_rgb = boundary_rgb_;
  d.diameter = scene.spacing;
  d.lo = c_.lo;
  d.hi = c_.hi;
  d.overlay = overlay_text(c_.overlay, sim.time(), frame, sim.steps(), last ? last->iterations : 0);
  return d;
}

}  // namespace sluice::view
