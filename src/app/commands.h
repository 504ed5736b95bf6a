#pragma once
// Subcommands of the `sluice` program; each is a thin layer over the library.
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
  std::vector<std::string> exports;  // csv, vtk
  bool quiet = false;
  int checkpoint_every = 0;  // frames between checkpoints (0: none)
  std::string resume;        // run directory to continue (its recorded scene and flags)
};
int run_simulate(const SimulateOptions& o);

struct BenchOptions {
  std::vector<std::string> scenes;
  long steps = 200;        // steps per run (0: the scene's whole duration)
  int repeat = 3;          // runs per scene; the median is reported
  int threads = 0;
  std::vector<std::string> set;
  std::string csv = "renders/bench/bench.csv";
  bool brute_force = false;  // O(n^2) neighbour search (the thesis' Figure 14 comparison)
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
  int threads = 0;
  std::vector<std::string> set;
  bool quiet = false;
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
  int tolerance = 0;          // allowed channel difference per pixel
  double max_fraction = 0;    // share of pixels allowed beyond the tolerance
  std::string diff;           // diff image path (written when the images differ)
};
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
  bool quick = false;        // the short version of every case (what CI runs)
  std::string solver = "both";  // iisph | wcsph | both
  std::string only;          // run only the case of this name
  int threads = 0;
  std::string csv = "renders/suite/suite.csv";
};
int run_suite(const SuiteOptions& o);

void set_threads(int threads);

}  // namespace sluice::app
