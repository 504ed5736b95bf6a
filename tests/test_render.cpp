// Image regression of the headless renderer: a 300-particle dam break rendered at
// 320x180 and compared with golden PNGs in tests/golden/.
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

struct Case {
  const char* golden;
  Index frame;
  ColormapName colormap;
  bool speed;  // colour by speed (0..max) instead of CFL (0..1)
  int msaa;
};

FrameData frame_data(const Simulation& sim, const StepStats& last, bool speed, std::vector<float>& values) {
  const FluidParticles& f = sim.fluid();
  values.resize(f.x.size());
  double vmax = 0;
  for (size_t i = 0; i < values.size(); ++i) {
    const double v = speed ? f.v[i].norm() : f.v[i].norm() * last.dt / sim.scene().spacing;
    values[i] = static_cast<float>(v);
    vmax = std::max(vmax, v);
  }
  FrameData d;
  d.fluid_xy = {f.x.front().data(), 2 * f.x.size()};
  d.fluid_value = values;
  d.boundary_xy = {sim.boundary().x.front().data(), 2 * sim.boundary().x.size()};
  d.diameter = sim.scene().spacing;
  d.hi = speed ? (vmax > 0 ? vmax : 1.0) : 1.0;
  char buf[96];
  std::snprintf(buf, sizeof buf, "T = %.3f S   FRAME %d   STEP %ld", sim.time(), sim.frame(), sim.steps());
  d.overlay = buf;
  return d;
}

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

TEST(RenderGolden, DamBreakFrames) {
  const Case cases[] = {
      {"render_frame0_cfl_spectrum.png", 0, ColormapName::spectrum, false, 0},
      {"render_frame3_cfl_spectrum.png", 3, ColormapName::spectrum, false, 0},
      {"render_frame6_speed_turbo_msaa4.png", 6, ColormapName::turbo, true, 4},
  };
  const Scene scene = parse_scene(kScene, "render_test.json");
  ASSERT_GT(scene.fluid_x.size(), 200u);
  Simulation sim(scene);
  StepStats last;
  last.dt = scene.time.dt;
  std::vector<float> values;
  for (const Case& c : cases) {
    while (sim.frame() < c.frame) last = sim.step();
    FrameSettings s;
    s.width = 320;
    s.height = 180;
    s.msaa = c.msaa;
    s.colormap = c.colormap;
    s.field_label = c.speed ? "SPEED M/S" : "CFL";
    s.bounds_min[0] = scene.bounds_min.x();
    s.bounds_min[1] = scene.bounds_min.y();
    s.bounds_max[0] = scene.bounds_max.x();
    s.bounds_max[1] = scene.bounds_max.y();
    FrameRenderer renderer(s);  // throws RenderError naming every EGL platform tried
    Image img;
    renderer.render(frame_data(sim, last, c.speed, values), img);
    ASSERT_EQ(img.width, 320);
    ASSERT_EQ(img.height, 180);
    check_against_golden(img, c.golden);
  }
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
