#pragma once
// A scene file (JSON) resolved into everything a simulation needs: settings, fluid
// particles on a lattice, boundary samples with their object ids. Reading and
// validation live in scene.cpp; sampling of shapes in shapes.cpp.
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "solver/motion.h"
#include "core/shapes.h"
#include "solver/settings.h"
#include "core/types.h"

namespace sluice {

// The shortest run (time.duration) and still or montage time after 0 [s]: shorter
// steps than that leave the solvers' divisions by dt^2 without precision.
inline constexpr double kMinDuration = 1e-6;

// A user mistake in a scene file or an override: the message names the file, the JSON
// path (e.g. /solver/tolerance), the value and what is allowed.
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One boundary object of the scene (a wall, a container, an obstacle). Its samples are
// boundary_x[first, first + count).
struct BoundaryObject {
  std::string name;   // "name" key, or "<shape><index>"
  std::string shape;  // box | polyline | polygon | circle | ellipse
  bool moving = false;  // has a scripted motion; false: a wall at rest (volumes computed once)
  Motion motion;        // pose over time; boundary_x holds the samples at rest (identity pose)
  shapes::BoundaryShape geometry;  // the shape at rest (solid-side tests, e.g. leak checks)
  Index first = 0;
  Index count = 0;
};

struct OutputSettings {
  std::string directory;                    // default "renders/<scene name>"
  std::vector<std::string> export_formats;  // subset of {"csv", "vtk"}
};

// The `render` section: how `sluice render` and `still` draw the scene when no flag says
// otherwise. Names are validated here; the renderer maps them to its own types.
struct RenderSettings {
  int width = 1280, height = 720;
  std::string color_by = "cfl";      // cfl | speed | pressure | density_error
  std::string colormap = "spectrum"; // spectrum | viridis | turbo
  bool fixed_range = false;          // false: automatic (fixed for the run, from the scene)
  double range_lo = 0, range_hi = 1;
  bool fixed_view = false;           // false: the scene's bounds at t = 0 with a margin
  Vec2 view_min{0, 0}, view_max{1, 1};
};

struct Scene {
  std::string file;    // path as given (for messages)
  std::string name;    // "name" key, or the file's stem
  double spacing = 0;  // fluid particle spacing h [m]; kernel support is 2h
  SolverSettings solver;
  TimeSettings time;
  StabilityLimits limits;
  OutputSettings output;
  RenderSettings render;

  std::vector<Vec2> fluid_x, fluid_v;      // initial fluid particles
  std::vector<Vec2> boundary_x;            // all boundary samples
  std::vector<Index> boundary_object;      // object index of each boundary sample
  std::vector<BoundaryObject> objects;
  Index fluid_removed = 0;                 // lattice points dropped inside boundary bands
  Index fluid_near_samples = 0;            // of those, dropped only as closer than 0.9 h to a sample

  Vec2 bounds_min{0, 0}, bounds_max{0, 0};  // box around all particles at t = 0
  nlohmann::json resolved;                  // the scene with every default filled in
};

// Fluid particles on the solid side of any boundary at time t (each object at its
// scripted pose) and more than half a spacing behind its surface, i.e. past the first
// sample layer: particles that passed through a wall. Open polylines count a band of
// half a spacing behind their last layer. 0 for a healthy run.
Index count_fluid_in_solids(const Scene& scene, const std::vector<Vec2>& fluid_x, double t);

// The same count, with the first such particle (in the order of fluid_x): its index, the
// object it is in, where it is and the nearest point of that object's surface (where it
// crossed, to within the step's motion), all at time t.
struct FluidInSolids {
  Index count = 0;
  Index first = -1;
  std::string object;
  Vec2 at = Vec2::Zero();
  Vec2 surface = Vec2::Zero();
};
FluidInSolids find_fluid_in_solids(const Scene& scene, const std::vector<Vec2>& fluid_x, double t);

// Reads and validates a scene file; each override is "json/path=value" or
// "json.path=value" (value parsed as JSON, else taken as a string), applied before
// validation. Throws SceneError.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {});

// Same from JSON text already in memory; `file` is only used in messages.
Scene parse_scene(const std::string& text, const std::string& file,
                  const std::vector<std::string>& overrides = {});

}  // namespace sluice
