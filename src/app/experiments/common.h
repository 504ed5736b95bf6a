#pragma once
// What the experiments of `sluice experiment` (app/experiment.cpp, one file each here)
// share: the run context, CSV numbers, figure specs and the scenes they derive.
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "analysis/figures.h"
#include "analysis/sweep.h"
#include "app/commands.h"
#include "io/csv.h"
#include "scene/scene.h"

namespace sluice::app::experiments {

namespace fs = std::filesystem;
using analysis::FigureKind;
using analysis::FigureSpec;
using analysis::SweepRun;

// `digits` significant digits (%g).
std::string fmt(double v, int digits = 9);

// 1-minute load average: timing experiments record it, since timings taken while other
// work shares the cores are not speed figures.
double load_average();

struct Context {
  fs::path dir;                   // <output>/<experiment>
  fs::path root;                  // <output>
  bool quick = false;             // the small version (tests, a first look)
  std::string scenes = "scenes";  // where the base scenes are
  std::string scene;              // --scene: replaces the experiment's base scene
  std::vector<std::string> set;   // --set: applied after the experiment's own overrides
  std::string md;                 // summary.md

  std::string scene_path(const std::string& base) const { return scene.empty() ? scenes + "/" + base : scene; }
  // The quick versions coarsen the base scenes first (an experiment's own overrides win).
  Scene load(const std::string& base, std::vector<std::string> own) const {
    // The thesis' relaxed Jacobi (Algorithm 2), whatever the program's default solver.
    own.insert(own.begin(), "solver.pressure_solver=jacobi");
    if (quick && scene.empty() && base == "column.json") own.insert(own.begin(), "spacing=0.02");
    if (quick && scene.empty() && base == "dam_break.json") own.insert(own.begin(), "spacing=0.04");
    own.insert(own.end(), set.begin(), set.end());
    return load_scene(scene_path(base), own);
  }
  // Makes the figure in `dir` and links it (or says why there is none) in summary.md.
  void figure(FigureSpec spec, const std::string& caption);
  // A Markdown table of the CSV file's columns (all when empty) in summary.md.
  void table(const fs::path& csv, const std::vector<std::string>& columns);
};

FigureSpec spec(FigureKind kind, const fs::path& csv, const std::string& x, std::vector<std::string> y,
                const std::string& output);

// One line per run: solver, steps, iterations, error, speed.
void print_run(const std::string& what, const SweepRun& r);

// The column scene of a given fluid height [m] (the tank 0.2 m higher).
std::vector<std::string> column_height(double width, double height);

// The boundary methods, and the scene of boundary-gamma and boundary-iterations.
extern const char* const kMethods[3];
// The scene of the boundary experiments: the breaking dam at h = 0.02 (5000 particles)
// with dt = 2 ms (a CFL number up to about 0.6): at the scene's 0.5 ms the solver stops
// at its minimum of 3 iterations on almost every step, and no method or gamma can show
// a difference.
std::vector<std::string> boundary_scene(const Context& c, double duration);

// Wall milliseconds per step of `scene` for each thread count, `repeat` rounds with the
// thread counts interleaved (1, 2, 1, 2, ...), so that a slow spell of a shared machine
// hits every thread count alike. ms[t][r]: thread count t, round r. after_run(t, run),
// when given, runs right after each run, still with threads[t] threads (reference loops
// timed in the same spell of load, per-thread-count results).
std::vector<std::vector<double>> interleaved_ms_per_step(
    const Scene& scene, const std::vector<int>& threads, int repeat, SweepRun* last = nullptr,
    const std::function<void(std::size_t, const SweepRun&)>& after_run = {});
double median(std::vector<double> v);
double mean(const std::vector<double>& v);

// Runs `m` with the context's overrides into DIR/file and links it in summary.md.
void montage_figure(Context& c, MontageOptions m, const std::string& file, const std::string& caption);

// The experiments, one file each (the list with names and thesis references: app/experiment.cpp).
void snapshots(Context& c);
void dam_break_iterations(Context& c);
void iisph_dt(Context& c);
void column_height_experiment(Context& c);
void fixed_iterations(Context& c);
void boundary_pressure(Context& c);
void boundary_gamma(Context& c);
void boundary_iterations(Context& c);
void wcsph(Context& c);
void speed_error(Context& c);
void parallel(Context& c);
void scaling(Context& c);
void neighbour_search(Context& c);

}  // namespace sluice::app::experiments
