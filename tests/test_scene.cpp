// Scene loader: shipped scenes, validation messages, overrides, boundary sampling and
// fluid removal.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "solver/leak_check.h"

namespace sluice {
namespace {

const std::string kFile = "scenes/x.json";

// A valid scene around `extra` top-level members (each ending with a comma).
std::string scene_with(const std::string& extra,
                       const std::string& fluid = R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 1]}])") {
  return "{" + extra + R"("spacing": 0.1, "fluid": )" + fluid + "}";
}

std::string error_of(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, kFile, overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

std::vector<Vec2> samples_of(const Scene& s, Index object) {
  const auto& o = s.objects.at(static_cast<std::size_t>(object));
  return {s.boundary_x.begin() + o.first, s.boundary_x.begin() + o.first + o.count};
}

double min_pair_distance(const std::vector<Vec2>& pts) {
  double d = INFINITY;
  for (std::size_t i = 0; i < pts.size(); ++i)
    for (std::size_t j = i + 1; j < pts.size(); ++j) d = std::min(d, (pts[i] - pts[j]).norm());
  return d;
}

// --- shipped scenes ---------------------------------------------------------------------------

TEST(SceneFiles, ShippedScenesLoad) {
  const std::vector<std::pair<std::string, std::size_t>> files = {
      {"dam_break", 20000}, {"dam_break_130k", 256 * 513}, {"column", 5000}, {"hydrostatic", 2000}};
  for (const auto& [name, count] : files) {
    SCOPED_TRACE(name);
    const auto start = std::chrono::steady_clock::now();
    const Scene s = load_scene(std::string(SLUICE_SOURCE_DIR) + "/scenes/" + name + ".json");
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 5.0);  // about 0.1 s for 130k particles in a Release build
    EXPECT_EQ(s.name, name);
    EXPECT_EQ(s.fluid_x.size(), count);
    EXPECT_EQ(s.fluid_v.size(), count);
    EXPECT_EQ(s.fluid_removed, 0);
    EXPECT_EQ(s.solver.boundary_pressure, BoundaryPressure::Solved);  // the default
    EXPECT_EQ(s.boundary_object.size(), s.boundary_x.size());
    ASSERT_EQ(s.objects.size(), 1u);
    EXPECT_EQ(s.objects[0].count, static_cast<Index>(s.boundary_x.size()));
  }
}

TEST(SceneFiles, DamBreakGeometry) {
  const Scene s = load_scene(std::string(SLUICE_SOURCE_DIR) + "/scenes/dam_break.json");
  EXPECT_EQ(s.spacing, 0.01);
  EXPECT_EQ(s.solver.type, SolverType::IISPH);
  EXPECT_EQ(s.time.dt, 5e-4);
  EXPECT_EQ(s.time.duration, 4.0);
  EXPECT_EQ(s.time.fps, 30.0);
  EXPECT_EQ(s.output.directory, "renders/dam_break");

  double low = INFINITY, left = INFINITY, high = -INFINITY, right = -INFINITY;
  for (const Vec2& p : s.fluid_x) {
    low = std::min(low, p.y());
    left = std::min(left, p.x());
    high = std::max(high, p.y());
    right = std::max(right, p.x());
  }
  EXPECT_NEAR(low, 0.005, 1e-12);
  EXPECT_NEAR(left, 0.005, 1e-12);
  EXPECT_NEAR(high, 1.995, 1e-12);
  EXPECT_NEAR(right, 0.995, 1e-12);

  // Closed tank (lid): layer 0 is the square half a spacing outside [0, 4]^2 (4 sides of
  // 4.01 m, 401 intervals each), layer 1 the square 1.5 spacings outside (403 each).
  std::size_t floor0 = 0, floor1 = 0;
  for (const Vec2& p : s.boundary_x) {
    if (std::abs(p.y() + 0.005) < 1e-12) ++floor0;
    if (std::abs(p.y() + 0.015) < 1e-12) ++floor1;
  }
  EXPECT_EQ(floor0, 402u + 2u);  // x = -0.005 ... 4.005, plus layer 1's side walls passing y = -0.005
  EXPECT_EQ(floor1, 404u);       // x = -0.015 ... 4.015
  EXPECT_EQ(s.boundary_x.size(), 4u * 401u + 4u * 403u);
  EXPECT_EQ(min_pair_distance(s.boundary_x) > 0.0099, true);
  EXPECT_NEAR(s.bounds_min.x(), -0.015, 1e-12);
  EXPECT_NEAR(s.bounds_min.y(), -0.015, 1e-12);
  EXPECT_NEAR(s.bounds_max.x(), 4.015, 1e-12);
  EXPECT_NEAR(s.bounds_max.y(), 4.015, 1e-12);
  EXPECT_EQ(s.objects[0].name, "tank");
  EXPECT_EQ(s.objects[0].shape, "box");
}

TEST(SceneFiles, ResolvedHasEveryDefault) {
  const Scene s = parse_scene(scene_with(""), "scenes/tiny.json");
  EXPECT_EQ(s.name, "tiny");
  EXPECT_EQ(s.output.directory, "renders/tiny");
  const auto& r = s.resolved;
  for (const char* k :
       {"type", "rest_density", "gravity", "viscosity", "tolerance", "omega", "min_iterations", "max_iterations",
        "pressure_init", "stiffness", "boundary_pressure", "gamma1", "gamma2", "gamma3"})
    EXPECT_TRUE(r["solver"].contains(k)) << k;
  for (const char* k : {"duration", "fps", "dt", "cfl", "dt_max", "dt_min"}) EXPECT_TRUE(r["time"].contains(k)) << k;
  EXPECT_TRUE(r["time"]["dt"].is_null());  // adaptive
  EXPECT_EQ(r["time"]["cfl"], 0.4);
  EXPECT_EQ(r["solver"]["tolerance"], 0.1);
  EXPECT_EQ(r["solver"]["type"], "iisph");
  EXPECT_EQ(r["solver"]["pressure_init"], "warm");
  EXPECT_EQ(r["stability"]["max_error_percent"], 50.0);
  EXPECT_EQ(r["output"]["directory"], "renders/tiny");
  EXPECT_EQ(r["output"]["export"], nlohmann::json::array());
  EXPECT_EQ(r["name"], "tiny");
  EXPECT_EQ(r["fluid"][0]["velocity"], nlohmann::json::array({0.0, 0.0}));
  EXPECT_EQ(r["render"]["resolution"], nlohmann::json::array({1280, 720}));
  EXPECT_EQ(r["render"]["color_by"], "cfl");
  EXPECT_TRUE(r["render"]["range"].is_null());
  EXPECT_TRUE(r["render"]["view"].is_null());
  // The resolved scene is itself a valid scene with the same result.
  const Scene again = parse_scene(r.dump(), "resolved.json");
  EXPECT_EQ(again.fluid_x.size(), s.fluid_x.size());
  EXPECT_EQ(again.resolved, r);
}

TEST(SceneFiles, RenderSection) {
  const Scene s =
      parse_scene(scene_with(R"("render": {"resolution": [640, 360], "color_by": "pressure", "colormap": "viridis",
      "range": [0, 5000], "view": {"min": [-0.5, 0], "max": [1.5, 1]}},)"),
                  "scenes/r.json");
  EXPECT_EQ(s.render.width, 640);
  EXPECT_EQ(s.render.height, 360);
  EXPECT_EQ(s.render.color_by, "pressure");
  EXPECT_EQ(s.render.colormap, "viridis");
  EXPECT_TRUE(s.render.fixed_range);
  EXPECT_EQ(s.render.range_hi, 5000);
  EXPECT_TRUE(s.render.fixed_view);
  EXPECT_EQ(s.render.view_min, Vec2(-0.5, 0));
  EXPECT_EQ(s.render.view_max, Vec2(1.5, 1));
  const Scene again = parse_scene(s.resolved.dump(), "resolved.json");
  EXPECT_EQ(again.resolved, s.resolved);
}

// --- validation messages ---------------------------------------------------------------------

struct BadCase {
  const char* what;
  std::string text;
  std::vector<std::string> expected;  // substrings of the message besides the file name
};

TEST(SceneErrors, BadInputsNameFilePathAndAllowed) {
  const std::string box = R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4]}],)";
  const std::vector<BadCase> cases = {
      {"malformed JSON",
       "{\n  \"spacing\": 0.01,\n  \"fluid\": [\n    {\"shape\": \"rectangle\", \"min\": [0, 0] \"max\": [1, 1]}\n  "
       "]\n}",
       {"scenes/x.json:4:42: JSON parse error: ", "unexpected string literal"}},
      {"bad literal",
       "{\"spacing\": 0.01,\n\"fluid\": [],\n\"x\": tru }",
       {"scenes/x.json:3:9: JSON parse error: ", "invalid literal"}},
      {"unknown top-level key",
       scene_with(R"("fluids": 1,)"),
       {"scenes/x.json:1:12: /fluids: unknown key; allowed keys: name, spacing, solver, time, stability, output, "
        "render, fluid, boundaries"}},
      {"unknown nested key",
       scene_with(R"("solver": {"tolernce": 0.05},)"),
       {"scenes/x.json:1:25: /solver/tolernce: unknown key; allowed keys: type, rest_density, gravity, viscosity, "
        "artificial_viscosity, sound_speed, gradient_correction, kernel, support, tolerance,"}},
      {"unknown boundary key",
       scene_with(R"("boundaries": [{"shape": "circle", "center": [0, 0], "radius": 1, "lid": true}],)"),
       {"/boundaries/0/lid: unknown key; allowed keys: shape, name, wall, wall_viscosity, center, radius, spacing, "
        "fluid_side, layers, "
        "layer_spacing"}},
      {"unknown wall kind",
       scene_with(R"("boundaries": [{"shape": "circle", "center": [0, 0], "radius": 1, "wall": "sticky"}],)"),
       {"/boundaries/0/wall", "sticky", "free_slip", "no_slip"}},
      {"negative wall viscosity",
       scene_with(
           R"("boundaries": [{"shape": "circle", "center": [0, 0], "radius": 1, "wall": "no_slip", "wall_viscosity": -1}],)"),
       {"/boundaries/0/wall_viscosity", "-1", ">= 0"}},
      {"wall viscosity on a free-slip wall",
       scene_with(R"("boundaries": [{"shape": "circle", "center": [0, 0], "radius": 1, "wall_viscosity": 1e-3}],)"),
       {"/boundaries/0/wall_viscosity: applies to a no-slip wall only"}},
      {"wrong type vec2",
       scene_with("", R"([{"shape": "rectangle", "min": "abc", "max": [1, 1]}])"),
       {R"(scenes/x.json:1:58: /fluid/0/min: expected an array of 2 numbers, got "abc")"}},
      {"float for int",
       scene_with(R"("solver": {"max_iterations": 10.5},)"),
       {"/solver/max_iterations: expected an integer, got 10.5"}},
      {"float for layers",
       scene_with(R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4], "layers": 2.0}],)"),
       {"/boundaries/0/layers: expected an integer, got 2.0"}},
      {"string for number", scene_with(R"("time": {"fps": "30"},)"), {R"(/time/fps: expected a number, got "30")"}},
      {"negative spacing",
       R"({"spacing": -0.01, "fluid": []})",
       {"/spacing: value -0.01 is out of range; must be > 0 [m]"}},
      {"missing spacing", R"({"fluid": []})", {"/spacing: missing required key"}},
      {"tolerance zero",
       scene_with(R"("solver": {"tolerance": 0},)"),
       {"/solver/tolerance: value 0 is out of range; must be > 0 (percent)"}},
      {"tolerance negative",
       scene_with(R"("solver": {"tolerance": -1},)"),
       {"scenes/x.json:1:26: /solver/tolerance: value -1 is out of range; must be > 0 (percent)"}},
      {"omega above 1",
       scene_with(R"("solver": {"omega": 1.5},)"),
       {"/solver/omega: value 1.5 is out of range; must be in (0, 1]"}},
      {"dt and cfl",
       scene_with(R"("time": {"dt": 1e-3, "cfl": 0.4},)"),
       {"/time: both dt and cfl are given; remove \"cfl\"", "or \"dt\""}},
      {"cfl above 2", scene_with(R"("time": {"cfl": 3},)"), {"/time/cfl: value 3 is out of range; must be in (0, 2]"}},
      {"settle neither a number nor auto",
       scene_with(R"("time": {"settle": "yes"},)"),
       {"/time/settle: expected a number >= 0 [s] or \"auto\", got \"yes\""}},
      {"negative settle",
       scene_with(R"("time": {"settle": -1},)"),
       {"/time/settle: value -1 is out of range; must be >= 0"}},
      {"dt_min above dt_max",
       scene_with(R"("time": {"dt_min": 1e-2},)"),
       {"/time/dt_min:", "need 0 < dt_min <= dt_max"}},
      {"bad enum",
       scene_with(R"("solver": {"boundary_pressure": "mirror"},)"),
       {R"(/solver/boundary_pressure: invalid value "mirror"; must be one of: solved, extrapolation, mirroring, zero)"}},
      {"bad solver type",
       scene_with(R"("solver": {"type": "pcisph"},)"),
       {"/solver/type:", "must be one of: iisph, wcsph"}},
      {"bad fluid side",
       scene_with(R"("boundaries": [{"shape": "polyline", "points": [[0, 0], [1, 0]], "fluid_side": "inside"}],)"),
       {"/boundaries/0/fluid_side:", "must be one of: left, right"}},
      {"bad shape",
       scene_with("", R"([{"shape": "square"}])"),
       {"/fluid/0/shape:", "must be one of: rectangle, ellipse, polygon"}},
      {"missing shape", scene_with("", R"([{"min": [0, 0]}])"), {"/fluid/0/shape: missing required key"}},
      {"empty fluid array",
       scene_with("", "[]"),
       {"scenes/x.json:1:27: /fluid: the scene has no fluid particles (0 lattice points"}},
      {"zero-area fluid",
       scene_with("", R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 0]}])"),
       {"/fluid: the scene has no fluid particles (0 lattice points"}},
      {"fluid inside solid circle",
       scene_with(R"("boundaries": [{"shape": "circle", "center": [0.5, 0.5], "radius": 2}],)"),
       {"scenes/x.json:1:98: /fluid: the scene has no fluid particles (100 lattice points, all removed inside "
        "boundaries)"}},
      {"fluid outside container",
       scene_with(R"("boundaries": [{"shape": "box", "min": [5, 5], "max": [6, 6], "lid": true}],)"),
       {"/fluid: the scene has no fluid particles (100 lattice points, all removed inside boundaries)"}},
      {"bad export",
       scene_with(R"("output": {"export": ["csv", "png"]},)"),
       {R"(/output/export/1: invalid value "png"; must be one of: csv, vtk)"}},
      {"export not array",
       scene_with(R"("output": {"export": "csv"},)"),
       {"/output/export: expected an array", "csv, vtk"}},
      {"min above max iterations",
       scene_with(R"("solver": {"min_iterations": 50, "max_iterations": 10},)"),
       {"/solver/min_iterations: min_iterations 50 is larger than max_iterations 10",
        "need 1 <= min_iterations <= max_iterations <= 10000"}},
      {"iterations out of range",
       scene_with(R"("solver": {"max_iterations": 0},)"),
       {"/solver/max_iterations: value 0 is out of range; must be an integer in [1, 10000]"}},
      {"duplicate key", scene_with(R"("solver": {"omega": 0.5, "omega": 0.7},)"), {"/solver/omega: duplicate key"}},
      {"solver not an object", scene_with(R"("solver": 3,)"), {"/solver: expected an object, got 3"}},
      {"self-intersecting polygon",
       scene_with("", R"([{"shape": "polygon", "points": [[0, 0], [1, 1], [1, 0], [0, 1]]}])"),
       {"/fluid/0/points:", "simple polygon"}},
      {"too few points",
       scene_with("", R"([{"shape": "polygon", "points": [[0, 0], [1, 1]]}])"),
       {"/fluid/0/points: expected an array of at least 3 points"}},
      {"spacing array length",
       scene_with(R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4], "spacing": [0.1, 0.1]}],)"),
       {"/boundaries/0/spacing: expected 4 spacings (one per segment: bottom, right, top, left), got 2"}},
      {"spacing array on circle",
       scene_with(R"("boundaries": [{"shape": "circle", "center": [0, 0], "radius": 1, "spacing": [0.1]}],)"),
       {"/boundaries/0/spacing: expected a number, got [0.1]"}},
      {"layers zero",
       scene_with(R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4], "layers": 0}],)"),
       {"/boundaries/0/layers: value 0 is out of range; must be an integer in [1, 1000]"}},
      {"duplicate boundary name", scene_with(box + R"("boundaries": 1,)"), {"/boundaries: duplicate key"}},
      {"box max below min",
       scene_with(R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 0]}],)"),
       {"/boundaries/0/max:", "must be above min"}},
      {"render range reversed",
       scene_with(R"("render": {"range": [2, 1]},)"),
       {"/render/range: range [2,1] must be [lo, hi] with lo < hi"}},
      {"render bad field",
       scene_with(R"("render": {"color_by": "velocity"},)"),
       {R"(/render/color_by: invalid value "velocity"; must be one of: cfl, speed, pressure, density_error)"}},
      {"render bad colormap",
       scene_with(R"("render": {"colormap": "jet"},)"),
       {"/render/colormap:", "spectrum, viridis, turbo"}},
      {"render odd resolution shape",
       scene_with(R"("render": {"resolution": "1280x720"},)"),
       {R"(/render/resolution: expected [width, height] in pixels, got "1280x720")"}},
      {"render resolution too small",
       scene_with(R"("render": {"resolution": [1, 720]},)"),
       {"/render/resolution/0: value 1 is out of range; must be an integer in [2, 16384]"}},
      {"render empty view",
       scene_with(R"("render": {"view": {"min": [0, 0], "max": [1, 0]}},)"),
       {"/render/view/max:", "must be above min"}},
      {"render view unknown key",
       scene_with(R"("render": {"view": {"min": [0, 0], "max": [1, 1], "zoom": 2}},)"),
       {"/render/view/zoom: unknown key; allowed keys: min, max"}},
      {"huge lattice",
       R"({"spacing": 1e-6, "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [1, 1]}]})",
       {"/fluid/0: the fluid would have more than 20000000 lattice points"}},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string msg = error_of(c.text);
    EXPECT_NE(msg.find(kFile), std::string::npos) << msg;
    for (const auto& e : c.expected)
      EXPECT_NE(msg.find(e), std::string::npos) << "message: " << msg << "\nexpected: " << e;
  }
}

TEST(SceneErrors, MissingFile) {
  try {
    load_scene("scenes/does_not_exist.json");
    FAIL() << "no error";
  } catch (const SceneError& e) {
    EXPECT_STREQ(e.what(), "scenes/does_not_exist.json: cannot open scene file: no such file");
  }
}

TEST(SceneErrors, DuplicateBoundaryNames) {
  const std::string msg = error_of(scene_with(
      R"("boundaries": [{"shape": "box", "name": "w", "min": [0, 0], "max": [4, 4]}, {"shape": "circle", "name": "w", "center": [2, 2], "radius": 0.1}],)"));
  EXPECT_NE(msg.find("/boundaries/1/name: duplicate name \"w\""), std::string::npos) << msg;
}

// A value error names the line:column (1-based) of the offending value in the file, like
// a syntax error; a value an override set, or changed, has none.
TEST(SceneErrors, ValueErrorsNameLineAndColumn) {
  const std::string text =
      "{\n"
      "  \"spacing\": 0.1,\n"
      "  \"solver\": {\n"
      "    \"type\": \"iisph\",\n"
      "    \"boundary_pressure\": \"mirror\",\n"
      "    \"tolerance\": -1\n"
      "  },\n"
      "  \"time\": {\"fps\": 30, \"fsp\": 30},\n"
      "  \"fluid\": [\n"
      "    {\"shape\": \"rectangle\", \"min\": [0, \"a\"], \"max\": [1, 1]}\n"
      "  ]\n"
      "}\n";
  const std::string mirror =
      "/solver/boundary_pressure: invalid value \"mirror\"; must be one of: solved, extrapolation, mirroring, zero";
  EXPECT_EQ(error_of(text), "scenes/x.json:6:18: /solver/tolerance: value -1 is out of range; must be > 0 (percent)");
  // A sibling set by an override leaves the value's position; numbers and strings are
  // found at their first character.
  EXPECT_EQ(error_of(text, {"solver.tolerance=1"}), "scenes/x.json:5:26: " + mirror);
  EXPECT_EQ(error_of(text, {"solver.tolerance=1", "solver.boundary_pressure=zero"}),
            "scenes/x.json:8:30: /time/fsp: unknown key; allowed keys: duration, fps, dt, cfl, dt_max, dt_min, settle, "
            "relax_start");
  EXPECT_EQ(error_of(text, {"solver.tolerance=1", "solver.boundary_pressure=zero", "time.fsp=null", "/time/fsp=1"}),
            "scenes/x.json: /time/fsp: unknown key; allowed keys: duration, fps, dt, cfl, dt_max, dt_min, settle, "
            "relax_start");
  const std::vector<std::string> good_solver_time = {"solver.tolerance=1", "solver.boundary_pressure=zero", "time={}"};
  EXPECT_EQ(error_of(text, good_solver_time),
            "scenes/x.json:10:35: /fluid/0/min: expected an array of 2 numbers, got [0,\"a\"]");
  // The value itself from an override: the message as without a file position.
  EXPECT_EQ(error_of(text, {"solver.tolerance=1", "solver.boundary_pressure=mirrors"}),
            "scenes/x.json: /solver/boundary_pressure: invalid value \"mirrors\"; must be one of: solved, "
            "extrapolation, mirroring, zero");
  // A value holding one an override changed is not the file's either.
  std::vector<std::string> o = good_solver_time;
  o.push_back("fluid.0.max.0=2");
  EXPECT_EQ(error_of(text, o), "scenes/x.json:10:35: /fluid/0/min: expected an array of 2 numbers, got [0,\"a\"]");
  o.push_back("fluid.0.min.1=-1");
  o.push_back("fluid.0.max=[1,-2]");
  EXPECT_EQ(error_of(text, o).rfind("scenes/x.json: /fluid/0/max: max [1, -2] is below min [0, -1]", 0), 0u)
      << error_of(text, o);
  // A missing key has no position.
  EXPECT_EQ(error_of("{\n  \"fluid\": []\n}"),
            "scenes/x.json: /spacing: missing required key; the fluid particle spacing in m, a number > 0");
  // A container's position is its opening bracket; a string's its opening quote, escapes
  // and all; a duplicate key's the second value.
  EXPECT_EQ(error_of("{\"spacing\": 0.1,\n \"fluid\":\n   [ ]}"),
            "scenes/x.json:3:4: /fluid: the scene has no fluid particles (0 lattice points: the fluid blocks are empty "
            "or have no area at this spacing)");
  EXPECT_EQ(error_of(scene_with(R"("name": "a\"\\/b",)")).substr(0, 27), "scenes/x.json:1:10: /name: ");
  EXPECT_EQ(error_of("{\"spacing\": 0.1,\n\"spacing\":  0.2, \"fluid\": []}"),
            "scenes/x.json:2:13: /spacing: duplicate key; each key may appear only once");
}

// --- overrides --------------------------------------------------------------------------------

TEST(SceneOverrides, ChangeValues) {
  const std::string text = scene_with("");
  const Scene s = parse_scene(text, kFile,
                              {"solver.tolerance=0.05", "/solver/type=wcsph", "fluid.0.max=[2,1]", "time.dt=5e-4",
                               "output.export=[\"vtk\"]", "name=\"renamed\""});
  EXPECT_EQ(s.solver.tolerance_percent, 0.05);
  EXPECT_EQ(s.solver.type, SolverType::WCSPH);
  EXPECT_EQ(s.fluid_x.size(), 200u);
  EXPECT_EQ(s.time.dt, 5e-4);
  EXPECT_EQ(s.output.export_formats, std::vector<std::string>{"vtk"});
  EXPECT_EQ(s.name, "renamed");
  EXPECT_EQ(s.resolved["solver"]["tolerance"], 0.05);
  EXPECT_EQ(s.resolved["solver"]["type"], "wcsph");
  // An override may replace a key set in the file: dt with cfl needs dt removed (null).
  const Scene a = parse_scene(scene_with(R"("time": {"dt": 1e-3},)"), kFile, {"time.dt=null", "time.cfl=0.5"});
  EXPECT_EQ(a.time.dt, 0.0);
  EXPECT_EQ(a.time.cfl, 0.5);
  // An override of one of dt and cfl replaces the file's other (`bench --sweep time.dt=...`
  // on a scene with a cfl); both in one override, or both overridden, stay a mistake.
  const Scene fixed = parse_scene(scene_with(R"("time": {"cfl": 1.0},)"), kFile, {"time.dt=2.5e-4"});
  EXPECT_EQ(fixed.time.dt, 2.5e-4);
  EXPECT_TRUE(fixed.resolved["time"]["cfl"].is_null());
  const Scene adaptive = parse_scene(scene_with(R"("time": {"dt": 1e-3},)"), kFile, {"time.cfl=0.5"});
  EXPECT_EQ(adaptive.time.dt, 0.0);
  EXPECT_EQ(adaptive.time.cfl, 0.5);
  EXPECT_NE(error_of(scene_with(""), {R"(time={"dt": 1e-3, "cfl": 0.4})"}).find("/time: both dt and cfl are given"),
            std::string::npos);
  EXPECT_NE(error_of(scene_with(""), {"time.dt=1e-3", "time.cfl=0.4"}).find("/time: both dt and cfl are given"),
            std::string::npos);
  // The index equal to an array's size appends.
  const Scene b = parse_scene(text, kFile, {R"(fluid.1={"shape": "rectangle", "min": [2, 0], "max": [3, 1]})"});
  EXPECT_EQ(b.fluid_x.size(), 200u);
}

// WCSPH's default stiffness k = rho0 (20 v)^2, v = max(sqrt(g H), fastest initial speed):
// the 1 m block of spacing 0.1 is H = 1 m high (its rows' extent plus a spacing).
TEST(SceneSettings, WcsphStiffnessDefaultsFromTheFluid) {
  const double c_gravity = 20 * std::sqrt(9.81 * 1.0);
  const Scene s = parse_scene(scene_with(R"("solver": {"type": "wcsph"},)"), kFile);
  EXPECT_NEAR(s.solver.stiffness, 1000 * c_gravity * c_gravity, 1e-6 * s.solver.stiffness);
  EXPECT_EQ(s.resolved["solver"]["stiffness"], s.solver.stiffness);
  // An initial velocity faster than sqrt(g H) sets it; a given stiffness (or null) wins.
  const std::string fast = R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 1], "velocity": [0, -5]}])";
  EXPECT_NEAR(parse_scene(scene_with(R"("solver": {"type": "wcsph"},)", fast), kFile).solver.stiffness,
              1000 * 100.0 * 100.0, 1e-3);
  EXPECT_EQ(parse_scene(scene_with(R"("solver": {"type": "wcsph", "stiffness": 5e5},)"), kFile).solver.stiffness, 5e5);
  EXPECT_EQ(
      parse_scene(scene_with(R"("solver": {"type": "wcsph", "stiffness": 5e5},)"), kFile, {"solver.stiffness=null"})
          .solver.stiffness,
      s.solver.stiffness);
  // Neither gravity nor motion: WCSPH needs the key, IISPH does not.
  const std::string still = R"("solver": {"type": "wcsph", "gravity": [0, 0]},)";
  const std::string msg = error_of(scene_with(still));
  EXPECT_NE(msg.find("/solver/stiffness: missing: WCSPH's default stiffness"), std::string::npos) << msg;
  EXPECT_NE(msg.find("set solver.stiffness"), std::string::npos) << msg;
  EXPECT_EQ(error_of(scene_with(still), {"solver.stiffness=1e6"}), "(no error)");
  const Scene iisph = parse_scene(scene_with(R"("solver": {"gravity": [0, 0]},)"), kFile);
  EXPECT_EQ(iisph.solver.stiffness, 0.0);
  EXPECT_TRUE(iisph.resolved["solver"]["stiffness"].is_null());
}

// solver.pressure_solver and solver.chebyshev_rho: the choices, the default and the range.
TEST(SceneSettings, PressureSolverChoices) {
  const std::string text = scene_with("");
  EXPECT_EQ(parse_scene(text, kFile).solver.pressure_solver, PressureSolver::Jacobi);
  const Scene c = parse_scene(text, kFile, {"solver.pressure_solver=chebyshev", "solver.chebyshev_rho=0.95"});
  EXPECT_EQ(c.solver.pressure_solver, PressureSolver::Chebyshev);
  EXPECT_EQ(c.solver.chebyshev_rho, 0.95);
  EXPECT_EQ(c.resolved["solver"]["pressure_solver"], "chebyshev");
  const std::string bad = error_of(text, {"solver.pressure_solver=cg"});
  EXPECT_NE(bad.find("/solver/pressure_solver"), std::string::npos) << bad;
  EXPECT_NE(bad.find("chebyshev"), std::string::npos) << bad;
  const std::string rho = error_of(text, {"solver.chebyshev_rho=1"});
  EXPECT_NE(rho.find("/solver/chebyshev_rho: value 1 is out of range; must be in [0, 1)"), std::string::npos) << rho;
  // multilevel: its cell size, and the boundary methods its coarse operator covers.
  const Scene m = parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.multilevel_cell=4"});
  EXPECT_EQ(m.solver.pressure_solver, PressureSolver::Multilevel);
  EXPECT_EQ(m.solver.multilevel_cell, 4.0);
  EXPECT_EQ(m.resolved["solver"]["pressure_solver"], "multilevel");
  EXPECT_EQ(parse_scene(text, kFile).solver.multilevel_cell, 6.0);
  EXPECT_EQ(parse_scene(text, kFile).solver.multilevel_wall_sweeps, 2);
  EXPECT_EQ(parse_scene(text, kFile, {"solver.multilevel_wall_sweeps=0"}).solver.multilevel_wall_sweeps, 0);
  const std::string sweeps = error_of(text, {"solver.multilevel_wall_sweeps=101"});
  EXPECT_NE(sweeps.find("/solver/multilevel_wall_sweeps"), std::string::npos) << sweeps;
  EXPECT_NE(sweeps.find("101"), std::string::npos) << sweeps;
  EXPECT_EQ(parse_scene(text, kFile).solver.multilevel_impact_damping, 0.0);
  EXPECT_EQ(parse_scene(text, kFile, {"solver.multilevel_impact_damping=0.5"}).solver.multilevel_impact_damping, 0.5);
  const std::string damping = error_of(text, {"solver.multilevel_impact_damping=1.5"});
  EXPECT_NE(damping.find("/solver/multilevel_impact_damping: value 1.5 is out of range; must be in [0, 1]"),
            std::string::npos)
      << damping;
  // The stabilisation: absent or null, the solver's own kappa (1 with multilevel, else 0).
  const Scene plain = parse_scene(text, kFile);
  EXPECT_EQ(stabilisation_kappa(plain.solver), 0.0);
  EXPECT_TRUE(plain.resolved["solver"]["pressure_stabilisation"].is_null());
  EXPECT_EQ(stabilisation_kappa(m.solver), kMultilevelStabilisation);
  EXPECT_EQ(
      stabilisation_kappa(
          parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.pressure_stabilisation=null"}).solver),
      1.0);
  const Scene two = parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.pressure_stabilisation=2"});
  EXPECT_EQ(stabilisation_kappa(two.solver), 2.0);
  EXPECT_EQ(two.resolved["solver"]["pressure_stabilisation"], 2.0);
  EXPECT_EQ(
      stabilisation_kappa(
          parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.pressure_stabilisation=0"}).solver),
      0.0);
  const std::string kappa = error_of(text, {"solver.pressure_stabilisation=-1"});
  EXPECT_NE(kappa.find("/solver/pressure_stabilisation: value -1 is out of range; must be in [0, 10]"),
            std::string::npos)
      << kappa;
  const std::string cell = error_of(text, {"solver.multilevel_cell=1.5"});
  EXPECT_NE(cell.find("/solver/multilevel_cell: value 1.5 is out of range; must be in [2, 64]"), std::string::npos)
      << cell;
  const std::string ext =
      error_of(text, {"solver.pressure_solver=multilevel", "solver.boundary_pressure=extrapolation"});
  EXPECT_NE(ext.find("/solver/pressure_solver"), std::string::npos) << ext;
  EXPECT_NE(ext.find("not \"extrapolation\""), std::string::npos) << ext;
  EXPECT_NO_THROW(
      parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.boundary_pressure=mirroring"}));
}

// solver.kernel and solver.support: defaults, values, errors naming the JSON path, and
// the multilevel cells no smaller than the support.
TEST(SceneSettings, KernelAndSupport) {
  const std::string text = scene_with("");
  const Scene d = parse_scene(text, kFile);
  EXPECT_EQ(d.solver.kernel, KernelKind::CubicSpline);
  EXPECT_EQ(d.solver.support, 2.0);
  EXPECT_EQ(d.resolved["solver"]["kernel"], "cubic_spline");
  EXPECT_EQ(d.resolved["solver"]["support"], 2.0);
  const Scene w = parse_scene(text, kFile, {"solver.kernel=wendland_c2", "solver.support=3"});
  EXPECT_EQ(w.solver.kernel, KernelKind::WendlandC2);
  EXPECT_EQ(w.solver.support, 3.0);
  const std::string bad = error_of(text, {"solver.kernel=gaussian"});
  EXPECT_NE(bad.find("/solver/kernel"), std::string::npos) << bad;
  EXPECT_NE(bad.find("wendland_c2"), std::string::npos) << bad;
  const std::string range = error_of(text, {"solver.support=5"});
  EXPECT_NE(range.find("/solver/support: value 5 is out of range; must be in [1.5, 4]"), std::string::npos) << range;
  const std::string cell =
      error_of(text, {"solver.pressure_solver=multilevel", "solver.multilevel_cell=2.5", "solver.support=3"});
  EXPECT_NE(cell.find("/solver/multilevel_cell: multilevel_cell 2.5 is smaller than the kernel's support 3"),
            std::string::npos)
      << cell;
  EXPECT_NO_THROW(parse_scene(text, kFile, {"solver.pressure_solver=multilevel", "solver.support=3"}));
}

// A fixed WCSPH step above 0.4 h / c is refused, naming the limit and the stiffness.
TEST(SceneSettings, WcsphStepAboveTheAcousticLimitIsRefused) {
  // k = 1e6: c = 31.62 m/s, limit 0.4 * 0.1 / c = 1.265e-3 s.
  const std::string wcsph = R"("solver": {"type": "wcsph", "stiffness": 1e6},)";
  EXPECT_EQ(error_of(scene_with(wcsph + R"("time": {"dt": 1.2e-3},)")), "(no error)");
  const std::string msg = error_of(scene_with(wcsph + R"("time": {"dt": 1.3e-3},)"));
  EXPECT_NE(msg.find("/time/dt: WCSPH step 0.0013 s exceeds the acoustic limit 0.4 h / c = 0.00126491"),
            std::string::npos)
      << msg;
  EXPECT_NE(msg.find("with stiffness 1000000 Pa*m, h = 0.1 m"), std::string::npos) << msg;
  const std::string own = error_of(scene_with(R"("solver": {"type": "wcsph"}, "time": {"dt": 1e-3},)"));
  EXPECT_NE(own.find("Pa*m, the scene's default, h = 0.1 m"), std::string::npos) << own;
}

TEST(SceneOverrides, Errors) {
  const std::string text = scene_with("");
  std::string msg = error_of(text, {"solver.tolernce=0.05"});
  EXPECT_NE(msg.find("scenes/x.json: /solver/tolernce: unknown key; allowed keys: type,"), std::string::npos) << msg;
  msg = error_of(text, {"solver.tolerance"});
  EXPECT_NE(msg.find("--set solver.tolerance: expected path=value"), std::string::npos) << msg;
  msg = error_of(text, {"solver..x=1"});
  EXPECT_NE(msg.find("--set solver..x=1: empty path component"), std::string::npos) << msg;
  msg = error_of(text, {"spacing.x=1"});
  EXPECT_NE(msg.find("--set spacing.x=1: the path goes through /spacing, which is 0.1, not an object or array"),
            std::string::npos)
      << msg;
  msg = error_of(text, {"fluid.3.max=[1,1]"});
  EXPECT_NE(msg.find("--set fluid.3.max=[1,1]: \"3\" is not an index of the array at /fluid (size 1"),
            std::string::npos)
      << msg;
  msg = error_of(text, {"fluid.x=1"});
  EXPECT_NE(msg.find("--set fluid.x=1: \"x\" is not an index of the array at /fluid"), std::string::npos) << msg;
  msg = error_of(text, {"solver.omega=2"});
  EXPECT_NE(msg.find("/solver/omega: value 2 is out of range"), std::string::npos) << msg;
}

// --- sampling ---------------------------------------------------------------------------------

TEST(SceneSampling, PolylinePerSegmentSpacing) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "polyline", "points": [[0, 3], [1, 3], [1, 4]], "spacing": [0.1, 0.25], "layers": 1}],)"),
      kFile);
  const auto b = samples_of(s, 0);
  std::size_t first = 0, second = 0;
  for (const Vec2& p : b) {
    if (std::abs(p.y() - 3) < 1e-12 && p.x() < 1 - 1e-12) ++first;  // segment 0 without its end corner
    if (std::abs(p.x() - 1) < 1e-12) ++second;                      // segment 1 with both corners
  }
  EXPECT_EQ(first, 10u);
  EXPECT_EQ(second, 5u);
  EXPECT_EQ(b.size(), 15u);
  EXPECT_NEAR(min_pair_distance(b), 0.1, 1e-12);
  EXPECT_EQ(s.resolved["boundaries"][0]["spacing"], nlohmann::json::array({0.1, 0.25}));
}

TEST(SceneSampling, NonUniformSpacingRounds) {
  // A 1 m segment with spacing 0.3 gets round(3.33) = 3 intervals of 1/3 m.
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "polyline", "points": [[0, 3], [1, 3]], "spacing": 0.3, "layers": 1}],)"),
      kFile);
  const auto b = samples_of(s, 0);
  ASSERT_EQ(b.size(), 4u);
  EXPECT_NEAR(b[1].x(), 1.0 / 3.0, 1e-12);
  EXPECT_NEAR(b[3].x(), 1.0, 1e-12);
}

TEST(SceneSampling, BoxWithLidIsClosedLoop) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "box", "min": [0, 0], "max": [1, 1], "lid": true, "layers": 2}],)"),
      kFile);
  const auto b = samples_of(s, 0);
  EXPECT_EQ(b.size(), 40u + 48u);  // layer 0: 4 x 10; layer 1: 4 x 12 around [-0.1, 1.1]^2
  EXPECT_GT(min_pair_distance(b), 1e-9);
  EXPECT_NEAR(min_pair_distance(b), 0.1, 1e-9);
  std::size_t on_box = 0, outside = 0;
  for (const Vec2& p : b) {
    const double linf = std::max(std::abs(p.x() - 0.5), std::abs(p.y() - 0.5));
    if (std::abs(linf - 0.5) < 1e-12) ++on_box;
    if (std::abs(linf - 0.6) < 1e-12) ++outside;
  }
  EXPECT_EQ(on_box, 40u);
  EXPECT_EQ(outside, 48u);
  // Samples on the surface (surface_offset 0): the lattice's outer ring, h/2 from them,
  // would start compressed and is removed.
  EXPECT_EQ(s.fluid_x.size(), 64u);
  EXPECT_EQ(s.fluid_removed, 36);
  EXPECT_EQ(s.fluid_near_samples, 36);
}

// A box obstacle (fluid_side outside) is closed unless told otherwise: without its top it
// would be a cup inside the fluid that fills with water.
TEST(SceneSampling, BoxObstacleIsClosedByDefault) {
  const std::string obstacle =
      R"({"surface_offset": 0, "shape": "box", "min": [1, 1], "max": [2, 2], "layers": 1, "fluid_side": "outside")";
  const Scene closed = parse_scene(scene_with(R"("boundaries": [)" + obstacle + "}],"), kFile);
  const Scene open = parse_scene(scene_with(R"("boundaries": [)" + obstacle + R"(, "lid": false}],)"), kFile);
  auto top_samples = [](const Scene& s) {
    std::size_t n = 0;
    for (const Vec2& p : samples_of(s, 0)) n += std::abs(p.y() - 2.0) < 1e-12 && p.x() > 1 + 1e-9 && p.x() < 2 - 1e-9;
    return n;
  };
  EXPECT_GT(top_samples(closed), 0u);
  EXPECT_EQ(top_samples(open), 0u);
  EXPECT_EQ(parse_scene(scene_with(R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4]}],)"), kFile)
                .objects[0]
                .geometry.lid,
            false);  // a container stays open at the top
}

TEST(SceneSampling, BoxSpacingPerWall) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "box", "min": [0, 0], "max": [1, 2], "lid": true, "layers": 1, "spacing": [0.1, 0.5, 0.25, 1]}],)"),
      kFile);
  // bottom 10 + right 4 + top 4 + left 2 intervals, corners once
  EXPECT_EQ(samples_of(s, 0).size(), 20u);
  const Scene open = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "box", "min": [0, 0], "max": [1, 2], "layers": 1, "spacing": [0.1, 0.5, 0.25, 1]}],)"),
      kFile);
  EXPECT_EQ(samples_of(open, 0).size(), 2u + 10u + 4u + 1u);  // left, bottom, right, top-right corner
}

TEST(SceneSampling, LayersGoAwayFromFluid) {
  auto layer1_y = [](const std::string& side) {
    const Scene s = parse_scene(
        scene_with(
            R"("boundaries": [{"surface_offset": 0, "shape": "polyline", "points": [[0, 3], [1, 3]], "fluid_side": ")" +
            side + R"(", "layer_spacing": 0.05}],)"),
        kFile);
    const auto b = samples_of(s, 0);
    return b.back().y();
  };
  EXPECT_NEAR(layer1_y("left"), 3 - 0.05, 1e-12);  // fluid above a left-to-right wall
  EXPECT_NEAR(layer1_y("right"), 3 + 0.05, 1e-12);

  // Polygon obstacle (default fluid outside): layers inward for both orientations.
  for (const char* pts : {"[[3, 3], [4, 3], [4, 4], [3, 4]]", "[[3, 3], [3, 4], [4, 4], [4, 3]]"}) {
    SCOPED_TRACE(pts);
    const Scene s = parse_scene(
        scene_with(R"("boundaries": [{"surface_offset": 0, "shape": "polygon", "points": )" + std::string(pts) + "}],"),
        kFile);
    for (const Vec2& p : samples_of(s, 0)) {
      const double linf = std::max(std::abs(p.x() - 3.5), std::abs(p.y() - 3.5));
      EXPECT_TRUE(std::abs(linf - 0.5) < 1e-12 || std::abs(linf - 0.4) < 1e-12) << p.transpose();
    }
    const Scene c = parse_scene(
        scene_with(R"("boundaries": [{"surface_offset": 0, "shape": "polygon", "fluid_side": "inside", "points": )" +
                       std::string(pts) + "}],",
                   R"([{"shape": "rectangle", "min": [3, 3], "max": [4, 4]}])"),
        kFile);
    for (const Vec2& p : samples_of(c, 0)) {
      const double linf = std::max(std::abs(p.x() - 3.5), std::abs(p.y() - 3.5));
      EXPECT_TRUE(std::abs(linf - 0.5) < 1e-12 || std::abs(linf - 0.6) < 1e-12) << p.transpose();
    }
    EXPECT_EQ(c.fluid_x.size(), 64u);  // the outer ring, h/2 from the samples, is removed
  }

  // Circle: obstacle layers inside, container layers outside.
  for (const char* side : {"outside", "inside"}) {
    SCOPED_TRACE(side);
    const Scene s = parse_scene(
        scene_with(
            R"("boundaries": [{"surface_offset": 0, "shape": "circle", "center": [5, 5], "radius": 0.5, "layers": 3, "fluid_side": ")" +
                std::string(side) + "\"}],",
            std::string(side) == "inside" ? R"([{"shape": "rectangle", "min": [4.8, 4.8], "max": [5.2, 5.2]}])"
                                          : R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 1]}])"),
        kFile);
    const double sign = std::string(side) == "outside" ? -1 : 1;
    std::vector<std::size_t> per_layer(3, 0);
    for (const Vec2& p : samples_of(s, 0)) {
      const double r = (p - Vec2(5, 5)).norm();
      for (int k = 0; k < 3; ++k)
        if (std::abs(r - (0.5 + sign * 0.1 * k)) < 1e-12) ++per_layer[static_cast<std::size_t>(k)];
    }
    EXPECT_EQ(per_layer[0], 31u);  // round(2 pi 0.5 / 0.1)
    EXPECT_EQ(per_layer[1], sign < 0 ? 25u : 38u);
    EXPECT_EQ(per_layer[2], sign < 0 ? 19u : 44u);
    EXPECT_EQ(samples_of(s, 0).size(), per_layer[0] + per_layer[1] + per_layer[2]);
  }
}

TEST(SceneSampling, EllipseUniformArcLength) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"surface_offset": 0, "shape": "ellipse", "center": [5, 5], "radii": [1, 0.25], "layers": 1, "spacing": 0.05}],)"),
      kFile);
  const auto b = samples_of(s, 0);
  ASSERT_GT(b.size(), 50u);
  double lo = INFINITY, hi = 0;
  for (std::size_t i = 0; i < b.size(); ++i) {
    const double d = (b[(i + 1) % b.size()] - b[i]).norm();
    lo = std::min(lo, d);
    hi = std::max(hi, d);
    EXPECT_NEAR(std::pow(b[i].x() - 5, 2) + std::pow((b[i].y() - 5) / 0.25, 2), 1.0, 1e-9);
  }
  EXPECT_GT(lo, 0.045);
  EXPECT_LT(hi, 0.0505);
}

TEST(SceneSampling, ObjectsAreContiguous) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"shape": "box", "min": [-1, -1], "max": [4, 4]}, {"shape": "circle", "name": "rock", "center": [2, 2], "radius": 0.3}],)"),
      kFile);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].name, "box0");
  EXPECT_EQ(s.objects[1].name, "rock");
  EXPECT_EQ(s.objects[1].shape, "circle");
  EXPECT_EQ(s.objects[0].first, 0);
  EXPECT_EQ(s.objects[1].first, s.objects[0].count);
  EXPECT_EQ(static_cast<std::size_t>(s.objects[1].first + s.objects[1].count), s.boundary_x.size());
  for (std::size_t i = 0; i < s.boundary_x.size(); ++i)
    EXPECT_EQ(s.boundary_object[i], static_cast<Index>(i) < s.objects[0].count ? 0 : 1);
}

// --- fluid lattice and removal -----------------------------------------------------------------

TEST(SceneFluid, CircleObstacleRemovesInside) {
  const double h = 0.01, r = 0.2;
  const Vec2 c(0.5, 0.5);
  const Scene s = parse_scene(
      R"({"spacing": 0.01, "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [1, 1], "velocity": [1, 2]}],
      "boundaries": [{"shape": "circle", "center": [0.5, 0.5], "radius": 0.2}]})",
      kFile);
  // Removed: inside the circle or within half a spacing of it (no lattice point is near that edge).
  std::size_t expected = 0;
  for (int j = 0; j < 100; ++j)
    for (int i = 0; i < 100; ++i) {
      const double d = (Vec2((i + 0.5) * h, (j + 0.5) * h) - c).norm();
      ASSERT_GT(std::abs(d - (r + 0.5 * h)), 1e-5);
      if (d < r + 0.5 * h) ++expected;
    }
  EXPECT_EQ(s.fluid_removed, static_cast<Index>(expected));
  EXPECT_EQ(s.fluid_x.size() + expected, 10000u);
  for (std::size_t i = 0; i < s.fluid_x.size(); ++i) {
    EXPECT_GE((s.fluid_x[i] - c).norm(), r + 0.5 * h * (1 - 1e-6));
    EXPECT_EQ(s.fluid_v[i], Vec2(1, 2));
  }
}

TEST(SceneFluid, KeepsParticlesHalfASpacingFromWalls) {
  const std::string tank = R"("boundaries": [{"shape": "box", "min": [0, 0], "max": [4, 4]}],)";
  auto fluid = [](const char* lo, const char* hi) {
    return std::string(R"([{"shape": "rectangle", "min": )") + lo + R"(, "max": )" + hi + "}]";
  };
  // Exactly 0.5 h from the bottom and left walls: all kept.
  const Scene kept = parse_scene("{" + tank + R"("spacing": 0.01, "fluid": )" + fluid("[0, 0]", "[1, 2]") + "}", kFile);
  EXPECT_EQ(kept.fluid_x.size(), 20000u);
  EXPECT_EQ(kept.fluid_removed, 0);
  // Shifted left by 1e-4: the first column is 0.49 h from the wall and goes.
  const Scene shifted =
      parse_scene("{" + tank + R"("spacing": 0.01, "fluid": )" + fluid("[-0.0001, 0]", "[0.9999, 2]") + "}", kFile);
  EXPECT_EQ(shifted.fluid_removed, 200);
  EXPECT_EQ(shifted.fluid_x.size(), 19800u);
  // Fluid poking through the wall: what is behind the wall or within 0.5 h of it goes.
  const Scene through =
      parse_scene("{" + tank + R"("spacing": 0.01, "fluid": )" + fluid("[-0.5, 0]", "[1, 2]") + "}", kFile);
  EXPECT_EQ(through.fluid_x.size(), 20000u);
  EXPECT_EQ(through.fluid_removed, 50 * 200);
}

TEST(SceneFluid, ShapesAndDuplicates) {
  // Two identical blocks merge into one; an overlapping shifted block adds only new points.
  const Scene twice = parse_scene(scene_with("", R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 1]},
      {"shape": "rectangle", "min": [0, 0], "max": [1, 1], "velocity": [5, 5]}])"),
                                  kFile);
  EXPECT_EQ(twice.fluid_x.size(), 100u);
  EXPECT_EQ(twice.fluid_v[0], Vec2(0, 0));  // the first block wins
  const Scene shifted = parse_scene(scene_with("", R"([{"shape": "rectangle", "min": [0, 0], "max": [1, 1]},
      {"shape": "rectangle", "min": [0.5, 0], "max": [1.5, 1]}])"),
                                    kFile);
  EXPECT_EQ(shifted.fluid_x.size(), 150u);

  // Ellipse and polygon: lattice aligned to the bounding box, points inside kept.
  const Scene ellipse =
      parse_scene(R"({"spacing": 0.01, "fluid": [{"shape": "ellipse", "center": [0, 0], "radii": [1, 0.5]}]})", kFile);
  EXPECT_NEAR(static_cast<double>(ellipse.fluid_x.size()) * 1e-4, std::numbers::pi * 0.5, 0.01);
  const Scene triangle =
      parse_scene(R"({"spacing": 0.01, "fluid": [{"shape": "polygon", "points": [[0, 0], [1, 0], [0, 1]]}]})", kFile);
  EXPECT_NEAR(static_cast<double>(triangle.fluid_x.size()) * 1e-4, 0.5, 0.01);
  for (const Vec2& p : triangle.fluid_x) EXPECT_LE(p.x() + p.y(), 1.0 + 1e-12);
}

}  // namespace
}  // namespace sluice

namespace sluice {
namespace {

// The leak check names the object a particle passed into, where it is and the nearest
// point of that object's surface.
TEST(SceneSampling, FluidInSolidsNamesTheObjectAndWhere) {
  const Scene s = parse_scene(
      scene_with(R"("boundaries": [{"name": "rock", "shape": "circle", "center": [3, 3], "radius": 0.5}],)"), kFile);
  const std::vector<Vec2> x{{0.5, 0.5}, {3.0, 3.1}, {3.0, 2.9}};
  const FluidInSolids r = find_fluid_in_solids(s, x, 0.0);
  EXPECT_EQ(r.count, 2);
  EXPECT_EQ(r.first, 1);
  EXPECT_EQ(r.object, "rock");
  EXPECT_EQ(r.at, Vec2(3.0, 3.1));
  EXPECT_NEAR(r.surface.x(), 3.0, 0.02);
  EXPECT_NEAR(r.surface.y(), 3.5, 0.02);
  EXPECT_EQ(count_fluid_in_solids(s, x, 0.0), 2);
  EXPECT_EQ(find_fluid_in_solids(s, {{0.5, 0.5}}, 0.0).count, 0);
}

}  // namespace
}  // namespace sluice

namespace sluice {
namespace {

// Fluid closer than 0.9 spacings to a boundary sample would start compressed: it is
// removed and counted, and what stays keeps that distance from every sample.
TEST(SceneSampling, FluidNearSamplesIsRemovedAndCounted) {
  const Scene s = parse_scene(
      scene_with(
          R"("boundaries": [{"shape": "circle", "center": [0.5, 0.5], "radius": 0.23, "surface_offset": 0, "layers": 1}],)"),
      kFile);
  EXPECT_GT(s.fluid_near_samples, 0);
  EXPECT_LE(s.fluid_near_samples, s.fluid_removed);
  double closest = std::numeric_limits<double>::infinity();
  for (const Vec2& f : s.fluid_x)
    for (const Vec2& b : s.boundary_x) closest = std::min(closest, (f - b).norm());
  EXPECT_GE(closest, shapes::kMinSampleDistance * s.spacing * (1 - 1e-6));
}

}  // namespace
}  // namespace sluice
