// Image regression of the headless renderer: frames of a 300-particle dam break and of
// a swinging paddle, rendered at 320x180 through the program's own path (src/view) and
// compared with golden PNGs in tests/golden/.
//
// Tolerance: at most 0.5% of the pixels may differ by more than 8 levels in a channel.
// Mesa's llvmpipe renders bit-identically (CI); a GPU driver may differ by a few levels
// at disc edges. On failure the actual image and a diff image are written next to the
// test binary (render_failures/) and their paths printed.
// Refresh the goldens (after an intended change of the picture):
//   SLUICE_UPDATE_GOLDENS=1 build/sluice_render_tests --gtest_filter='RenderGolden.*'
// Without an EGL display these tests fail with the EGL error; they never skip.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "render/colormap.h"
#include "render/font.h"
#include "render/frame.h"
#include "render/image.h"
#include "render/video.h"
#include "scene/scene.h"
#include "solver/simulation.h"
#include "temp_dir.h"
#include "test_process.h"
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

// The rule of `sluice compare --preset tests` (one constant: they cannot drift apart).
constexpr int kTolerance = kTestsRule.tolerance;
constexpr double kMaxFraction = kTestsRule.max_fraction;

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

// --- Text (no EGL) -------------------------------------------------------------------

long ink(const Image& img) {
  long n = 0;
  for (size_t i = 0; i < img.rgb.size(); i += 3) n += img.rgb[i] < 128;
  return n;
}

Image text_image(const std::string& text, int px) {
  Image img(text_width(text, px) + 4, line_height(px) + 4);
  fill_rect(img, 0, 0, img.width, img.height, {255, 255, 255});
  draw_text(img, 2, 2, text, px, {0, 0, 0});
  return img;
}

TEST(Font, MixedCaseDrawsWithInk) {
  const Image lower = text_image("t = 0.500 s", 20), upper = text_image("T = 0.500 S", 20);
  EXPECT_GT(ink(lower), 50);
  EXPECT_GT(ink(upper), 50);
  EXPECT_NE(lower.rgb, upper.rgb);  // lower case is its own glyphs, not capitals
  // Proportional: "m" is wider than "i" (the bitmap font gave every glyph 6 columns).
  EXPECT_GT(text_width("mmmm", 20), text_width("iiii", 20) + 20);
  // Text grows with its size.
  EXPECT_GT(text_width("speed [m/s]", 40), text_width("speed [m/s]", 20) + 60);
}

TEST(Font, MiddleDotAndBracketsAreGlyphsNotBoxes) {
  // U+FFFF is not in the font: it draws as the missing-glyph box, which has more ink
  // than a middle dot and differs from it.
  const Image dot = text_image("\u00b7", 30), missing = text_image("\uffff", 30);
  EXPECT_GT(ink(dot), 0);
  EXPECT_LT(ink(dot), ink(missing));
  EXPECT_NE(text_image("Pa\u00b7m", 20).rgb, text_image("Pa m", 20).rgb);
  EXPECT_NE(text_image("[", 30).rgb, text_image("\uffff", 30).rgb);
}

TEST(Font, FitTextSizeShrinksToTheWidth) {
  const std::string label = "density error [%]";
  const int px = fit_text_size(label, 20, 100);
  EXPECT_LT(px, 20);
  EXPECT_LE(text_width(label, px), 100);
  EXPECT_EQ(fit_text_size("CFL", 20, 100), 20);
}

// --- Colorbar ticks (no EGL) -----------------------------------------------------------

// True when v / step is an integer and step is 1, 2 or 5 times a power of ten.
bool round_multiple(double v, double step) {
  const double p = std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  const double m = step / p;
  const bool one_two_five = std::fabs(m - 1) < 1e-9 || std::fabs(m - 2) < 1e-9 || std::fabs(m - 5) < 1e-9;
  return one_two_five && std::fabs(v / step - std::round(v / step)) < 1e-6;
}

TEST(ColorbarTicks, AreOneTwoFiveMultiplesInsideTheRange) {
  const double ranges[][2] = {{0, 3.962}, {0, 1}, {0, 19620}, {-0.37, 0.81}, {0, 6.264}, {1e-5, 3e-5}, {100, 101}};
  for (const auto& r : ranges) {
    const double step = nice_step(r[0], r[1]);
    const std::vector<double> ticks = nice_ticks(r[0], r[1]);
    ASSERT_GE(ticks.size(), 3u) << r[0] << ":" << r[1];
    EXPECT_LE(ticks.size(), 7u) << r[0] << ":" << r[1];
    for (double t : ticks) {
      EXPECT_TRUE(round_multiple(t, step)) << t << " step " << step;
      EXPECT_GE(t, r[0] - 1e-12);
      EXPECT_LE(t, r[1] + 1e-12);
    }
  }
  EXPECT_TRUE(nice_ticks(1, 1).empty());  // no range, no ticks (and no endless loop)
  EXPECT_TRUE(nice_ticks(0, HUGE_VAL).empty());
  // The issue's range: 0..3.962 had ticks at its quarters (0.9905, 1.981, ...).
  EXPECT_EQ(nice_ticks(0, 3.962), (std::vector<double>{0, 1, 2, 3}));
}

TEST(ColorbarTicks, LabelsHaveTheStepsDecimals) {
  EXPECT_EQ(tick_label(0, 0.2), "0");
  EXPECT_EQ(tick_label(0.6000000000000001, 0.2), "0.6");
  EXPECT_EQ(tick_label(0.25, 0.05), "0.25");
  EXPECT_EQ(tick_label(15000, 5000), "15000");
  EXPECT_EQ(tick_label(2e-5, 1e-5), "2.0e-05");
}

// --- Layout (EGL) ------------------------------------------------------------------------

// The rightmost column of row `y` holding the walls' grey.
int rightmost_wall(const Image& img, int y) {
  for (int x = img.width - 1; x >= 0; --x) {
    const std::uint8_t* p = img.at(x, y);
    if (p[0] == 150 && p[1] == 150 && p[2] == 150) return x;
  }
  return -1;
}

Image still_at_start(const Scene& scene, const view::ImageOptions& o) {
  Simulation sim(scene);
  const view::ImageConfig config = view::resolve_image(o, scene);
  FrameRenderer renderer(config.frame);
  view::FrameBuilder builder(config, sim);
  Image img;
  renderer.render(builder.build(sim, 0, nullptr), img);
  return img;
}

TEST(RenderLayout, TankLinesUpAcrossColourFields) {
  const Scene scene = parse_scene(kScene, "render_test.json");
  view::ImageOptions a = options("speed", "spectrum", 0), b = options("density_error", "spectrum", 0);
  a.resolution = b.resolution = "1280x720";
  const Image ia = still_at_start(scene, a), ib = still_at_start(scene, b);
  const FrameLayout L = fit_layout(view::resolve_image(a, scene).frame);
  const int y = (L.scene_y0 + L.scene_y1) / 2;
  ASSERT_GT(rightmost_wall(ia, y), 0);
  EXPECT_EQ(rightmost_wall(ia, y), rightmost_wall(ib, y));
  // The same scene pixels, apart from the colours of the fluid (both blue at rest: equal).
  for (int row = L.band_h; row < 720; row += 37)
    for (int x = 0; x < L.strip_x; ++x) ASSERT_EQ(0, std::memcmp(ia.at(x, row), ib.at(x, row), 3)) << x << "," << row;
  // The colorbar sits beside the tank: the issue measured 240 px of white between them.
  EXPECT_LT(L.bar_x - L.scene_x1, 3 * L.text_px);
  EXPECT_GT(L.bar_x, L.scene_x1);
}

TEST(RenderLayout, OverlayBandDoesNotGrowWithItsText) {
  FrameSettings s;
  s.width = 640;
  s.height = 360;
  s.bounds_max[0] = 0.4;
  s.bounds_max[1] = 0.25;
  FrameRenderer r(s);
  const std::vector<double> xy = {0.1, 0.1, 0.2, 0.1};
  const std::vector<float> v = {0.2f, 0.8f};
  FrameData d;
  d.fluid_xy = xy;
  d.fluid_value = v;
  d.diameter = 0.01;
  Image early, late;
  d.overlay = view::overlay_text(view::Overlay::full, 0.0, 0, 0, 0);
  r.render(d, early);
  d.overlay = view::overlay_text(view::Overlay::full, 12.345, 1234, 1234567, 87);
  r.render(d, late);
  const FrameLayout& L = r.layout();
  ASSERT_GT(L.band_h, 0);
  // Everything below the band is the same pixels; the band spans the image at one height.
  EXPECT_EQ(0, std::memcmp(early.at(0, L.band_h), late.at(0, L.band_h), 3u * 640 * (360 - L.band_h)));
  for (const Image* img : {&early, &late})
    for (int y = 0; y < L.band_h - 1; ++y) EXPECT_EQ(img->at(639, y)[0], 245) << "row " << y;
  EXPECT_NE(early.rgb, late.rgb);
}

TEST(RenderLayout, OverlayModesAndTitleRows) {
  EXPECT_EQ(view::overlay_text(view::Overlay::time, 0.5, 10, 500, 3), "t = 0.500 s");
  EXPECT_EQ(view::overlay_text(view::Overlay::none, 0.5, 10, 500, 3), "");
  EXPECT_EQ(view::overlay_text(view::Overlay::full, 0.5, 10, 500, 3).rfind("t = 0.500 s", 0), 0u);
  const Scene scene = parse_scene(kScene, "render_test.json");
  view::ImageOptions o = options("cfl", "spectrum", 0);
  const int one_row = fit_layout(view::resolve_image(o, scene).frame).band_h;
  o.title = "Dam break";
  const int two_rows = fit_layout(view::resolve_image(o, scene).frame).band_h;
  o.title.clear();
  o.overlay = "none";
  const int none = fit_layout(view::resolve_image(o, scene).frame).band_h;
  EXPECT_EQ(none, 0);
  EXPECT_GT(one_row, 0);
  EXPECT_GT(two_rows, one_row + one_row / 2);
  o.overlay = "sometimes";
  EXPECT_THROW(view::resolve_image(o, scene), view::FlagError);
}

// --- Render options: particle scale, background, object colours (EGL) --------------------

long count_colour(const Image& img, Rgb c) {
  long n = 0;
  for (size_t i = 0; i < img.rgb.size(); i += 3)
    n += img.rgb[i] == c.r && img.rgb[i + 1] == c.g && img.rgb[i + 2] == c.b;
  return n;
}

long count_not(const Image& img, Rgb c) { return static_cast<long>(img.rgb.size() / 3) - count_colour(img, c); }

TEST(RenderOptions, ParticleScaleGrowsTheDiscs) {
  const Scene scene = parse_scene(kScene, "render_test.json");
  view::ImageOptions small = options("cfl", "spectrum", 0), big = small;
  small.overlay = big.overlay = "none";
  small.no_colorbar = big.no_colorbar = true;
  small.particle_scale = 0.5;
  big.particle_scale = 1.0;
  // Discs of half the spacing cover about a quarter of the area, with white between them.
  const long covered_small = count_not(still_at_start(scene, small), {255, 255, 255});
  const long covered_big = count_not(still_at_start(scene, big), {255, 255, 255});
  EXPECT_LT(covered_small, covered_big * 2 / 3);
  small.particle_scale = 0;
  EXPECT_THROW(view::resolve_image(small, scene), view::FlagError);
}

TEST(RenderOptions, BackgroundAndObjectColours) {
  const Scene scene = parse_scene(kScene, "render_test.json");
  view::ImageOptions o = options("cfl", "spectrum", 0);
  o.background = "black";
  o.object_colors = {"tank=#d04040"};
  const Image img = still_at_start(scene, o);
  EXPECT_LT(count_colour(img, {255, 255, 255}), 50);  // no white background left
  const std::uint8_t* corner = img.at(0, img.height - 1);
  EXPECT_EQ(corner[0] + corner[1] + corner[2], 0);
  EXPECT_GT(count_colour(img, {208, 64, 64}), 200);  // the tank in its colour
  const FrameLayout L = fit_layout(view::resolve_image(o, scene).frame);
  EXPECT_EQ(rightmost_wall(img, (L.scene_y0 + L.scene_y1) / 2), -1);  // and no grey wall left
  // Light labels on the dark background: the colorbar strip holds near-white ink.
  long light = 0;
  for (int y = L.bar_y; y < L.bar_y + L.bar_h; ++y)
    for (int x = L.bar_x + L.bar_w + 1; x < img.width; ++x) light += img.at(x, y)[0] > 120;
  EXPECT_GT(light, 30);
  EXPECT_EQ(ink_on({255, 255, 255}).r, 25);
}

std::string flag_error_of(const view::ImageOptions& o, const Scene& scene) {
  try {
    view::resolve_image(o, scene);
  } catch (const view::FlagError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(RenderOptions, BadColoursNameTheFlagAndWhatIsAllowed) {
  const Scene scene = parse_scene(kScene, "render_test.json");
  view::ImageOptions o;
  o.background = "purple2";
  EXPECT_EQ(flag_error_of(o, scene).rfind("--background purple2: expected #rrggbb or one of white", 0), 0u);
  o.background = "#12345g";
  EXPECT_NE(flag_error_of(o, scene).find("#rrggbb"), std::string::npos);
  o.background = "#102030";
  o.object_colors = {"paddle=red"};
  EXPECT_EQ(flag_error_of(o, scene), "--object-color paddle=red: no object paddle in the scene; its objects: tank");
  o.object_colors = {"tank"};
  EXPECT_NE(flag_error_of(o, scene).find("expected NAME=COLOUR"), std::string::npos);
  EXPECT_EQ(view::parse_color("#102030")->g, 0x20);
  EXPECT_EQ(view::parse_color("FFFFFF")->b, 255);
  EXPECT_FALSE(view::parse_color("").has_value());
}

// --- Video formats (no EGL) ------------------------------------------------------------

bool has(const std::vector<std::string>& args, const std::string& a) {
  return std::find(args.begin(), args.end(), a) != args.end();
}

TEST(Video, FormatsAndQualityReachFfmpeg) {
  VideoJob job;
  job.frames_pattern = "d/frames/f_%03d.png";
  job.output = "d/run.webm";
  job.format = VideoFormat::webm;
  job.crf = 40;
  std::vector<std::string> a = ffmpeg_arguments(job);
  EXPECT_TRUE(has(a, "libvpx-vp9"));
  EXPECT_TRUE(has(a, "40"));
  EXPECT_TRUE(has(a, "d/frames/f_%03d.png"));
  EXPECT_EQ(a.back(), "d/run.webm.tmp.webm");
  job.format = VideoFormat::gif;
  job.output = "d/run.gif";
  a = ffmpeg_arguments(job);
  EXPECT_FALSE(has(a, "-crf"));
  EXPECT_EQ(a.back(), "d/run.gif.tmp.gif");
  job.format = VideoFormat::mp4;
  job.crf = -1;
  a = ffmpeg_arguments(job);
  EXPECT_TRUE(has(a, "libx264"));
  EXPECT_TRUE(has(a, "18"));  // the default CRF
  VideoFormat f;
  EXPECT_FALSE(parse_video_format("avi", f));
  EXPECT_TRUE(parse_video_format("gif", f));
  EXPECT_EQ(f, VideoFormat::gif);
}

// --- The program's render flags ----------------------------------------------------------

std::vector<std::string> tiny_render(const fs::path& out, const std::vector<std::string>& extra) {
  std::vector<std::string> a = {"render",
                                std::string(SLUICE_SOURCE_DIR) + "/scenes/column.json",
                                "-o",
                                out.string(),
                                "--set",
                                "spacing=0.04",
                                "--set",
                                "time.duration=0.2",
                                "--resolution",
                                "160x90",
                                "-q"};
  a.insert(a.end(), extra.begin(), extra.end());
  return a;
}

// One line "sluice: ..." naming the flag, its value and what is allowed; exit 1.
void expect_flag_error(const std::vector<std::string>& extra, const std::vector<std::string>& words) {
  const test::CaseDir dir;
  const test::Result r = test::run_sluice(dir, tiny_render(dir.work() / "out", extra));
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_EQ(r.err.rfind("sluice: ", 0), 0u) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  for (const std::string& w : words) EXPECT_NE(r.err.find(w), std::string::npos) << "no '" << w << "' in: " << r.err;
}

TEST(RenderFlags, BadValuesAreOneLineNamingTheFlag) {
  expect_flag_error({"--format", "avi"}, {"--format avi", "mp4, webm, gif"});
  expect_flag_error({"--crf", "60"}, {"--crf 60", "0 (best) to 51"});
  expect_flag_error({"--crf", "5", "--format", "gif"}, {"--crf 5", "GIF has no CRF"});
  expect_flag_error({"--crf", "-3"}, {"--crf", "-3"});
  expect_flag_error({"--frame-pattern", "frame.png"}, {"--frame-pattern frame.png", "%0Nd"});
  expect_flag_error({"--frame-pattern", "f_%05d.jpg"}, {"--frame-pattern f_%05d.jpg"});
  expect_flag_error({"--frame-pattern", "f_%s.png"}, {"--frame-pattern f_%s.png"});
  expect_flag_error({"--particle-scale", "0"}, {"--particle-scale", "'0'"});
  expect_flag_error({"--background", "purple2"}, {"--background purple2", "#rrggbb"});
  expect_flag_error({"--object-color", "nope=red"}, {"--object-color nope=red", "its objects:"});
  expect_flag_error({"--overlay", "some"}, {"--overlay", "some"});
}

TEST(RenderFlags, GifAndWebmWithAFramePattern) {
  const test::CaseDir cases;
  const fs::path dir = cases.work();
  test::Result r = test::run_sluice(
      cases, tiny_render(dir / "gif", {"--format", "gif", "--frame-pattern", "shot-%03d.png", "--overlay", "time",
                                       "--title", "Column", "--particle-scale", "1.5"}));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "gif" / "frames" / "shot-000.png"));
  EXPECT_TRUE(fs::exists(dir / "gif" / "frames" / "shot-004.png"));
  EXPECT_FALSE(fs::exists(dir / "gif" / "frames" / "frame_00000.png"));
  std::ifstream gif(dir / "gif" / "column.gif", std::ios::binary);
  char magic[6] = {};
  gif.read(magic, 6);
  EXPECT_EQ(std::string(magic, 6), "GIF89a");
  r = test::run_sluice(cases, tiny_render(dir / "webm", {"--format", "webm", "--crf", "40"}));
  ASSERT_EQ(r.status, 0) << r.err;
  std::ifstream webm(dir / "webm" / "column.webm", std::ios::binary);
  unsigned char ebml[4] = {};
  webm.read(reinterpret_cast<char*>(ebml), 4);
  EXPECT_EQ(ebml[0], 0x1A);  // the EBML (Matroska/WebM) signature 1A 45 DF A3
  EXPECT_EQ(ebml[1], 0x45);
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
  const sluice::test::TempDir dir;
  const fs::path p = dir.path() / "roundtrip.png";
  write_png(p.string(), img);
  const Image back = read_png(p.string());
  EXPECT_EQ(back.rgb, img.rgb);
  fs::remove(p);
}

}  // namespace
}  // namespace sluice
