// The `sluice` program on bad input, run as a subprocess (the issue "Bad input"): each
// case gives exactly one line on stderr, starting with "sluice:" and naming the file,
// the JSON path, the value and what is allowed; a specific exit status; no crash or
// sanitizer report; and no file that looks complete but is not (no *.tmp left, no
// stats.csv without a summary.json, nothing at all written for a scene or flag error).
#include <fcntl.h>
#include <gtest/gtest.h>
#include <spawn.h>
#include <stdlib.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "render/image.h"
#include "scene/scene.h"
#include "solver/leak_check.h"
#include "test_process.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;

using test::CaseDir;
using test::read_text;
using test::Result;
using test::run_sluice;
using test::write_text;

// Every file and folder under `root` with its content ("<dir>" for folders).
std::map<std::string, std::string> snapshot(const fs::path& root) {
  std::map<std::string, std::string> files;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string rel = fs::relative(e.path(), root).string();
    files[rel] = e.is_directory() ? "<dir>" : read_text(e.path());
  }
  return files;
}

// What a run may leave: complete files only. Temporary names mean a write was cut
// short; stats.csv and summary.json come as a pair, and the summary is valid JSON with
// a status. Entries in `before` (what the case set up) are not the program's doing.
void expect_no_partial_files(const fs::path& root, const std::map<std::string, std::string>& before = {}) {
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (before.contains(fs::relative(e.path(), root).string())) continue;
    const std::string name = e.path().filename().string();
    EXPECT_EQ(name.find(".tmp"), std::string::npos) << "temporary file left: " << e.path();
    if (name == "stats.csv" || name == "summary.json") {
      const fs::path other = e.path().parent_path() / (name == "stats.csv" ? "summary.json" : "stats.csv");
      EXPECT_TRUE(fs::exists(other)) << e.path() << " without " << other;
    }
    if (name == "summary.json") {
      const auto j = nlohmann::json::parse(read_text(e.path()), nullptr, false);
      EXPECT_TRUE(j.is_object() && j.contains("status")) << e.path() << " is not a complete summary";
    }
  }
}

// The checks every bad input must pass: the status, one line on stderr starting with
// "sluice:" that holds every fragment, no trace of a crash.
void expect_one_clear_line(const Result& r, int status, const std::vector<std::string>& fragments) {
  EXPECT_EQ(r.status, status) << "stderr: " << r.err;
  ASSERT_FALSE(r.err.empty());
  EXPECT_EQ(r.err.rfind("sluice:", 0), 0u) << r.err;
  EXPECT_EQ(r.err.back(), '\n') << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << "more than one line:\n" << r.err;
  for (const std::string& f : fragments)
    EXPECT_NE(r.err.find(f), std::string::npos) << "missing '" << f << "' in: " << r.err;
  for (const char* crash : {"terminate", "Aborted", "Sanitizer", "runtime error", "Segmentation", "core dumped"})
    EXPECT_EQ(r.err.find(crash), std::string::npos) << r.err;
}

// A scene that runs in milliseconds: 36 particles in a box, 4 steps, frames 0 and 1.
// `extra` are top-level members, each ending with a comma.
std::string tiny(const std::string& extra = "",
                 const std::string& fluid = R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                 const std::string& boundaries = R"([{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]}])") {
  return "{" + extra + R"( "name": "tiny", "spacing": 0.05, "time": {"duration": 0.02, "fps": 50, "dt": 0.005},
  "fluid": )" +
         fluid + R"(,
  "boundaries": )" +
         boundaries + "}\n";
}

struct Case {
  std::string name;
  std::map<std::string, std::string> files;  // written into the working directory first
  std::vector<std::string> args;
  int status;
  std::vector<std::string> fragments;
  bool writes_nothing = true;  // the working directory must be left exactly as it was
};

const std::string kRoot = std::string(SLUICE_SOURCE_DIR) + "/";

std::vector<Case> cases() {
  const std::string ok = tiny();
  const std::string previous_summary = R"({"status": "completed"})";
  return {
      // --- the scene file -----------------------------------------------------------------
      {"malformed JSON",
       {{"bad.json", "{\"spacing\": 0.05,\n \"fluid\": [,]}"}},
       {"simulate", "bad.json", "-q"},
       2,
       {"sluice: scene error: bad.json:2:12: JSON parse error", "unexpected ','"}},
      {"truncated file",
       {{"cut.json", ok.substr(0, 60)}},
       {"simulate", "cut.json", "-q"},
       2,
       {"cut.json:1:61: JSON parse error", "unexpected end of input"}},
      {"empty file",
       {{"empty.json", ""}},
       {"simulate", "empty.json", "-q"},
       2,
       {"empty.json:1:1: JSON parse error", "unexpected end of input"}},
      {"non-object root",
       {{"root.json", "[1, 2]"}},
       {"simulate", "root.json", "-q"},
       2,
       {"root.json: the scene must be a JSON object {...}, got [1,2]"}},
      {"unknown key",
       {{"x.json", tiny(R"("solver": {"tolerence": 0.1},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:26: /solver/tolerence: unknown key; allowed keys: type, rest_density", "tolerance"}},
      {"wrong type",
       {{"x.json", tiny(R"("stability": {"bounds_margin": "far"},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:33: /stability/bounds_margin: expected a number, got \"far\""}},
      {"energy bound out of range",
       {{"x.json", tiny(R"("stability": {"max_energy_gain": 0},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"/stability/max_energy_gain: value 0 is out of range; must be > 0"}},
      {"speed bound out of range",
       {{"x.json", tiny(R"("stability": {"max_speed_ratio": 0.5},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"/stability/max_speed_ratio: value 0.5 is out of range; must be >= 1"}},
      {"out-of-range value",
       {{"x.json", tiny(R"("solver": {"omega": 1.5},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:22: /solver/omega: value 1.5 is out of range; must be in (0, 1]"}},
      {"negative dt",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.dt=-0.001"},
       2,
       {"x.json: /time/dt: value -0.001 is out of range; must be > 0 [s]"}},
      {"unknown solver type",
       {{"x.json", tiny(R"("solver": {"type": "sph"},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:21: /solver/type: invalid value \"sph\"; must be one of: iisph, wcsph"}},
      {"duplicate key",
       {{"x.json", tiny(R"("spacing": 0.1,)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:45: /spacing: duplicate key"}},
      {"fluid entirely inside walls",
       {{"x.json", tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                        R"([{"shape": "circle", "center": [0.15, 0.15], "radius": 1, "fluid_side": "outside"}])")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:2:12: /fluid: the scene has no fluid particles (36 lattice points, all removed inside boundaries)"}},
      {"zero fluid particles",
       {{"x.json", tiny("", "[]")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:2:12: /fluid: the scene has no fluid particles (0 lattice points"}},
      {"missing scene file",
       {},
       {"simulate", "nope.json", "-q"},
       2,
       {"sluice: scene error: nope.json: cannot open scene file: no such file"}},
      {"directory as the scene",
       {{"scenes/keep", ""}},
       {"simulate", "scenes", "-q"},
       2,
       {"scenes: is a directory; expected a scene file (JSON)"}},
      {"nesting too deep",
       {{"deep.json", std::string(100000, '[') + std::string(100000, ']')}},
       {"simulate", "deep.json", "-q"},
       2,
       {"deep.json:1:101: /0/0/0/", "nested more than 100 levels deep"}},

      // --- overrides ----------------------------------------------------------------------
      {"bad --set path",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "solver..tolerance=1"},
       2,
       {"--set solver..tolerance=1: empty path component"}},
      {"--set through a number",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "spacing.x=1"},
       2,
       {"--set spacing.x=1: the path goes through /spacing, which is 0.05, not an object or array"}},
      {"--set without =",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "spacing"},
       2,
       {"--set spacing: expected path=value"}},
      {"--set unknown key",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.fsp=30"},
       2,
       {"x.json: /time/fsp: unknown key; allowed keys: duration, fps"}},
      {"--set value not UTF-8",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "spacing=\xff"},
       2,
       {"x.json: /spacing: expected a number, got \""}},

      // --- resource limits ----------------------------------------------------------------
      {"too many fluid particles",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "spacing=1e-6"},
       2,
       {"x.json:2:13: /fluid/0: the fluid would have more than 20000000 lattice points; increase /spacing (now 1e-06 "
        "m)"}},
      {"too many boundary samples",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "boundaries.0.spacing=1e-9"},
       2,
       {"x.json: /boundaries/0: would create about", "boundary samples; the limit is 20000000"}},
      {"layers spreading out",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "boundaries.0.layers=1000", "--set", "boundaries.0.layer_spacing=100"},
       2,
       {"x.json: /boundaries/0: would create about",
        "the limit is 20000000 (check spacing, layers and layer_spacing)"}},
      {"too many frames",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.duration=1e6", "--set", "time.fps=1e3"},
       2,
       {"x.json: /time: duration 1000000 s at fps 1000 makes 1000000000 frames; the limit is 10000000"}},
      {"huge resolution",
       {{"x.json", tiny(R"("render": {"resolution": [100000, 720]},)")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:1:28: /render/resolution/0: value 100000 is out of range; must be an integer in [2, 16384]"}},

      // --- flags --------------------------------------------------------------------------
      {"bad flag value",
       {{"x.json", ok}},
       {"simulate", "x.json", "--threads", "abc"},
       1,
       {"sluice: --threads: expected an integer >= 1 and <= 4096, got 'abc'", "sluice simulate --help"}},
      {"too many threads",
       {{"x.json", ok}},
       {"simulate", "x.json", "--threads", "1000000000"},
       1,
       {"--threads: expected an integer >= 1 and <= 4096, got '1000000000'"}},
      {"negative duration",
       {{"x.json", ok}},
       {"simulate", "x.json", "--duration=-1"},
       1,
       {"--duration: expected a number > 0, got '-1'"}},
      {"unknown export format", {{"x.json", ok}}, {"simulate", "x.json", "--export", "pdf"}, 1, {"--export", "pdf"}},
      // A format given twice is the flag's mistake (exit 1, as above), not the scene's.
      {"export format twice",
       {{"x.json", ok}},
       {"simulate", "x.json", "--export", "csv,csv"},
       1,
       {"sluice: error: --export csv,csv: \"csv\" is given twice; each of csv, vtk at most once"}},
      // nlohmann keeps the last of duplicate keys: the override must refuse them as the file does.
      {"duplicate key in a --set value",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", R"(solver={"type":"iisph","type":"wcsph"})"},
       2,
       {"sluice: scene error: --set solver=", "duplicate key \"type\" in the value; each key may appear only once"}},
      {"validate hydrostatic, unknown case",
       {},
       {"validate", "hydrostatic", "--case", "nosuch", "-o", "v"},
       1,
       {"--case nosuch: expected one of ", "iisph_solved", "wcsph_solved", "iisph_extrapolation", "wcsph_zero"},
       false},
      {"validate hydrostatic, a case of the other solver",
       {},
       {"validate", "hydrostatic", "--solver", "wcsph", "--case", "iisph_solved", "-o", "v"},
       1,
       {"--case iisph_solved: it is a case of iisph, and --solver wcsph leaves it out; drop --solver or choose a case "
        "starting with wcsph_"},
       false},
      {"validate dam-break, spacings not coarse to fine",
       {},
       {"validate", "dam-break", "--spacing", "0.02,0.04", "-o", "v"},
       1,
       {"--spacing 0.02,0.04: the spacings must run from coarse to fine"},
       false},
      {"validate elliptical-drop, two spacings",
       {},
       {"validate", "elliptical-drop", "--spacing", "0.05,0.025", "-o", "v"},
       1,
       {"--spacing 0.05,0.025: elliptical-drop runs one spacing"},
       false},
      {"validate dam-break too short to reach the first measured point",
       {},
       {"validate", "dam-break", "--scene", kRoot + "scenes/validation/dam_break_martin_moyce.json", "--spacing",
        "0.05", "--set", "time.duration=0.1", "-o", "v"},
       2,
       {"/time/duration: the run ends at t = 0.1 s (T = 0.443), before the experiment's first measured point T = "
        "0.832",
        "so there is no front to measure; make it at least 0.188 s"},
       false},
      {"unknown flag", {{"x.json", ok}}, {"simulate", "x.json", "--frobnicate"}, 1, {"--frobnicate", "--help"}},
      {"missing scene argument",
       {},
       {"simulate"},
       1,
       {"SCENE (or --resume DIR) is required", "sluice simulate --help"}},
      {"no subcommand", {}, {}, 1, {"A subcommand is required", "sluice --help"}},
      {"bad --frames",
       {{"x.json", ok}},
       {"render", "x.json", "--frames", "5:1", "-q"},
       1,
       {"sluice: error: --frames 5:1: expected A:B, whole frame numbers with 0 <= A <= B"}},
      {"odd resolution for video",
       {{"x.json", ok}},
       {"render", "x.json", "--resolution", "101x100", "-q"},
       1,
       {"--resolution 101x100: H.264 (yuv420p) needs even width and height; or pass --no-video"}},
      {"bad --resolution",
       {{"x.json", ok}},
       {"render", "x.json", "--resolution", "99999x2", "-q"},
       1,
       {"--resolution 99999x2: expected WxH with 2 <= W, H <= 16384"}},

      // --- the output directory -------------------------------------------------------------
      {"output directory under a file",
       {{"x.json", ok}, {"afile", "x"}},
       {"simulate", "x.json", "-q", "-o", "afile/out"},
       3,
       {"sluice: output error: afile/out: cannot create directory: Not a directory"}},
      {"output directory under /dev/null",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "-o", "/dev/null/x"},
       3,
       {"sluice: output error: /dev/null/x: cannot create directory"}},
      {"output directory is a file",
       {{"x.json", ok}, {"afile", "x"}},
       {"simulate", "x.json", "-q", "-o", "afile"},
       3,
       {"afile: output directory exists and is not a directory"}},
      {"output directory holds a previous run",
       {{"x.json", ok},
        {"out/stats.csv", "step\n1\n"},
        {"out/summary.json", previous_summary},
        {"out/frames/frame_00000.png", "png"}},
       {"simulate", "x.json", "-q", "-o", "out"},
       3,
       {"sluice: output error: out: output directory holds a previous run (stats.csv, summary.json, frames/); pass "
        "--overwrite"}},
      {"previous run, render",
       {{"x.json", ok}, {"out/summary.json", previous_summary}, {"out/stats.csv", "step\n"}},
       {"render", "x.json", "-q", "-o", "out"},
       3,
       {"out: output directory holds a previous run (stats.csv, summary.json)", "--overwrite"}},
      {"killed run's temporary stats",
       {{"x.json", ok}, {"renders/tiny/stats.csv.tmp", "step\n1\n"}},
       {"simulate", "x.json", "-q"},
       3,
       {"renders/tiny: output directory holds a previous run (stats.csv.tmp)", "--overwrite"}},

      // --- issue 19: hostile testing ----------------------------------------------------------
      // 2: --overwrite must not delete the input
      {"scene among the files --overwrite removes",
       {{"out/summary.json", ok}},
       {"simulate", "out/summary.json", "-q", "-o", "out", "--overwrite"},
       3,
       {"sluice: output error: out/summary.json: --overwrite would delete the scene file out/summary.json"}},
      {"compare --diff onto an input",
       {{"a.png", "x"}, {"b.png", "y"}},
       {"compare", "a.png", "b.png", "--diff", "a.png"},
       2,
       {"sluice: error: --diff a.png: it names the input image a.png"}},
      // 3: steps that never end
      {"too many steps",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.dt=1e-9"},
       2,
       {"x.json: /time/dt: dt 1e-09 s for 0.12 s (an automatic settle of up to 0.1 s + duration) makes at least "
        "120000000 steps; the limit is 10000000"}},
      {"dt_min that does not advance the time",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.dt=null", "--set", "time.dt_min=1e-320"},
       2,
       {"x.json: /time/dt_min: value", "does not advance the time at t = 0.12 s in double precision; must be > "}},
      {"dt_min = dt_max = 1e-320",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "time.dt=null", "--set", "time.dt_min=1e-320", "--set",
        "time.dt_max=1e-320"},
       2,
       {"x.json: /time/dt_max: dt_max", "makes at least inf steps; the limit is 10000000"}},
      // 4: --frames past the end
      {"--frames past the end",
       {{"x.json", ok}},
       {"render", "x.json", "-q", "--frames", "5:10"},
       1,
       {"sluice: error: --frames 5:10: the scene's last frame is 1 (time.duration 0.02 s at 50 frames/s); allowed: 0 "
        "<= A <= B <= 1"}},
      {"--frames beyond 32 bits",
       {{"x.json", ok}},
       {"render", "x.json", "-q", "--frames", "0:2147483648"},
       1,
       {"--frames 0:2147483648: the scene's last frame is 1"}},
      // 5: a name that leaves renders/
      {"name with ../",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--set", "name=../../etc/x"},
       2,
       {"x.json: /name: invalid value \"../../etc/x\"; a name must not contain '/'"}},
      // 6: colour ranges that are not numbers
      {"--range -inf:inf",
       {{"x.json", ok}},
       {"render", "x.json", "-q", "--range=-inf:inf"},
       1,
       {"--range -inf:inf: expected lo:hi, finite numbers with lo < hi and hi - lo finite"}},
      {"--range nan:1",
       {{"x.json", ok}},
       {"render", "x.json", "-q", "--range=nan:1"},
       1,
       {"--range nan:1: expected lo:hi"}},
      {"render.range +-1e308",
       {{"x.json", tiny(R"("render": {"range": [-1e308, 1e308]},)")}},
       {"render", "x.json", "-q"},
       2,
       {"x.json:1:22: /render/range: range [-1e+308,1e+308] must be [lo, hi] with lo < hi and hi - lo finite"}},
      // 7: --max-fraction nan
      {"compare --max-fraction nan",
       {{"a.png", "x"}},
       {"compare", "a.png", "a.png", "--max-fraction", "nan"},
       2,
       {"sluice: --max-fraction: expected a number >= 0 and <= 1, got 'nan'"}},
      // 8: a polygon without area
      {"zero-area fluid polygon",
       {{"x.json", tiny("", R"([{"shape": "polygon", "points": [[0, 0], [0.3, 0.3], [0.15, 0.15]]}])")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:2:12: /fluid: the scene has no fluid particles (0 lattice points: the fluid blocks are empty or have "
        "no area"}},
      // 12: a polyline running back over itself
      {"self-overlapping polyline",
       {{"x.json", tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                        R"([{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]},
                            {"shape": "polyline", "points": [[0, -0.2], [1, -0.2], [0.5, -0.2]]}])")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:4:61: /boundaries/1/points: segment 0 crosses or runs along another segment; the polyline must not "
        "intersect or overlap itself"}},
      // 13: compare's inputs have their own exit status (3, an I/O error: docs/cli.md)
      {"compare: missing image",
       {{"a.png", "x"}},
       {"compare", "nope.png", "a.png"},
       3,
       {"sluice: input image error: nope.png: cannot open PNG: No such file or directory"}},
      {"compare: not a PNG",
       {{"a.png", "not a png"}},
       {"compare", "a.png", "a.png"},
       3,
       {"sluice: input image error: a.png: cannot read PNG: "}},
      {"compare: truncated PNG",
       {{"a.png", std::string("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16)}},
       {"compare", "a.png", "a.png"},
       3,
       {"sluice: input image error: a.png: cannot read PNG: "}},
      // 14: a duration too short for a step
      {"tiny duration",
       {{"x.json", ok}},
       {"simulate", "x.json", "-q", "--duration", "1e-300"},
       2,
       {"x.json: /time/duration: value 1e-300 is out of range; must be >= 1e-06 [s]"}},
      {"tiny still time",
       {{"x.json", ok}},
       {"still", "x.json", "--time", "1e-300"},
       1,
       {"sluice: error: --time 1e-300: allowed: 0, or 1e-06 s to time.duration"}},
      // 16, 17: still and montage check their sizes and times before running
      {"still --time 1e308",
       {{"x.json", ok}},
       {"still", "x.json", "--time", "1e308"},
       1,
       {"sluice: error: --time 1e+308: the time is after the scene's end; allowed: 0 to time.duration = 0.02 s"}},
      {"still --time after the end",
       {{"x.json", ok}},
       {"still", "x.json", "--time", "0.05"},
       1,
       {"--time 0.05: the time is after the scene's end"}},
      {"montage of 16384x16384 cells",
       {{"x.json", ok}},
       {"montage", "x.json", "--times", "0", "--cell", "16384x16384"},
       1,
       {"sluice: error: --cell 16384x16384: the montage would be ", "the limit is 16384 on each side"}},
      {"montage --times in hexadecimal",
       {{"x.json", ok}},
       {"montage", "x.json", "--times", "0x1"},
       1,
       {"sluice: error: --times 0x1: expected simulated times"}},
      // 17: smaller cases
      {"non-object root with --duration",
       {{"root.json", "[]"}},
       {"simulate", "root.json", "-q", "--duration", "0.01"},
       2,
       {"sluice: scene error: root.json: the scene must be a JSON object {...}, got []"}},
      {"number overflow",
       {{"x.json", "{\"spacing\": 0.05,\n \"time\": {\"duration\": 1e999}}"}},
       {"simulate", "x.json", "-q"},
       2,
       {"sluice: scene error: x.json:2:23: JSON parse error: number overflow parsing '1e999'"}},
      {"points file /dev/null",
       {{"x.json", tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                        R"([{"shape": "points", "file": "/dev/null"}])")}},
       {"simulate", "x.json", "-q"},
       2,
       {"x.json:3:46: /boundaries/0/file: \"/dev/null\" is not a regular file"}},
      {"bytes after a NUL",
       {{"x.json", ok + std::string(1, '\0') + "garbage"}},
       {"simulate", "x.json", "-q"},
       2,
       {"sluice: scene error: x.json:", ": a NUL byte; a scene file is JSON text"}},
      {"still -o a folder",
       {{"x.json", ok}, {"dir/keep", ""}},
       {"still", "x.json", "--time", "0", "-o", "dir"},
       3,
       {"sluice: output error: dir: is a directory; -o takes the PNG file to write"}},
  };
}

TEST(CliErrors, Table) {
  for (const Case& c : cases()) {
    SCOPED_TRACE(c.name);
    CaseDir dir;
    for (const auto& [name, text] : c.files) write_text(dir.work() / name, text);
    const auto before = snapshot(dir.work());
    const Result r = run_sluice(dir, c.args);
    expect_one_clear_line(r, c.status, c.fragments);
    if (c.writes_nothing) {
      EXPECT_EQ(snapshot(dir.work()), before) << "files were written or changed";
    }
    expect_no_partial_files(dir.work(), before);
  }
}

TEST(CliErrors, UnwritableOutputDirectory) {
  if (geteuid() == 0) GTEST_SKIP() << "root writes into read-only folders; the table covers a path under a file";
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  fs::create_directory(dir.work() / "locked");
  fs::permissions(dir.work() / "locked", fs::perms::owner_read | fs::perms::owner_exec);
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "locked"});
  fs::permissions(dir.work() / "locked", fs::perms::owner_all);
  expect_one_clear_line(r, 3, {"sluice: output error: locked: output directory is not writable: Permission denied"});
  EXPECT_TRUE(fs::is_empty(dir.work() / "locked"));
}

// A run that goes unstable keeps what it wrote, under the real names, with a summary
// saying so, and says it in one line.
TEST(CliErrors, UnstableRunKeepsStatsAndSummary) {
  CaseDir dir;
  // The fluid shoots out of the open box at 20 m/s and leaves the scene's bounds
  // within a few steps, after frame 1.
  write_text(dir.work() / "x.json", tiny(R"("stability": {"bounds_margin": 0.05},)"));
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--set", "fluid.0.velocity=[0, 20]",
                                    "--set", "time.duration=0.1", "--set", "time.fps=100"});
  expect_one_clear_line(
      r, 4, {"sluice: unstable at step ", "stats.csv, summary.json and the output up to frame 1 are kept in out"});
  expect_no_partial_files(dir.work());
  ASSERT_TRUE(fs::exists(dir.work() / "out/stats.csv"));
  EXPECT_NE(read_text(dir.work() / "out/stats.csv").find("\n1,"), std::string::npos)
      << "the step before the stop is kept";
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["status"], "unstable");
}

// A settling phase (time.settle) that goes unstable is reported as such, exit status 4,
// and the summary records it although no step of the run was taken.
TEST(CliErrors, UnstableSettlingIsReported) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--set", "time.settle=0.2", "--set",
                                    "stability.max_error_percent=1e-9"});
  expect_one_clear_line(r, 4, {"sluice: unstable while settling (time.settle = 0.2 s) at its step "});
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["status"], "unstable");
  EXPECT_EQ(summary["frames_written"], 0);
}

// --overwrite replaces a previous run: its frames beyond the new run's last one go, so
// that a video made from the folder shows only the new run; other files stay.
TEST(CliErrors, OverwriteReplacesPreviousRun) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  ASSERT_EQ(run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out"}).status, 0);
  write_text(dir.work() / "out/frames/frame_00007.png", "stale");
  write_text(dir.work() / "out/notes.txt", "mine");
  const std::string old_summary = read_text(dir.work() / "out/summary.json");

  const Result refused = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out"});
  expect_one_clear_line(refused, 3, {"out: output directory holds a previous run", "--overwrite"});
  EXPECT_EQ(read_text(dir.work() / "out/summary.json"), old_summary);

  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--overwrite"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.err, "");
  EXPECT_FALSE(fs::exists(dir.work() / "out/frames")) << "the previous run's frames are gone";
  EXPECT_EQ(read_text(dir.work() / "out/notes.txt"), "mine");
  EXPECT_EQ(nlohmann::json::parse(read_text(dir.work() / "out/summary.json"))["status"], "completed");
  expect_no_partial_files(dir.work());
}

// --overwrite also removes the videos of the other formats, their temporary names and
// frames of any --frame-pattern (a PNG in frames/ whose name holds a number).
TEST(CliErrors, OverwriteRemovesOtherVideosAndPatterns) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  for (const char* f :
       {"out/summary.json", "out/tiny.webm", "out/tiny.gif", "out/tiny.webm.tmp.webm", "out/tiny.gif.tmp.gif",
        "out/frames/shot-000.png", "out/frames/shot-001.png.tmp", "out/frames/frame_00003.png"})
    write_text(dir.work() / f, "old");
  write_text(dir.work() / "out/frames/legend.png", "mine: no frame number");
  write_text(dir.work() / "out/tiny.webm.txt", "mine");
  const Result refused = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out"});
  expect_one_clear_line(refused, 3,
                        {"(summary.json, frames/, tiny.webm, tiny.webm.tmp.webm, tiny.gif, tiny.gif.tmp.gif)"});
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--overwrite"});
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* f : {"out/tiny.webm", "out/tiny.gif", "out/tiny.webm.tmp.webm", "out/tiny.gif.tmp.gif",
                        "out/frames/shot-000.png", "out/frames/shot-001.png.tmp", "out/frames/frame_00003.png"})
    EXPECT_FALSE(fs::exists(dir.work() / f)) << f;
  EXPECT_EQ(read_text(dir.work() / "out/frames/legend.png"), "mine: no frame number");
  EXPECT_EQ(read_text(dir.work() / "out/tiny.webm.txt"), "mine");
}

// ffmpeg absent: the frames are kept, no video or log that suggests one, exit 5. Needs
// a headless EGL display; skipped (with the reason) where there is none.
TEST(RenderCli, FfmpegAbsentKeepsFrames) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  fs::create_directory(dir.base() / "empty_bin");
  const Result r = run_sluice(dir, {"render", "x.json", "-q", "-o", "out", "--resolution", "64x64"},
                              (dir.base() / "empty_bin").string());
  if (r.status == 6) GTEST_SKIP() << "no headless EGL here: " << r.err;
  expect_one_clear_line(r, 5,
                        {"sluice: video error: cannot start ffmpeg (No such file or directory; install it",
                         "the frames are kept in out/frames"});
  EXPECT_TRUE(fs::exists(dir.work() / "out/frames/frame_00000.png"));
  EXPECT_TRUE(fs::exists(dir.work() / "out/frames/frame_00001.png"));
  EXPECT_FALSE(fs::exists(dir.work() / "out/tiny.mp4"));
  EXPECT_FALSE(fs::exists(dir.work() / "out/ffmpeg.log"));
  EXPECT_EQ(nlohmann::json::parse(read_text(dir.work() / "out/summary.json"))["status"], "completed");
  expect_no_partial_files(dir.work());
}

// --- parser limits, at the library level ----------------------------------------------------

std::string parse_error(const std::string& text, const std::vector<std::string>& overrides = {}) {
  try {
    parse_scene(text, "x.json", overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(SceneLimits, BoundariesTogetherStayUnderTheSampleLimit) {
  // Each circle alone has about 6.1 million samples (one layer, half a spacing inside);
  // four of them do not fit.
  std::string walls = "[";
  for (int i = 0; i < 4; ++i)
    walls += std::string(i ? ", " : "") +
             R"({"shape": "circle", "center": [5, 5], "radius": 1, "spacing": 1e-6, "layers": 1})";
  walls += "]";
  const std::string e = parse_error(tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])", walls));
  EXPECT_NE(e.find("x.json:3:264: /boundaries/3: the boundaries up to this one would create about 24504423 samples"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("the limit is 20000000 of each"), std::string::npos) << e;
}

TEST(SceneLimits, CoordinatesNearTheRangeOfDouble) {
  // Finite input whose offset layers overflow: refused instead of sampled at infinity.
  const std::string e = parse_error(tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                                         R"([{"shape": "polyline", "points": [[1.7e308, 0], [1.7e308, 1]], "spacing": 1,
                                              "layer_spacing": 1e308, "layers": 3}])"));
  EXPECT_NE(e.find("x.json:3:18: /boundaries/0: "), std::string::npos) << e;
}

TEST(SceneLimits, LongCurveAtASmallFluidSpacing) {
  // Few samples (spacing 1000 m) but a curve of 10^8 fluid spacings to clear the fluid along.
  const std::string e =
      parse_error(tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])",
                       R"([{"shape": "polyline", "points": [[0, -1], [5e6, -1]], "spacing": 1000}])"));
  EXPECT_NE(e.find("x.json:3:18: /boundaries/0: the curve would be cut into about 100000000 pieces"), std::string::npos)
      << e;
}

}  // namespace
}  // namespace sluice

namespace sluice {
namespace {

// --- issue 19: cases that need more than one line of the table ------------------------------

// 9: an object that its script moves into the fluid at t = 0 clears the fluid there (the
// rest pose is far away); the run would otherwise stop later as a leak.
TEST(Reliability, FluidRemovalUsesThePoseAtTimeZero) {
  const std::string boundaries = R"([{"shape": "box", "min": [0, 0], "max": [0.5, 0.5]},
    {"shape": "circle", "center": [5, 5], "radius": 0.1,
     "motion": {"type": "keyframes", "keys": [{"time": 0, "offset": [-4.85, -4.85]}, {"time": 1, "offset": [-4.85, -4.85]}]}}])";
  const Scene scene =
      parse_scene(tiny("", R"([{"shape": "rectangle", "min": [0, 0], "max": [0.3, 0.3]}])", boundaries), "x.json");
  EXPECT_GT(scene.fluid_removed, 0);
  for (const Vec2& p : scene.fluid_x) EXPECT_GT((p - Vec2(0.15, 0.15)).norm(), 0.1) << p.transpose();
  EXPECT_EQ(count_fluid_in_solids(scene, scene.fluid_x, 0.0), 0);
}

// 15: a scene too large for the memory the process may use is refused before anything is
// allocated, with both figures (here under RLIMIT_AS, as `ulimit -v` sets it).
TEST(Reliability, MemoryEstimateRefusesBeforeAllocating) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  test::Limits limits;
  limits.address_space = 256ull << 20;
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--set", "spacing=0.0005"}, "", limits);
  expect_one_clear_line(r, 2,
                        {"sluice: scene error: x.json: /spacing: 360000 fluid particles and ",
                         " of memory; the limit is 256 MiB (RLIMIT_AS (ulimit -v)); increase /spacing"});
  EXPECT_FALSE(fs::exists(dir.work() / "out/stats.csv"));
}

// 1, 10, 13: a disk that fills up during the run (RLIMIT_FSIZE: a write past the limit
// fails with EFBIG). The run's record stays: stats.csv with the rows it has and a
// summary.json saying "failed"; no temporary file; exit 3 with the path and errno.
void expect_failed_run_kept(const CaseDir& dir, const Result& r, const std::string& failed_file) {
  expect_one_clear_line(r, 3, {"sluice: output error: " + failed_file, "File too large"});
  expect_no_partial_files(dir.work());
  ASSERT_TRUE(fs::exists(dir.work() / "out/stats.csv"));
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_NE(summary["message"].get<std::string>().find("File too large"), std::string::npos) << summary["message"];
}

// Why this machine cannot render (exit status 6 of a plain still of x.json), or "": the
// tests that render ask first, so that a 6 from the case itself is a failure, not a skip.
std::string no_egl(const CaseDir& dir) {
  const Result r = run_sluice(dir, {"still", "x.json", "--time", "0", "--resolution", "16x16", "-o", "egl_probe.png"});
  fs::remove(dir.work() / "egl_probe.png");
  return r.status == 6 ? r.err : "";
}

long count_pngs(const fs::path& folder) {
  long n = 0;
  for (const auto& e : fs::directory_iterator(folder)) n += e.path().extension() == ".png";
  return n;
}

TEST(Reliability, SimulateOnAFullDiskKeepsTheRecord) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  test::Limits limits;
  limits.file_size = 16384;  // stats.csv reaches it after ~60 of its 200 rows
  const Result r = run_sluice(dir, {"simulate", "x.json", "-q", "-o", "out", "--set", "time.duration=1"}, "", limits);
  expect_failed_run_kept(dir, r, "out/stats.csv");
}

TEST(RenderReliability, RenderOnAFullDiskKeepsTheRecord) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  test::Limits limits;
  limits.file_size = 16384;
  if (const std::string why = no_egl(dir); !why.empty()) GTEST_SKIP() << "no headless EGL here: " << why;
  const Result r = run_sluice(
      dir, {"render", "x.json", "-q", "-o", "out", "--no-video", "--resolution", "64x64", "--set", "time.duration=1"},
      "", limits);
  expect_failed_run_kept(dir, r, "out/stats.csv");
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["frames_written"], count_pngs(dir.work() / "out/frames"));
}

// A frame that cannot be written: exit 3 naming it (not 6, "no EGL"), no frame_*.png.tmp,
// and frames_written counts the PNGs there are.
TEST(RenderReliability, FrameThatCannotBeWrittenExits3) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  test::Limits limits;
  limits.file_size = 8192;  // under one 1280x720 frame, over the short run's stats.csv and summary
  if (const std::string why = no_egl(dir); !why.empty()) GTEST_SKIP() << "no headless EGL here: " << why;
  const Result r = run_sluice(dir, {"render", "x.json", "-q", "-o", "out", "--no-video"}, "", limits);
  expect_one_clear_line(r, 3, {"sluice: output error: out/frames/frame_00000.png: write failed: File too large"});
  expect_no_partial_files(dir.work());
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["status"], "failed");
  EXPECT_EQ(summary["frames_written"], count_pngs(dir.work() / "out/frames"));
}

TEST(RenderReliability, StillMontageAndDiffOnAFullDiskExit3) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  // Noise: the diff image does not compress below the limit.
  render::Image a(256, 256), b(256, 256);
  unsigned seed = 1;
  for (auto& c : a.rgb) c = static_cast<std::uint8_t>((seed = seed * 1103515245u + 12345u) >> 24);
  render::write_png((dir.work() / "a.png").string(), a);
  render::write_png((dir.work() / "b.png").string(), b);
  test::Limits limits;
  limits.file_size = 8192;  // under any PNG here, over what the program prints on stderr
  const Result diff = run_sluice(dir, {"compare", "a.png", "b.png", "--diff", "d.png"}, "", limits);
  expect_one_clear_line(diff, 3, {"sluice: output error: d.png: write failed: File too large"});
  EXPECT_FALSE(fs::exists(dir.work() / "d.png.tmp"));
  if (const std::string why = no_egl(dir); !why.empty()) GTEST_SKIP() << "no headless EGL here: " << why;
  const Result still = run_sluice(dir, {"still", "x.json", "--time", "0", "-o", "s.png"}, "", limits);
  expect_one_clear_line(still, 3, {"sluice: output error: s.png: write failed: File too large"});
  // montage says what it runs first; the error is its last line
  const Result montage = run_sluice(dir, {"montage", "x.json", "--times", "0,0.02", "-o", "m.png"}, "", limits);
  EXPECT_EQ(montage.status, 3) << montage.err;
  EXPECT_NE(montage.err.find("\nsluice: output error: m.png: write failed: File too large\n"), std::string::npos)
      << montage.err;
  expect_no_partial_files(dir.work());
}

// --- interruption --------------------------------------------------------------------------

// A render long enough to be interrupted: 5000 steps, 250 small frames.
std::vector<std::string> long_render(const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {"render", "x.json",          "-q",    "-o",           "out", "--resolution", "64x64",
                                   "--set",  "time.duration=5", "--set", "time.dt=0.001"};
  args.insert(args.end(), extra.begin(), extra.end());
  return args;
}

bool wait_for_file(const fs::path& p, double seconds) {
  for (int i = 0; i < static_cast<int>(seconds * 100); ++i) {
    if (fs::exists(p)) return true;
    usleep(10000);
  }
  return fs::exists(p);
}

// SIGINT and SIGTERM stop a real render at the next step: exit 130 / 143, the record says
// "interrupted" with the step and the time and how to resume, stats.csv, the frames and
// the checkpoints stay, nothing partial; and --resume finishes the run.
TEST(RenderReliability, SignalsStopARenderAndKeepItsRecord) {
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal == SIGINT ? "SIGINT" : "SIGTERM");
    CaseDir dir;
    write_text(dir.work() / "x.json", tiny());
    if (const std::string why = no_egl(dir); !why.empty()) GTEST_SKIP() << "no headless EGL here: " << why;
    const pid_t pid = test::start_sluice(dir, long_render({"--no-video", "--checkpoint-every", "2"}));
    if (!wait_for_file(dir.work() / "out/frames/frame_00003.png", 60)) {
      kill(pid, SIGKILL);
      FAIL() << "no frame 3 after 60 s: " << test::wait_sluice(dir, pid).err;
    }
    kill(pid, signal);
    const Result r = test::wait_sluice(dir, pid);
    expect_one_clear_line(
        r, 128 + signal,
        {std::string("sluice: interrupted by ") + (signal == SIGINT ? "SIGINT" : "SIGTERM") + " at step ",
         "are kept in out; resume with: sluice render --resume out"});
    expect_no_partial_files(dir.work());
    const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
    EXPECT_EQ(summary["status"], "interrupted");
    EXPECT_GT(summary["interrupted"]["step"].get<long>(), 0);
    EXPECT_GT(summary["interrupted"]["time"].get<double>(), 0.0);
    EXPECT_EQ(summary["interrupted"]["resume"], "sluice render --resume out");
    EXPECT_EQ(summary["frames_written"], count_pngs(dir.work() / "out/frames"));
    EXPECT_TRUE(fs::exists(dir.work() / "out/stats.csv"));
    EXPECT_TRUE(fs::exists(dir.work() / "out/checkpoints/run.json"));
    if (signal == SIGINT) {
      const Result resumed = run_sluice(dir, {"render", "--resume", "out", "-q"});
      EXPECT_EQ(resumed.status, 0) << resumed.err;
      EXPECT_EQ(nlohmann::json::parse(read_text(dir.work() / "out/summary.json"))["status"], "completed");
    }
  }
}

// A signal during time.settle is seen when the settling ends (the solver's constructor runs
// it): the message says so, and why no checkpoint exists although --checkpoint-every was
// given (checkpoints start at t = 0), instead of asking for --checkpoint-every N and
// reporting "step 0, t = 0" as if the run had started.
TEST(Reliability, SignalWhileSettlingSaysSo) {
  CaseDir dir;
  write_text(dir.work() / "x.json", tiny());
  // 50 000 settling steps of 36 particles: a few seconds.
  const pid_t pid = test::start_sluice(dir, {"simulate", "x.json", "-o", "out", "--checkpoint-every", "1", "--set",
                                             "time.settle=5", "--set", "time.dt=1e-4"});
  bool settling = false;
  for (int i = 0; i < 6000 && !settling; ++i) {
    settling = read_text(dir.base() / "stderr").find("settling for 5 s") != std::string::npos;
    if (!settling) usleep(10000);
  }
  if (!settling) {
    kill(pid, SIGKILL);
    FAIL() << "no settling after 60 s: " << test::wait_sluice(dir, pid).err;
  }
  kill(pid, SIGINT);
  const Result r = test::wait_sluice(dir, pid);
  EXPECT_EQ(r.status, 130) << r.err;
  const std::string last = r.err.substr(r.err.rfind("sluice:"));
  for (const std::string f :
       {"sluice: interrupted by SIGINT while settling (time.settle = 5 s, run to its end), before t = 0",
        "stats.csv and summary.json are kept in out",
        "no frame and no checkpoint was written (checkpoints start at t = 0, after settling); run again with "
        "--overwrite"})
    EXPECT_NE(last.find(f), std::string::npos) << "missing '" << f << "' in: " << r.err;
  EXPECT_EQ(r.err.find("--checkpoint-every N"), std::string::npos) << r.err;
  expect_no_partial_files(dir.work());
  const auto summary = nlohmann::json::parse(read_text(dir.work() / "out/summary.json"));
  EXPECT_EQ(summary["status"], "interrupted");
  EXPECT_EQ(summary["interrupted"]["settling"], true);
  EXPECT_EQ(summary["frames_written"], 0);
}

// When WCSPH stops the elliptical drop (here its step, set too long for its acoustic
// limit; IISPH takes it), the IISPH result computed before it is written, not lost.
TEST(Reliability, EllipticalDropKeepsTheResultBeforeAFailure) {
  CaseDir dir;
  const Result r =
      run_sluice(dir, {"validate", "elliptical-drop", "--scene", kRoot + "scenes/validation/elliptical_drop.json",
                       "--spacing", "0.1", "--set", "time.dt=0.01", "--set", "solver.stiffness=1e6", "-o", "v"});
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("acoustic limit"), std::string::npos) << r.err;
  EXPECT_NE(r.out.find("with the iisph run before wcsph stopped"), std::string::npos) << r.out;
  const std::string csv = read_text(dir.work() / "v/elliptical_drop.csv");
  EXPECT_NE(csv.find("\niisph,0.1,"), std::string::npos) << csv;
  EXPECT_EQ(csv.find("wcsph"), std::string::npos) << csv;
  EXPECT_NE(read_text(dir.work() / "v/elliptical_drop_axes.csv").find("\niisph,"), std::string::npos);
}

// 11: SIGTERM while ffmpeg encodes stops ffmpeg too (no orphan), removes its partial file
// (each format's own temporary name), and the summary says "interrupted" with the
// command that makes the video.
TEST(RenderReliability, SigtermWhileEncodingStopsFfmpeg) {
  for (const std::string format : {"mp4", "webm"}) {
    SCOPED_TRACE(format);
    CaseDir dir;
    write_text(dir.work() / "x.json", tiny());
    // A stand-in ffmpeg that starts its output file and then takes its time.
    const fs::path bin = dir.base() / "bin";
    write_text(bin / "ffmpeg",
               "#!/bin/sh\necho $$ > ffmpeg.pid\nfor a; do last=$a; done\n: > \"$last\"\nexec /bin/sleep 60\n");
    fs::permissions(bin / "ffmpeg", fs::perms::owner_all);
    if (const std::string why = no_egl(dir); !why.empty()) GTEST_SKIP() << "no headless EGL here: " << why;
    const pid_t pid = test::start_sluice(
        dir, {"render", "x.json", "-q", "-o", "out", "--resolution", "64x64", "--format", format}, bin.string());
    // The shell creates ffmpeg.pid before it writes the pid: wait for the text.
    bool started = wait_for_file(dir.work() / "ffmpeg.pid", 60);
    for (int i = 0; started && i < 500 && read_text(dir.work() / "ffmpeg.pid").empty(); ++i) usleep(10000);
    if (!started || read_text(dir.work() / "ffmpeg.pid").empty()) {
      kill(pid, SIGKILL);
      FAIL() << "the stand-in ffmpeg did not start: " << test::wait_sluice(dir, pid).err;
    }
    const fs::path partial = dir.work() / ("out/tiny." + format + ".tmp." + format);
    wait_for_file(partial, 5);  // let it create its output file
    const pid_t ffmpeg = std::stoi(read_text(dir.work() / "ffmpeg.pid"));
    kill(pid, SIGTERM);
    const Result r = test::wait_sluice(dir, pid);
    const bool orphan = kill(ffmpeg, 0) == 0;
    if (orphan) kill(ffmpeg, SIGKILL);
    EXPECT_FALSE(orphan) << "ffmpeg still runs";
    fs::remove(dir.work() / "ffmpeg.pid");
    expect_one_clear_line(
        r, 143,
        {"sluice: interrupted by SIGTERM while ffmpeg encoded out/tiny." + format, "make the video with: ffmpeg "});
    EXPECT_FALSE(fs::exists(partial));
    EXPECT_FALSE(fs::exists(dir.work() / ("out/tiny." + format)));
    expect_no_partial_files(dir.work());
    EXPECT_EQ(nlohmann::json::parse(read_text(dir.work() / "out/summary.json"))["status"], "interrupted");
  }
}

}  // namespace
}  // namespace sluice
