// `sluice montage`: one scene simulated to several times (and, with --vary, once per
// value of one scene setting), a cell rendered at each time, the cells composed into
// one grid with one colour scale (the thesis' Figures 2 and 8).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "app/commands.h"
#include "app/run.h"
#include "io/output.h"
#include "render/frame.h"
#include "render/image.h"
#include "scene/scene.h"
#include "solver/simulation.h"
#include "view/montage.h"
#include "view/scene_view.h"

namespace sluice::app {

namespace fs = std::filesystem;
using namespace sluice::render;
using namespace sluice::view;

namespace {

// The largest montage side: as for any image (--resolution), and what a PNG viewer opens.
constexpr int kMaxMontageSide = 16384;

// Frame rates tried when the scene's own does not land on every requested time; 1/1000 s
// covers times with up to three decimals, and a higher rate would force many short steps.
constexpr int kMaxLandingFps = 1000;

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  size_t start = 0;
  while (true) {
    const size_t end = text.find(sep, start);
    parts.push_back(text.substr(start, end == std::string::npos ? std::string::npos : end - start));
    if (end == std::string::npos) return parts;
    start = end + 1;
  }
}

std::vector<double> parse_times(const std::string& text) {
  const char* allowed = "expected simulated times T1,T2,... in seconds, strictly increasing, e.g. 0,0.4,0.8";
  std::vector<double> times;
  for (const std::string& part : split(text, ',')) {
    char* end = nullptr;
    const double t = std::strtod(part.c_str(), &end);
    // Decimal only: strtod would also read 0x1 (hexadecimal) and inf.
    const bool decimal = part.find_first_not_of("0123456789.eE+-") == std::string::npos;
    if (part.empty() || !decimal || *end != '\0' || !std::isfinite(t)) throw FlagError("--times", text, allowed);
    if (t < 0) throw FlagError("--times", text, "time " + part + " is negative; times must be >= 0");
    if (!times.empty() && !(t > times.back()))
      throw FlagError("--times", text,
                      "times must be strictly increasing; " + part + " follows " + number_text(times.back()));
    times.push_back(t);
  }
  return times;
}

struct Variation {
  std::string key;  // empty: no --vary, one run
  std::vector<std::string> values;
};

Variation parse_vary(const std::string& text) {
  Variation v;
  if (text.empty()) return v;
  const size_t eq = text.find('=');
  const char* allowed =
      "expected KEY=V1,V2,... with a scene path as for --set, e.g. solver.boundary_pressure=extrapolation,zero";
  if (eq == std::string::npos || eq == 0) throw FlagError("--vary", text, allowed);
  v.key = text.substr(0, eq);
  v.values = split(text.substr(eq + 1), ',');
  for (const std::string& value : v.values)
    if (value.empty()) throw FlagError("--vary", text, allowed);
  return v;
}

// The smallest frame rate whose frame times k / fps include every requested time
// exactly (as doubles), the scene's own first. The simulation shortens its steps to land
// on frame times (Simulation::step), so at such a rate every cell shows the state at
// exactly its time, within one uninterrupted run. The alternative, stopping the run at
// each time like `still` does (time.duration = T), would need a fresh run per time.
// Only the step lengths near the frame times change; the physics does not.
std::optional<double> landing_fps(const std::vector<double>& times, double scene_fps) {
  auto lands = [&](double fps) {
    for (double t : times)
      if (std::round(t * fps) / fps != t) return false;
    return true;
  };
  if (lands(scene_fps)) return scene_fps;
  for (int fps = 1; fps <= kMaxLandingFps; ++fps)
    if (lands(fps)) return fps;
  return std::nullopt;
}

// The scene of one variant, set up to land on every time and to stop at the last one.
Scene load_variant(const MontageOptions& o, const std::vector<double>& times, const Variation& vary, size_t v) {
  std::vector<std::string> overrides = o.set;
  if (!vary.key.empty()) overrides.push_back(vary.key + "=" + vary.values[v]);
  const Scene scene = load_scene(o.scene, overrides);
  const double duration = scene.time.duration;
  if (times.back() > duration)
    throw FlagError("--times", o.times,
                    "time " + number_text(times.back()) +
                        " s is after the scene's end; allowed: 0 to time.duration = " + number_text(duration) + " s");
  const std::optional<double> fps = landing_fps(times, scene.time.fps);
  if (!fps)
    throw FlagError("--times", o.times,
                    "every time must be a whole multiple of 1/N s for some N <= " + std::to_string(kMaxLandingFps) +
                        " (e.g. 0.125 or 0.4) so that the simulation can land on it exactly");
  overrides.push_back(number_override("time.fps", *fps));
  // No need to simulate past the last cell (time.duration must stay > 0).
  if (times.back() > 0) overrides.push_back(number_override("time.duration", times.back()));
  return load_scene(o.scene, overrides);
}

// The last part of a scene path, for the cells' labels: "solver.boundary_pressure" and
// "/solver/boundary_pressure" both say "boundary_pressure" (the cells are narrow).
std::string short_key(const std::string& key) {
  const size_t cut = key.find_last_of("./");
  return cut == std::string::npos || cut + 1 == key.size() ? key : key.substr(cut + 1);
}

// "t = 0.40 s": two decimals, more where the time needs them (0.125 is not 0.13).
std::string time_label(double t) {
  char buf[40];
  for (int digits = 2; digits <= 6; ++digits) {
    std::snprintf(buf, sizeof buf, "t = %.*f s", digits, t);
    if (std::strtod(buf + 4, nullptr) == t) break;
  }
  return buf;
}

// The default goes to the scene's output directory, created as `render` and `simulate`
// create it. An explicit -o names a file: a folder that does not exist there is more
// likely a typo than a wish, so it is refused rather than created.
fs::path output_path(const MontageOptions& o, const Scene& scene) {
  if (o.output.empty()) {
    make_directory(scene.output.directory);
    return fs::path(scene.output.directory) / "montage.png";
  }
  const fs::path out(o.output);
  if (fs::is_directory(out)) throw OutputError(out.string() + ": is a directory; -o takes the PNG file to write");
  if (out.has_parent_path() && !fs::is_directory(out.parent_path()))
    throw OutputError(out.string() + ": folder " + out.parent_path().string() +
                      " does not exist; create it first or choose another -o");
  return out;
}

// One fresh run of `scene`, a cell at each time, appended to `cells`.
void render_variant(const Scene& scene, const ImageConfig& config, const std::vector<double>& times,
                    const std::string& variant_label, Overlay overlay, std::vector<MontageCell>& cells) {
  FrameRenderer renderer(config.frame);  // before the run: EGL problems show at once
  Simulation sim(scene);
  FrameBuilder builder(config, sim);
  StepStats st;
  bool stepped = false;
  for (double t : times) {
    while (sim.time() < t && !sim.finished()) {
      st = sim.step();
      stepped = true;
    }
    if (sim.time() != t)  // landing_fps() makes every time a frame time
      throw std::logic_error("montage: the run is at t = " + number_text(sim.time()) + " s instead of " +
                             number_text(t) + " s");
    MontageCell cell;
    renderer.render(builder.build(sim, sim.frame(), stepped ? &st : nullptr), cell.image);
    if (overlay != Overlay::none) cell.labels.push_back(time_label(t));
    if (overlay == Overlay::full)
      cell.labels.push_back("frame " + std::to_string(sim.frame()) + "   step " + std::to_string(sim.steps()) +
                            "   iterations " + std::to_string(stepped ? st.iterations : 0));
    if (!variant_label.empty()) cell.labels.push_back(variant_label);
    cells.push_back(std::move(cell));
  }
}

}  // namespace

int run_montage(const MontageOptions& o) {
  set_threads(o.threads);
  if (o.cols < 0) throw FlagError("--cols", std::to_string(o.cols), "expected an integer >= 1");
  const std::vector<double> times = parse_times(o.times);
  const Variation vary = parse_vary(o.vary);
  const Overlay overlay = parse_overlay(o.overlay);
  int cell_w = 0, cell_h = 0;
  parse_resolution(o.cell, cell_w, cell_h, "--cell");

  // Every variant's scene before any run: a bad value of the last one shows at once.
  const size_t count = vary.key.empty() ? 1 : vary.values.size();
  const int columns = o.cols > 0         ? o.cols
                      : vary.key.empty() ? std::min<int>(4, static_cast<int>(times.size()))
                                         : static_cast<int>(times.size());
  // The montage's size before any run: a grid too large to write fails only at the end.
  const MontageLayout layout = montage_layout(cell_w, cell_h, static_cast<int>(times.size() * count), columns,
                                              vary.key.empty() ? 1 : 2, !o.title.empty(), MontageColorbar{});
  if (layout.width > kMaxMontageSide || layout.height > kMaxMontageSide)
    throw FlagError("--cell", o.cell,
                    "the montage would be " + std::to_string(layout.width) + "x" + std::to_string(layout.height) +
                        " pixels; the limit is " + std::to_string(kMaxMontageSide) +
                        " on each side (use a smaller --cell, other --cols, or fewer --times)");
  std::vector<Scene> scenes;
  for (size_t v = 0; v < count; ++v) {
    scenes.push_back(load_variant(o, times, vary, v));
    check_memory(scenes.back());
  }

  ImageOptions image;
  image.resolution = o.cell;
  image.color_by = o.color_by;
  image.colormap = o.colormap;
  image.range = o.range;
  image.no_overlay = true;   // the label band says the time
  image.no_colorbar = true;  // one shared colorbar on the montage instead
  // One colour range for all cells, the first variant's: the variants differ in the very
  // setting being compared, and per-variant ranges would hide that difference.
  const ImageConfig first = resolve_image(image, scenes.front());
  const fs::path out = output_path(o, scenes.front());

  std::vector<MontageCell> cells;
  for (size_t v = 0; v < count; ++v) {
    ImageConfig config = resolve_image(image, scenes[v]);
    config.lo = first.lo;
    config.hi = first.hi;
    const std::string label = vary.key.empty() ? "" : short_key(vary.key) + " = " + vary.values[v];
    std::fprintf(stderr, "sluice: montage run %zu of %zu%s%s: %zu fluid particles to t = %g s\n", v + 1, count,
                 label.empty() ? "" : ", ", label.c_str(), scenes[v].fluid_x.size(), times.back());
    try {
      render_variant(scenes[v], config, times, label, overlay, cells);
    } catch (const SimulationUnstable& e) {
      throw SimulationUnstable(std::string(e.what()) + " (montage run " + std::to_string(v + 1) +
                               (label.empty() ? "" : ", " + label) + "); no montage written");
    }
  }

  const MontageColorbar bar{first.frame.colormap, first.lo, first.hi, first.frame.field_label};
  const Image montage = compose_montage(cells, columns, o.title, bar);
  write_png(out.string(), montage);
  std::fprintf(stderr, "sluice: wrote %s (%zu cells, %dx%d)\n", out.c_str(), cells.size(), montage.width,
               montage.height);
  return 0;
}

}  // namespace sluice::app
