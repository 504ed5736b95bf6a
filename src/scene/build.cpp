// A scene assembled: the text parsed (json_reader.cpp), the overrides applied
// (overrides.cpp), the sections read (sections.h), then the particles made from the
// shapes (core/shapes.cpp): boundary samples, the fluid lattice, the fluid inside the
// boundaries removed, and the bounds. The format is documented in docs/scene_format.md;
// keep the two in sync.
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <system_error>

#include "core/shapes.h"
#include "scene/json_reader.h"
#include "scene/overrides.h"
#include "scene/scene.h"
#include "scene/sections.h"

namespace sluice {

using namespace scene_detail;

namespace {

// Clears the fluid inside the boundaries as they stand at t = 0: objects at rest (and
// moving ones whose script leaves them at rest at t = 0) together, every other moving
// object on its own, with the fluid taken into its rest frame and back.
Index remove_fluid_at_start(Scene& scene, const std::vector<shapes::BoundaryShape>& walls, double h) {
  std::vector<shapes::BoundaryShape> at_rest;
  std::vector<Vec2> rest_samples;
  std::vector<std::size_t> posed;
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const BoundaryObject& obj = scene.objects[i];
    const Pose pose = obj.moving ? obj.motion.at(0.0) : Pose{};
    if (pose.angle != 0 || pose.shift != Vec2::Zero()) {
      posed.push_back(i);
      continue;
    }
    at_rest.push_back(walls[i]);
    rest_samples.insert(rest_samples.end(), scene.boundary_x.begin() + obj.first,
                        scene.boundary_x.begin() + obj.first + obj.count);
  }
  Index near = 0;
  Index removed = shapes::remove_covered_fluid(scene.fluid_x, scene.fluid_v, at_rest, rest_samples, h, &near);
  scene.fluid_near_samples = near;
  for (std::size_t i : posed) {
    const BoundaryObject& obj = scene.objects[i];
    const Pose pose = obj.motion.at(0.0);
    const PoseMap back(Pose{-pose.angle, 0, 0, Vec2::Zero(), Vec2::Zero(), Vec2::Zero()});
    // The kept particles are picked by index (carried as the "velocity" of the rest-frame
    // copy), so that their positions are not rounded by the way there and back.
    std::vector<Vec2> rest(scene.fluid_x.size()), index(scene.fluid_x.size());
    for (std::size_t k = 0; k < rest.size(); ++k) {
      rest[k] = back.rotated(scene.fluid_x[k] - pose.shift);
      index[k] = Vec2(static_cast<double>(k), 0);
    }
    const std::vector<Vec2> samples(scene.boundary_x.begin() + obj.first,
                                    scene.boundary_x.begin() + obj.first + obj.count);
    removed += shapes::remove_covered_fluid(rest, index, {walls[i]}, samples, h, &near);
    scene.fluid_near_samples += near;
    std::vector<Vec2> x, v;
    for (const Vec2& k : index) {
      x.push_back(scene.fluid_x[static_cast<std::size_t>(k.x())]);
      v.push_back(scene.fluid_v[static_cast<std::size_t>(k.x())]);
    }
    scene.fluid_x = std::move(x);
    scene.fluid_v = std::move(v);
  }
  return removed;
}

}  // namespace

Scene parse_scene(const std::string& text, const std::string& file, const std::vector<std::string>& overrides,
                  const InitialVelocity& initial_velocity) {
  Context ctx{file, &text, {}};
  json root = parse_json(text, ctx);
  // Before the overrides: one of them (e.g. --duration's time.duration) would otherwise
  // report the wrong type as its own mistake.
  if (!root.is_object()) throw SceneError(file + ": the scene must be a JSON object {...}, got " + show(root));
  for (const auto& o : overrides) apply_override(root, o, ctx.overridden);

  Scene scene;
  scene.file = file;
  Reader top(ctx, &root, "");
  // Look up every top-level key first so that a misspelt section is reported before
  // anything that depends on it.
  const json* name = top.find("name");
  const json* spacing = top.find("spacing");
  const json* sections[5] = {top.find("solver"), top.find("time"), top.find("stability"), top.find("output"),
                             top.find("render")};
  const json* fluid = top.find("fluid");
  const json* boundaries = top.find("boundaries");
  top.finish();

  std::string stem = std::filesystem::path(file).stem().string();
  scene.name = name ? ctx.string(*name, "/name") : (stem.empty() ? "scene" : stem);
  check_name(ctx, scene.name);
  if (!spacing) ctx.fail("/spacing", "missing required key; the fluid particle spacing in m, a number > 0");
  scene.spacing = ctx.number(*spacing, "/spacing", Range::positive("[m]"));
  const double h = scene.spacing;

  json resolved = root;
  resolved["name"] = scene.name;
  resolved["spacing"] = h;
  {
    Reader r(ctx, sections[0], "/solver");
    scene.solver = read_solver(r, ctx);
    resolved["solver"] = r.resolved();
  }
  {
    Reader r(ctx, sections[1], "/time");
    scene.time = read_time(r, ctx);
    resolved["time"] = r.resolved();
  }
  {
    Reader r(ctx, sections[2], "/stability");
    scene.limits = read_stability(r);
    resolved["stability"] = r.resolved();
  }
  {
    Reader r(ctx, sections[3], "/output");
    scene.output = read_output(r, ctx, scene.name);
    resolved["output"] = r.resolved();
  }
  {
    Reader r(ctx, sections[4], "/render");
    scene.render = read_render(r, ctx);
    resolved["render"] = r.resolved();
  }

  // Shapes.
  if (!fluid) ctx.fail("/fluid", "missing required key; an array of fluid blocks (rectangle, ellipse, polygon)");
  if (!fluid->is_array()) ctx.fail("/fluid", "expected an array of fluid blocks, got " + show(*fluid));
  std::vector<shapes::FluidShape> blocks;
  resolved["fluid"] = json::array();
  for (std::size_t i = 0; i < fluid->size(); ++i) {
    Reader r(ctx, &(*fluid)[i], "/fluid/" + std::to_string(i));
    blocks.push_back(read_fluid_block(r, ctx));
    resolved["fluid"].push_back(r.resolved());
  }

  std::vector<shapes::BoundaryShape> walls;
  std::set<std::string> names;
  BoundaryCost total;  // of all objects: each may stay under the limit, the sum must too
  resolved["boundaries"] = json::array();
  if (boundaries && !boundaries->is_array())
    ctx.fail("/boundaries", "expected an array of boundary objects, got " + show(*boundaries));
  for (std::size_t i = 0; boundaries && i < boundaries->size(); ++i) {
    Reader r(ctx, &(*boundaries)[i], "/boundaries/" + std::to_string(i));
    BoundaryObject obj;
    walls.push_back(read_boundary(r, ctx, i, h, obj));
    const BoundaryCost cost = boundary_cost(walls.back(), h);
    total.samples += cost.samples;
    total.curve_pieces += cost.curve_pieces;
    check_boundary_cost(ctx, r.path(), cost, total);
    if (!names.insert(obj.name).second)
      ctx.fail(r.at("name"), "duplicate name \"" + obj.name + "\"; boundary names must be unique");
    resolved["boundaries"].push_back(r.resolved());
    scene.objects.push_back(obj);
  }
  scene.resolved = std::move(resolved);

  // Boundary samples, one contiguous range per object.
  for (std::size_t i = 0; i < walls.size(); ++i) {
    scene.objects[i].geometry = walls[i];
    const auto samples = walls[i].sample();
    // Offsets of coordinates near the range of double overflow; nothing downstream
    // (grids, volumes) can place a sample at infinity.
    for (const Vec2& p : samples)
      if (!std::isfinite(p.x()) || !std::isfinite(p.y()))
        ctx.fail("/boundaries/" + std::to_string(i),
                 "its samples would have coordinates beyond the range of numbers "
                 "(coordinates, radii or layer_spacing too large); keep them far below 1e300");
    scene.objects[i].first = static_cast<Index>(scene.boundary_x.size());
    scene.objects[i].count = static_cast<Index>(samples.size());
    scene.boundary_x.insert(scene.boundary_x.end(), samples.begin(), samples.end());
    scene.boundary_object.insert(scene.boundary_object.end(), samples.size(), static_cast<Index>(i));
  }

  // Fluid lattice, duplicates of overlapping blocks merged, then the boundary bands cleared.
  double lattice_total = 0;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    Vec2 lo, hi;
    blocks[i].bounding_box(lo, hi);
    lattice_total += static_cast<double>(shapes::lattice_count(lo.x(), hi.x(), h)) *
                     static_cast<double>(shapes::lattice_count(lo.y(), hi.y(), h));
    if (lattice_total > kMaxParticles)
      ctx.fail("/fluid/" + std::to_string(i), "the fluid would have more than " + num(kMaxParticles) +
                                                  " lattice points; increase /spacing (now " + num(h) + " m)");
  }
  for (const auto& b : blocks) {
    const auto pts = shapes::fill_lattice(b, h);
    scene.fluid_x.insert(scene.fluid_x.end(), pts.begin(), pts.end());
    scene.fluid_v.insert(scene.fluid_v.end(), pts.size(), b.velocity);
  }
  if (blocks.size() > 1) shapes::merge_duplicates(scene.fluid_x, scene.fluid_v, h, 1e-9 * h);
  const std::size_t lattice_points = scene.fluid_x.size();
  scene.fluid_removed = remove_fluid_at_start(scene, walls, h);
  if (scene.fluid_x.empty())
    ctx.fail("/fluid",
             "the scene has no fluid particles (" + std::to_string(lattice_points) +
                 (lattice_points ? " lattice points, all removed inside boundaries)"
                                 : " lattice points: the fluid blocks are empty or have no area at this spacing)"));
  if (initial_velocity) initial_velocity(scene.fluid_x, scene.fluid_v);

  const bool default_stiffness = !(scene.solver.stiffness > 0);
  if (default_stiffness) {
    scene.solver.stiffness = wcsph_default_stiffness(scene);
    if (scene.solver.stiffness > 0) scene.resolved["solver"]["stiffness"] = scene.solver.stiffness;
  }
  if (scene.solver.type == SolverType::WCSPH) {
    if (!(scene.solver.stiffness > 0))
      ctx.fail("/solver/stiffness",
               "missing: WCSPH's default stiffness k = rest_density (20 v)^2 needs a speed v, sqrt(g H) or the "
               "fastest initial fluid velocity, and this scene has neither gravity nor initial motion; set "
               "solver.stiffness, e.g. 1e6 [Pa*m]");
    // The fixed step must resolve the sound waves (Monaghan 1992): dt <= 0.4 h / c.
    const double c = std::sqrt(scene.solver.stiffness / scene.solver.rest_density);
    const double limit = wcsph_acoustic_limit(scene);
    if (scene.time.dt > 0 && scene.time.dt > limit)
      ctx.fail("/time/dt",
               "WCSPH step " + num(scene.time.dt) + " s exceeds the acoustic limit 0.4 h / c = " + num(limit) +
                   " s (sound speed c = sqrt(stiffness / rest_density) = " + num(c) + " m/s with stiffness " +
                   num(scene.solver.stiffness) + " Pa*m" + (default_stiffness ? ", the scene's default" : "") +
                   ", h = " + num(h) + " m); use time.dt <= " + num(limit) + " or time.dt=null for the adaptive step");
  }

  // Bounds of everything at t = 0.
  scene.bounds_min = scene.bounds_max = scene.fluid_x.front();
  for (const auto* list : {&scene.fluid_x, &scene.boundary_x})
    for (const Vec2& p : *list) {
      scene.bounds_min = scene.bounds_min.cwiseMin(p);
      scene.bounds_max = scene.bounds_max.cwiseMax(p);
    }
  return scene;
}

Scene load_scene(const std::string& path, const std::vector<std::string>& overrides,
                 const InitialVelocity& initial_velocity) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status))
    throw SceneError(path + ": cannot open scene file: no such file" +
                     (ec && ec != std::errc::no_such_file_or_directory ? " (" + ec.message() + ")" : std::string()));
  if (std::filesystem::is_directory(status))
    throw SceneError(path + ": is a directory; expected a scene file (JSON), e.g. scenes/dam_break.json");
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(path + ": not a regular file; expected a scene file (JSON)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneError(path + ": cannot open scene file: " + std::strerror(errno));
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, overrides, initial_velocity);
}

}  // namespace sluice
