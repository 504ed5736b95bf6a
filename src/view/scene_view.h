#pragma once
// From a simulation to the renderer's frames: the image settings a user asked for
// (flags over the scene's `render` section), the automatic colour range, and the
// per-frame arrays (fluid field values, boundary samples with their moving flags).
// Shared by `sluice render` / `still` and the image regression tests, so the tests
// render exactly what the program does.
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/frame.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::view {

// A number as messages show it (%g: 0.5, 1e-06).
std::string number_text(double v);

// A mistake in a command-line flag: "FLAG VALUE: what is allowed".
class FlagError : public std::runtime_error {
 public:
  FlagError(const std::string& flag, const std::string& value, const std::string& allowed)
      : std::runtime_error(flag + " " + value + ": " + allowed) {}
};

// Image flags shared by `render` and `still`. An empty string takes the scene's
// `render` section (whose defaults are 1280x720, cfl, spectrum, automatic range).
struct ImageOptions {
  std::string resolution;   // WxH
  std::string color_by;     // cfl | speed | pressure | density_error
  std::string colormap;     // spectrum | viridis | turbo
  std::string range;        // "lo:hi" or "auto"
  std::string overlay;      // full | time | none (empty: full)
  bool no_overlay = false;  // the older spelling of --overlay none
  std::string title;        // a title row above the scene (none when empty)
  bool no_colorbar = false;
  double particle_scale = 1;               // disc diameter over the spacing, 0 < s <= 10
  std::string background;                  // colour (empty: white)
  std::vector<std::string> object_colors;  // NAME=COLOUR, one per boundary object named
  int msaa = 0;                            // 0 or 4
  std::string egl = "auto";                // auto | surfaceless | device
};

enum class Field { cfl, speed, pressure, density_error };
enum class Overlay { full, time, none };

// A colour: #rrggbb, rrggbb or a name (white, black, grey, lightgrey, darkgrey, slate,
// red, green, blue, orange, brown); nullopt when it is none of these.
std::optional<render::Rgb> parse_color(const std::string& text);
// The flag's mistake, for messages.
extern const char* const kColorsAllowed;

// The colorbar's title of a field, with its unit: "speed [m/s]", "pressure [Pa·m]".
const char* field_label(Field f);
// The overlay line of a frame: "t = 0.500 s" (time), with frame, step and iterations (full).
std::string overlay_text(Overlay mode, double time, Index frame, long step, int iterations);
// Everything the image options resolve to for one scene.
struct ImageConfig {
  render::FrameSettings frame;
  Field field = Field::cfl;
  Overlay overlay = Overlay::full;
  double lo = 0, hi = 1;  // colour range, fixed for the run
  // Boundary samples' colour per scene object (walls grey, moving objects slate unless
  // given), indexed like Scene::objects.
  std::vector<render::Rgb> object_rgb;
};

// Throws FlagError for a bad flag value.
ImageConfig resolve_image(const ImageOptions& o, const Scene& scene);
// --overlay full|time|none; throws FlagError.
Overlay parse_overlay(const std::string& text);

// The automatic colour range of a field: fixed for the run, from the scene's scales.
void automatic_range(Field f, const Scene& scene, double& lo, double& hi);

// "a:b" as two numbers; false when malformed.
bool parse_pair(const std::string& s, double& a, double& b);
// "WxH" with 2 <= W, H <= 16384; throws FlagError naming `flag`.
void parse_resolution(const std::string& s, int& w, int& h, const std::string& flag = "--resolution");

// Per-frame particle arrays of a simulation, in the renderer's terms. The arrays stay
// valid until the next build() or until the simulation steps.
class FrameBuilder {
 public:
  FrameBuilder(const ImageConfig& c, const Simulation& sim);
  // `last` is the step that reached this frame (nullptr before the first step).
  render::FrameData build(const Simulation& sim, Index frame, const StepStats* last);

 private:
  ImageConfig c_;
  std::vector<render::Rgb> boundary_rgb_;
  std::vector<float> values_;
};

}  // namespace sluice::view
