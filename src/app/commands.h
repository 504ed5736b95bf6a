#pragma once
// Subcommands of the `sluice` program; each is a thin layer over the library. Their flags
// are set up in app/cmd_<name>.cpp (app/cli.h), their runs in app/<name>.cpp.
#include <string>
#include <vector>

#include "view/scene_view.h"

namespace sluice::app {

struct SimulateOptions {
  std::string scene;
  std::string output_dir;  // empty: the scene's output.directory
  double duration = 0;     // > 0 overrides time.duration
  int threads = 0;         // 0: OpenMP default
  std::vector<std::string> set;
  std::vector<std::string> exports;  // csv, vtk (empty: the scene's output.export)
  bool quiet = false;
  bool overwrite = false;    // replace a previous run in the output directory
  int checkpoint_every = 0;  // frames between checkpoints (0: none)
  std::string resume;        // run directory to continue (its recorded scene and flags)
};
int run_simulate(const SimulateOptions& o);

struct BenchOptions {
  std::vector<std::string> scenes;
  long steps = 200;  // steps per run (0: the scene's whole duration)
  int repeat = 3;    // runs per scene; the median is reported
  int threads = 0;
  std::vector<std::string> set;
  std::string csv = "renders/bench/bench.csv";
  bool brute_force = false;  // O(n^2) neighbour search (the thesis' Figure 14 comparison)
  // Sweep mode (any of these set): one scene, every combination of the swept values run
  // to the scene's duration; bench.csv, bench.md and bench.png in `output_dir`.
  std::vector<std::string> sweep;    // KEY=V1,V2,...
  double duration = 0;               // > 0 overrides time.duration
  std::string output_dir;            // default renders/bench/<scene name>
  std::string jobs;                  // write the runs' command lines here instead of running them
  std::vector<std::string> collect;  // merge the bench.csv files of these directories
  bool overwrite = false;            // replace an earlier bench.csv (sweep, --collect) or run (--end-to-end)
  // End-to-end mode: `render` of one scene (default scenes/dam_break_130k.json) timed as a
  // whole and split (simulation, drawing, PNG, video); end_to_end.csv in `output_dir`
  // (default renders/bench/end_to_end). duration 0: 5 s.
  bool end_to_end = false;
  double fps = 60;
  std::string resolution = "1920x1080";
};
int run_bench(const BenchOptions& o);

using view::ImageOptions;

struct RenderOptions {
  std::string scene;
  std::string output_dir;  // empty: the scene's output.directory
  double fps = 0;          // > 0 overrides time.fps
  double duration = 0;     // > 0 overrides time.duration
  std::string frames;      // "A:B": render only frames A..B (the run stops at B)
  ImageOptions image;
  bool no_video = false;
  std::string format = "mp4";                    // video container: mp4 | webm | gif
  int crf = -1;                                  // video quality (< 0: the format's default)
  std::string frame_pattern = "frame_%05d.png";  // the PNG frames' names (printf, one %d)
  std::vector<std::string> exports;              // csv, vtk (empty: the scene's output.export)
  int threads = 0;
  std::vector<std::string> set;
  bool quiet = false;
  bool overwrite = false;    // replace a previous run in the output directory
  int checkpoint_every = 0;  // frames between checkpoints (0: none)
  std::string resume;        // run directory to continue (its recorded scene and flags)
};
int run_render(const RenderOptions& o);

struct StillOptions {
  std::string scene;
  double time = 0;
  std::string output;  // empty: <output dir>/still.png
  ImageOptions image;
  int threads = 0;
  std::vector<std::string> set;
};
int run_still(const StillOptions& o);

struct CompareOptions {
  std::string a, b;
  std::string preset = "strict";     // strict | tests (render::kStrictRule, kTestsRule)
  int tolerance = -1;                // allowed channel difference per pixel; < 0: the preset's
  double max_fraction = -1;          // share of compared pixels allowed beyond it; < 0: the preset's
  std::string mask;                  // PNG of the images' size: its non-black pixels are ignored
  std::vector<std::string> regions;  // "x,y,w,h": ignored rectangles
  std::string diff;                  // diff image path (written when the images differ)
};
// The exit status of `sluice compare`, for CI scripts (docs/cli.md). A FlagError is a
// usage error there; an ImageReadError or OutputError an I/O error.
enum CompareExit : int { kCompareSame = 0, kCompareDifferent = 1, kCompareUsage = 2, kCompareIo = 3, kCompareSize = 4 };
int run_compare(const CompareOptions& o);

struct BenchRenderOptions {
  std::vector<long> particles{10000, 130000};
  std::vector<std::string> resolutions{"1280x720", "1920x1080"};
  int repeat = 5;
  int msaa = 0;
  std::string egl = "auto";
  std::string csv = "renders/bench/render.csv";
};
int run_bench_render(const BenchRenderOptions& o);

struct SuiteOptions {
  std::string file = "scenes/hard/suite.json";
  bool quick = false;           // the short version of every case (what CI runs)
  std::string solver = "both";  // iisph | wcsph | both
  std::string only;             // run only the case of this name
  int threads = 0;
  std::string csv = "renders/suite/suite.csv";
};
int run_suite(const SuiteOptions& o);

struct ValidateOptions {
  std::string what;   // hydrostatic | dam-break | elliptical-drop
  std::string scene;  // empty: scenes/validation/<what>.json
  std::string output_dir = "renders/validation";
  std::string solver = "both";  // dam-break, elliptical-drop: iisph | wcsph | both
  std::string only;             // hydrostatic: run only this case
  // dam-break: the spacings to run (empty: 0.04, 0.02, 0.01); elliptical-drop: at most one,
  // overriding the scene's. Each > 0.
  std::vector<double> spacing;
  double max_rms = 0.20;  // dam-break: bound on the RMS relative front error (the tests' bound)
  int threads = 0;
  std::vector<std::string> set;
};
int run_validate(const ValidateOptions& o);

void set_threads(int threads);

// "path=value" for a --set override from a numeric flag, with every digit of the value
// (std::to_string keeps 6 decimals: --duration 1e-7 became time.duration=0.000000).
std::string number_override(const std::string& path, double value);

// `sluice montage`: snapshots of a scene at several times (and, with --vary, for several
// values of one scene setting) in one grid image with one shared colour scale.
struct MontageOptions {
  std::string scene;
  std::string times;  // "T1,T2,...": strictly increasing, within [0, time.duration]
  std::string vary;   // "KEY=V1,V2,...": one fresh run per value (applied as --set KEY=V)
  int cols = 0;       // 0: the number of times when varying, else min(4, times)
  std::vector<std::string> set;
  std::string cell = "480x270";  // size of each rendered cell, WxH
  std::string color_by;          // empty: the scene's render.color_by
  std::string colormap;          // empty: the scene's render.colormap
  std::string range;             // "lo:hi" or "auto"; empty: the scene's render range
  std::string title;
  std::string overlay = "time";  // each cell's band: full | time | none
  std::string output;            // empty: <output directory>/montage.png
  int threads = 0;
};
int run_montage(const MontageOptions& o);

}  // namespace sluice::app

namespace sluice::app {

// `sluice figures KIND INPUT...`: gnuplot figures from stats.csv / bench.csv / experiment
// CSV files (analysis/figures.h), Markdown tables, and the standard figures of a run.
struct FiguresOptions {
  std::string kind;                 // series | box | scatter | table | run
  std::vector<std::string> inputs;  // CSV files (run: run directories holding stats.csv)
  std::string x = "time";
  std::vector<std::string> y;
  std::vector<std::string> labels;
  std::string group;
  std::vector<std::string> where;
  std::string color;
  std::string highlight;
  bool mean = false, pareto = false, logx = false, logy = false;
  std::string style = "lines";
  std::string title, xlabel, ylabel;
  std::string output;  // figure (png/svg/pdf) or table (.md); run: a directory
  std::string size = "1200x800";
  std::vector<std::string> columns;  // table: the columns to show (default all)
  std::string format = "png";        // run: png, svg or pdf
};
int run_figures(const FiguresOptions& o);

}  // namespace sluice::app

namespace sluice::app {

// `sluice experiment NAME...`: the thesis' chapter-5 experiments (app/experiment.cpp lists
// them, app/experiments/ holds one file each).
struct ExperimentOptions {
  std::vector<std::string> names;                  // experiment names, `all` or `list`
  std::string output_dir = "renders/experiments";  // each experiment writes DIR/<name>/
  bool quick = false;                              // small versions (tests, a first look)
  std::string scenes = "scenes";                   // folder of the base scenes
  std::string scene;                               // replaces the base scene (one experiment)
  std::vector<std::string> set;                    // overrides applied after the experiment's
  int threads = 0;
};
int run_experiment(const ExperimentOptions& o);
std::vector<std::string> experiment_names();

}  // namespace sluice::app
