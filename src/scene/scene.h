#pragma once
// A scene file (JSON) resolved into a SimulationSetup (settings, fluid particles on a
// lattice, boundary samples with their objects) plus the program's own settings.
// Reading and validation live in src/scene (build.cpp assembles a scene: json_reader,
// overrides, the section readers); sampling of shapes in core/shapes.cpp.
#include <functional>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/types.h"
#include "solver/setup.h"

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

struct OutputSettings {
  std::string directory;                    // default "renders/<scene name>"
  std::vector<std::string> export_formats;  // subset of {"csv", "vtk"}
};

// The `render` section: how `sluice render` and `still` draw the scene when no flag says
// otherwise. Names are validated here; the renderer maps them to its own types.
struct RenderSettings {
  int width = 1280, height = 720;
  std::string color_by = "cfl";       // cfl | speed | pressure | density_error
  std::string colormap = "spectrum";  // spectrum | viridis | turbo
  bool fixed_range = false;           // false: automatic (fixed for the run, from the scene)
  double range_lo = 0, range_hi = 1;
  bool fixed_view = false;  // false: the scene's bounds at t = 0 with a margin
  Vec2 view_min{0, 0}, view_max{1, 1};
};

// A scene: the simulation's setup plus what only the program reads (its name and file,
// output and render settings, the resolved JSON).
struct Scene : SimulationSetup {
  std::string file;  // path as given (for messages)
  std::string name;  // "name" key, or the file's stem
  OutputSettings output;
  RenderSettings render;

  Index fluid_removed = 0;       // lattice points dropped inside boundary bands
  Index fluid_near_samples = 0;  // of those, dropped only as closer than 0.9 h to a sample
  nlohmann::json resolved;       // the scene with every default filled in
};

// An initial velocity field the scene format cannot express (the elliptical drop's strain
// about the fluid's centroid): it replaces the velocities v of the fluid particles at x.
// The scene applies it to its fluid before anything reads the initial motion (WCSPH's
// default stiffness and its acoustic check), so these see the motion the run starts with.
using InitialVelocity = std::function<void(const std::vector<Vec2>& x, std::vector<Vec2>& v)>;

// Reads and validates a scene file; each override is "json/path=value" or
// "json.path=value" (value parsed as JSON, else taken as a string), applied before
// validation. Throws SceneError.
Scene load_scene(const std::string& path, const std::vector<std::string>& overrides = {},
                 const InitialVelocity& initial_velocity = {});

// Same from JSON text already in memory; `file` is only used in messages.
Scene parse_scene(const std::string& text, const std::string& file, const std::vector<std::string>& overrides = {},
                  const InitialVelocity& initial_velocity = {});

}  // namespace sluice
