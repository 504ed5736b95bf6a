// Image regression of the headless renderer: frames of a 300-particle dam break and of
// a swinging paddle, rendered at 320x180 through the program's own path (src/view) and
// compared with golden PNGs in tests/golden/.
//
// Tolerance: at most 0.5% of the pixels may differ by more than 8 levels in a channel.
// Mesa's llvmpipe renders bit-identically (CI); a GPU driver may differ by a few levels
// at disc edges. On failure the actual image and a diff image are written next to the
// test binary (render_failures/) and their paths printed.
// Refresh the goldens (after an intended change of the picture):
//   SLUICE_UPDATE_GOLDENS=1 build/sluice_tests --gtest_filter='RenderGolden.*'
// Without an EGL display these tests fail with the EGL error; they never skip.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

#include "render/colormap.h"
#include "render/frame.h"
#include "render/image.h"
#include "scene/scene.h"
#include "sim/simulation.h"
#include "view/scene_view.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using namespace sluice::render;

const char* kScene = R"({
  "name": "render_test",
  "spacing": 0.01,
  "solver": { "type": "iisph" },
  "time": { "duration": 0.3, "fps": 20, "dt": 1e-3 },
  "output": { "export": [] },
  "fluid": [ { "shape": "rectangle", "min": [0, 0], "max": [0.15, 0.2] } ],
  "boundaries": [ { "name": "tank", "shape": "box", "min": [0, 0], "max": [0.4, 0.25], "lid": false, "layers": 2 } ]
})";

constexpr int kTolerance = 8;
constexpr double kMaxFraction = 0.005;

void check_against_golden(const Image& actual, const std::string& name) {
  const fs::path golden = fs::path(SLUICE_SOURCE_DIR) / "tests" / "golden" / name;
  const char* update = std::getenv("SLUICE_UPDATE_GOLDENS");
  if (update && std::string(update) == "1") {
    write_png(golden.string(), actual);
    std::printf("updated %s\n", golden.c_str());
    return;
  }
  ASSERT_TRUE(fs::exists(golden)) << golden << " is missing; create it with SLUICE_UPDATE_GOLDENS=1";
  const Image expected = read_png(golden.string());
  const CompareResult r = compare_images(actual, expected, kTolerance, kMaxFraction);
  if (r.passed) return;
  const fs::path dir = fs::absolute("render_failures");
  fs::create_directories(dir);
  const fs::path actual_path = dir / name, diff_path = dir / ("diff_" + name);
  write_png(actual_path.string(), actual);
  write_png(diff_path.string(), diff_image(actual, expected, kTolerance));
  ADD_FAILURE() << name << ": " << r.differing << " of " << r.total << " pixels differ by more than " << kTolerance
                << " levels (largest difference " << r.max_difference << ", sizes "
                << (r.same_size ? "equal" : "differ") << ")\n  actual: " << actual_path << "\n  diff:   " << diff_path
                << "\n  golden: " << golden;
}

// Renders frames of `scene` through the program's own path (image options over the
// scene's render section, automatic range, FrameBuilder) and compares each with its golden.
struct Case {
  const char* golden;
  Index frame;
  view::ImageOptions options;
};

void check_frames(const Scene& scene, const std::vector<Case>& cases) {
  Simulation sim(scene);
  StepStats last;
  bool stepped = false;
  for (const Case& c : cases) {
    while (sim.frame() < c.frame) {
      last = sim.step();
      stepped = true;
    }
    const view::ImageConfig config = view::resolve_image(c.options, scene);
    FrameRenderer renderer(config.frame);  // throws RenderError naming every EGL platform tried
    view::FrameBuilder builder(config, sim);
    Image img;
    renderer.render(builder.build(sim, sim.frame(), stepped ? &last : nullptr), img);
    ASSERT_EQ(img.width, config.frame.width);
    ASSERT_EQ(img.height, config.frame.height);
    check_against_golden(img, c.golden);
  }
}

view::ImageOptions options(const char* color_by, const char* colormap, int msaa) {
  view::ImageOptions o;
  o.resolution = "320x180";
  o.color_by = color_by;
  o.colormap = colormap;
  o.msaa = msaa;
  return o;
}

TEST(RenderGolden, DamBreakFrames) {
  const Scene scene = parse_scene(kScene, "render_test.json");
  ASSERT_GT(scene.fluid_x.size(), 200u);
  check_frames(scene, {{"render_frame0_cfl_spectrum.png", 0, options("cfl", "spectrum", 0)},
                       {"render_frame3_cfl_spectrum.png", 3, options("cfl", "spectrum", 0)},
                       {"render_frame6_speed_turbo_msaa4.png", 6, options("speed", "turbo", 4)}});
}

// A moving boundary (a paddle swinging into the fluid) drawn in its own colour, a view
// window from the scene's render section, pressure on viridis with the automatic range.
TEST(RenderGolden, MovingBoundaryAndViewWindow) {
  const Scene scene = parse_scene(R"({
    "spacing": 0.01, "time": {"duration": 0.3, "fps": 20, "dt": 1e-3},
    "render": {"resolution": [320, 180], "view": {"min": [0, 0], "max": [0.32, 0.18]}, "color_by": "pressure", "colormap": "viridis"},
    "fluid": [{"shape": "rectangle", "min": [0.06, 0], "max": [0.4, 0.12]}],
    "boundaries": [{"name": "tank", "shape": "box", "min": [0, 0], "max": [0.4, 0.25]},
                   {"name": "paddle", "shape": "polygon", "points": [[0.03, 0], [0.05, 0], [0.05, 0.2], [0.03, 0.2]],
                    "motion": {"type": "oscillation", "angular_amplitude": 0.3, "pivot": [0.04, 0], "period": 0.8}}]})",
                                 "render_moving.json");
  view::ImageOptions from_scene;  // every image setting from the scene's render section
  check_frames(scene, {{"render_moving_frame4_pressure_viridis.png", 4, from_scene}});
}

TEST(RenderCompare, CountsPixelsBeyondTolerance) {
  Image a(10, 10), b(10, 10);
  b.at(3, 4)[1] = 5;
  b.at(5, 5)[2] = 20;
  CompareResult r = compare_images(a, b, 8, 0.0);
  EXPECT_TRUE(r.same_size);
  EXPECT_EQ(r.differing, 1);
  EXPECT_EQ(r.max_difference, 20);
  EXPECT_FALSE(r.passed);
  EXPECT_TRUE(compare_images(a, b, 8, 0.01).passed);
  EXPECT_TRUE(compare_images(a, b, 20, 0.0).passed);
  EXPECT_FALSE(compare_images(a, Image(10, 11), 255, 1.0).passed);
}

TEST(RenderColormap, EndpointsAndPngRoundTrip) {
  const Colormap spectrum(ColormapName::spectrum);
  EXPECT_EQ(spectrum.at(0).b, 255);
  EXPECT_EQ(spectrum.at(0).r, 0);
  EXPECT_EQ(spectrum.at(1).r, 255);
  EXPECT_EQ(spectrum.at(1).b, 0);
  EXPECT_EQ(spectrum.at(0.5).g, 255);
  const Colormap viridis(ColormapName::viridis);  // dark purple to yellow
  EXPECT_LT(viridis.at(0).g, 20);
  EXPECT_GT(viridis.at(1).r, 230);
  Image img(7, 3);
  for (size_t i = 0; i < img.rgb.size(); ++i) img.rgb[i] = static_cast<std::uint8_t>(i * 13);
  const fs::path p = fs::temp_directory_path() / "sluice_roundtrip.png";
  write_png(p.string(), img);
  const Image back = read_png(p.string());
  EXPECT_EQ(back.rgb, img.rgb);
  fs::remove(p);
}

}  // namespace
}  // namespace sluice
