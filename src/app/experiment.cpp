// `sluice experiment NAME`: the experiments of the thesis' chapter 5, one command each.
// Every experiment writes its numbers as CSV, its figures through `sluice figures`
// (analysis/figures.h) and a summary.md that says what to compare with which thesis
// figure or table. Runs are fresh in-process simulations (analysis::run_sweep_point), so
// a result does not depend on the order of the runs.
//
// Units: the thesis' experiments use their own scale (time steps of 0.05 s); sluice's
// scenes are in metres with h = 0.01 m, so the swept values are the equivalents here
// (the stable range of dt, the column of 5000 particles), not the thesis' numbers.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <map>

#include "analysis/csv.h"
#include "analysis/figures.h"
#include "analysis/machine.h"
#include "analysis/sweep.h"
#include "app/commands.h"
#include "app/run.h"
#include "io/output.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::app {

namespace {

namespace fs = std::filesystem;
using analysis::FigureKind;
using analysis::FigureSpec;
using analysis::SweepRun;

std::string fmt(double v, int digits = 9) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// A CSV file built row by row.
class Csv {
 public:
  explicit Csv(std::string header) : text_(std::move(header) + "\n") {}
  void row(const std::vector<std::string>& fields) { text_ += analysis::join(fields, ",") + "\n"; }
  void write(const fs::path& path) const { write_file_atomic(path.string(), text_); }

 private:
  std::string text_;
};

// 1-minute load average: timing experiments record it, since timings taken while other
// work shares the cores are not speed figures.
double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = -1;
  in >> l;
  return l;
}

struct Context {
  fs::path dir;                   // <output>/<experiment>
  fs::path root;                  // <output>
  bool quick = false;             // the small version (tests, a first look)
  std::string scenes = "scenes";  // where the base scenes are
  std::string scene;              // --scene: replaces the experiment's base scene
  std::vector<std::string> set;   // --set: applied after the experiment's own overrides
  std::string md;                 // summary.md

  std::string scene_path(const std::string& base) const { return scene.empty() ? scenes + "/" + base : scene; }
  // The quick versions coarsen the base scenes first (an experiment's own spacing wins).
  Scene load(const std::string& base, std::vector<std::string> own) const {
    if (quick && scene.empty() && base == "column.json") own.insert(own.begin(), "spacing=0.02");
    if (quick && scene.empty() && base == "dam_break.json") own.insert(own.begin(), "spacing=0.04");
    own.insert(own.end(), set.begin(), set.end());
    return load_scene(scene_path(base), own);
  }
  void figure(FigureSpec spec, const std::string& caption) {
    spec.output = (dir / spec.output).string();
    const std::string why = analysis::make_figure(spec);
    const std::string name = fs::path(spec.output).filename().string();
    if (why.empty()) {
      md += "![" + caption + "](" + name + ")\n\n*" + caption + "*\n\n";
      std::printf("  wrote %s\n", spec.output.c_str());
    } else {
      md += "(no figure " + name + ": " + why + ")\n\n";
      std::fprintf(stderr, "sluice: warning: no figure %s: %s\n", spec.output.c_str(), why.c_str());
    }
  }
  void table(const fs::path& csv, const std::vector<std::string>& columns) {
    md += analysis::markdown_table(analysis::read_csv_table(csv.string()), columns) + "\n";
  }
};

FigureSpec spec(FigureKind kind, const fs::path& csv, const std::string& x, std::vector<std::string> y,
                const std::string& output) {
  FigureSpec s;
  s.kind = kind;
  s.inputs = {csv.string()};
  s.x = x;
  s.y = std::move(y);
  s.output = output;
  return s;
}

void print_run(const std::string& what, const SweepRun& r) {
  std::printf("  %-42s %-5s %8ld steps %8.2f iters %9.4f %% err %9.3f s/sim-s%s\n", what.c_str(), r.solver.c_str(), r.steps,
              r.avg_iterations, r.avg_density_error, r.seconds_per_simulated_second(), r.stable ? "" : "  UNSTABLE");
  std::fflush(stdout);
}

std::string override_number(const std::string& key, double v) { return key + "=" + fmt(v, 17); }

// The column scene of a given fluid height [m] (the tank 0.2 m higher).
std::vector<std::string> column_height(double width, double height) {
  return {"fluid.0.max=[" + fmt(width, 17) + "," + fmt(height, 17) + "]",
          "boundaries.0.max=[" + fmt(width, 17) + "," + fmt(height + 0.2, 17) + "]"};
}

// --- Figure 3: iterations and compression error over time (breaking dam) ------------------

void dam_break_iterations(Context& c) {
  std::vector<std::string> own;
  if (c.quick) own = {"time.duration=0.5"};
  const Scene scene = c.load("dam_break.json", own);
  StatsCsv stats((c.dir / "stats.csv").string());
  long max_iterations = 0;
  const SweepRun r = analysis::run_sweep_point(scene, {}, [&](const StepStats& st) {
    stats.write(st);
    max_iterations = std::max<long>(max_iterations, st.iterations);
  });
  stats.finish();
  print_run(scene.name, r);
  c.md += "Scene `" + c.scene_path("dam_break.json") + "`: " + std::to_string(r.particles) + " particles, " +
          std::to_string(r.steps) + " steps to t = " + fmt(r.simulated, 4) + " s" + (r.stable ? "" : " (UNSTABLE: " + r.message + ")") +
          ". Average iterations " + fmt(r.avg_iterations, 4) + " (largest " + std::to_string(max_iterations) +
          "), average density error " + fmt(r.avg_density_error, 3) + " %.\n\n";
  FigureSpec a = spec(FigureKind::Series, c.dir / "stats.csv", "time", {"iterations"}, "iterations.png");
  a.mean = true;
  c.figure(a, "Solver iterations per step over time, with their mean (thesis Figure 3, left)");
  FigureSpec b = spec(FigureKind::Series, c.dir / "stats.csv", "time", {"avg_error_percent"}, "compression_error.png");
  b.mean = true;
  c.figure(b, "Predicted average compression error (Eq. 23) at the solver's exit over time (thesis Figure 3, right)");
}

// --- Figure 6a and Table 2: IISPH against the time step --------------------------------------

void iisph_dt(Context& c) {
  const std::vector<double> dts = c.quick ? std::vector<double>{1e-3, 2e-3}
                                          : std::vector<double>{2.5e-4, 5e-4, 7.5e-4, 1e-3, 1.5e-3, 2e-3};
  // 100 frames at 30 fps, as the thesis' Table 2.
  const double duration = c.quick ? 0.1 : 100.0 / 30.0;
  Csv csv("dt,stable,particles,steps,avg_iterations,avg_density_error_percent,max_density_error_percent,pressure_s,"
          "neighbors_s,overall_s,s_per_simulated_s,best");
  std::vector<SweepRun> runs;
  for (double dt : dts) {
    const Scene scene = c.load("column.json", {override_number("time.dt", dt), override_number("time.duration", duration),
                                               "solver.type=iisph"});
    runs.push_back(analysis::run_sweep_point(scene, {}));
    print_run("dt = " + fmt(dt), runs.back());
  }
  std::size_t best = runs.size();
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].stable && (best == runs.size() || runs[i].ms_phase[4] * runs[i].steps < runs[best].ms_phase[4] * runs[best].steps))
      best = i;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SweepRun& r = runs[i];
    const double n = static_cast<double>(r.steps) / 1000.0;
    csv.row({fmt(dts[i]), r.stable ? "1" : "0", std::to_string(r.particles), std::to_string(r.steps), fmt(r.avg_iterations, 4),
             fmt(r.avg_density_error, 4), fmt(r.max_density_error, 4), fmt(r.ms_phase[2] * n, 4), fmt(r.ms_phase[0] * n, 4),
             fmt(r.ms_phase[4] * n, 4), fmt(r.seconds_per_simulated_second(), 4), i == best ? "1" : "0"});
  }
  csv.write(c.dir / "iisph_dt.csv");
  c.md += "The 5000-particle column (`" + c.scene_path("column.json") + "`), " + fmt(duration, 4) +
          " simulated seconds per run, tolerance 0.1 %. Times are the solver's wall time in seconds (pressure = the "
          "relaxed Jacobi solve, neighbors = the neighbour search, overall = the whole steps); load average at the end " +
          fmt(load_average(), 3) + ". Compare with the thesis' Table 2 and Figure 6a: iterations grow with dt, the "
          "overall time has a minimum where fewer steps stop paying for more iterations.\n\n";
  c.table(c.dir / "iisph_dt.csv", {"dt", "stable", "steps", "avg_iterations", "avg_density_error_percent", "pressure_s",
                                   "neighbors_s", "overall_s", "best"});
  if (best < runs.size()) c.md += "Fastest overall: dt = " + fmt(dts[best]) + " s (`best` = 1).\n\n";
  FigureSpec a = spec(FigureKind::Series, c.dir / "iisph_dt.csv", "dt", {"avg_iterations"}, "iterations_vs_dt.png");
  a.style = "linespoints";
  a.where = {"stable=1"};
  c.figure(a, "Average solver iterations against the time step (thesis Figure 6a)");
  FigureSpec b = spec(FigureKind::Series, c.dir / "iisph_dt.csv", "dt", {"pressure_s", "neighbors_s", "overall_s"},
                      "times_vs_dt.png");
  b.style = "linespoints";
  b.where = {"stable=1"};
  b.ylabel = "wall time for the run [s]";
  c.figure(b, "Pressure solve, neighbour search and overall time against the time step (thesis Table 2)");
}

// --- Figure 6b: IISPH against the column height -------------------------------------------------

void column_height_experiment(Context& c) {
  const std::vector<double> heights = c.quick ? std::vector<double>{0.25, 0.5} : std::vector<double>{0.25, 0.5, 1, 1.5, 2};
  const double duration = c.quick ? 0.1 : 1.0;
  Csv csv("height,particles,stable,steps,avg_iterations,avg_density_error_percent,s_per_simulated_s");
  for (double h : heights) {
    auto own = column_height(0.5, h);
    own.push_back("time.dt=1e-3");
    own.push_back(override_number("time.duration", duration));
    const Scene scene = c.load("column.json", own);
    const SweepRun r = analysis::run_sweep_point(scene, {});
    print_run("height = " + fmt(h) + " m", r);
    csv.row({fmt(h), std::to_string(r.particles), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_iterations, 4),
             fmt(r.avg_density_error, 4), fmt(r.seconds_per_simulated_second(), 4)});
  }
  csv.write(c.dir / "column_height.csv");
  c.md += "Columns 0.5 m wide of growing height, dt = 1 ms, " + fmt(duration, 3) +
          " s each, tolerance 0.1 %. Compare with the thesis' Figure 6b: deeper columns need more iterations.\n\n";
  c.table(c.dir / "column_height.csv", {});
  FigureSpec a = spec(FigureKind::Series, c.dir / "column_height.csv", "height", {"avg_iterations"}, "iterations_vs_height.png");
  a.style = "linespoints";
  a.where = {"stable=1"};
  c.figure(a, "Average solver iterations against the column height at dt = 1 ms (thesis Figure 6b)");
}

// --- Figure 7: compression error against a fixed number of iterations ----------------------------

void fixed_iterations(Context& c) {
  const std::vector<int> counts = c.quick ? std::vector<int>{2, 8} : std::vector<int>{1, 2, 3, 4, 6, 8, 12, 16, 24, 32};
  const double duration = c.quick ? 0.1 : 0.5;
  Csv csv("iterations,stable,steps,avg_density_error_percent,max_density_error_percent,avg_predicted_error_percent,message");
  for (int n : counts) {
    const Scene scene = c.load("column.json", {"time.dt=1e-3", override_number("time.duration", duration),
                                               "solver.min_iterations=" + std::to_string(n),
                                               "solver.max_iterations=" + std::to_string(n)});
    double predicted = 0;
    const SweepRun r = analysis::run_sweep_point(scene, {}, [&](const StepStats& st) { predicted += st.avg_error_percent; });
    print_run(std::to_string(n) + " iterations", r);
    csv.row({std::to_string(n), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4),
             fmt(r.max_density_error, 4), fmt(r.steps > 0 ? predicted / static_cast<double>(r.steps) : 0, 4),
             analysis::csv_quote(r.message)});
  }
  csv.write(c.dir / "fixed_iterations.csv");
  c.md += "The column with exactly N relaxed Jacobi iterations per step (min = max = N), dt = 1 ms, " + fmt(duration, 3) +
          " s each. The density error is Eq. 15's at each step's start; the predicted error is Eq. 23's at the solver's "
          "exit. Compare with the thesis' Figure 7: the error falls as the iterations grow.\n\n";
  c.table(c.dir / "fixed_iterations.csv", {"iterations", "stable", "avg_density_error_percent", "max_density_error_percent",
                                          "avg_predicted_error_percent"});
  FigureSpec a = spec(FigureKind::Series, c.dir / "fixed_iterations.csv", "iterations",
                      {"avg_density_error_percent", "avg_predicted_error_percent"}, "error_vs_iterations.png");
  a.style = "linespoints";
  a.logy = true;
  a.where = {"stable=1"};
  a.xlabel = "solver iterations per step (fixed)";
  a.ylabel = "average compression error [%]";
  c.figure(a, "Compression error against a fixed number of Jacobi iterations (thesis Figure 7)");
}

// --- Figures 9 and 10: boundary methods -----------------------------------------------------------

const char* const kMethods[] = {"extrapolation", "mirroring", "zero"};

// The scene of the boundary experiments: the breaking dam at h = 0.02 (5000 particles)
// with dt = 2 ms (a CFL number up to about 0.6): at the scene's 0.5 ms the solver stops
// at its minimum of 3 iterations on almost every step, and no method or gamma can show
// a difference.
std::vector<std::string> boundary_scene(const Context& c, double duration) {
  return {c.quick ? "spacing=0.05" : "spacing=0.02", "time.dt=2e-3", override_number("time.duration", c.quick ? 0.2 : duration)};
}

// Point i of the Halton sequence in base b (deterministic, evenly spread samples).
double halton(int i, int b) {
  double f = 1, r = 0;
  for (int n = i; n > 0; n /= b) {
    f /= b;
    r += f * (n % b);
  }
  return r;
}

void boundary_gamma(Context& c) {
  const int samples = c.quick ? 2 : 6;
  Csv csv("method,gamma1,gamma2,gamma3,stable,avg_iterations,avg_density_error_percent,s_per_simulated_s,best");
  Csv best_csv("method,gamma1,gamma2,gamma3,avg_iterations,avg_density_error_percent");
  c.md += "For each boundary method, the scene's gammas (0.84, 1, 1) and " + std::to_string(samples) +
          " Halton samples of gamma1 in [0.7, 1.1], gamma2 in [0.7, 1.3], gamma3 in [0.7, 1.5] on the breaking dam "
          "at h = " + std::string(c.quick ? "0.05" : "0.02") + " with dt = 2 ms. The best sample has the fewest average iterations among the stable runs whose average density "
          "error stays within 0.2 % (twice the tolerance: a gamma that lets the fluid compress or leak does not count). "
          "Compare with the thesis' Figure 9 (a local optimum of a random search, like this one).\n\n| method | gamma1 | gamma2 | gamma3 | avg iterations | avg density error % |\n|---|---|---|---|---|---|\n";
  for (const char* method : kMethods) {
    struct Sample {
      double g[3];
      SweepRun r;
    };
    std::vector<Sample> runs;
    for (int i = 0; i <= samples; ++i) {
      Sample s{{0.84, 1.0, 1.0}, {}};
      if (i > 0) s = {{0.7 + 0.4 * halton(i, 2), 0.7 + 0.6 * halton(i, 3), 0.7 + 0.8 * halton(i, 5)}, {}};
      auto own = boundary_scene(c, 0.8);
      own.push_back(std::string("solver.boundary_pressure=") + method);
      for (int k = 0; k < 3; ++k) own.push_back(override_number("solver.gamma" + std::to_string(k + 1), s.g[k]));
      s.r = analysis::run_sweep_point(c.load("dam_break.json", own), {});
      print_run(std::string(method) + " g=" + fmt(s.g[0], 3) + "," + fmt(s.g[1], 3) + "," + fmt(s.g[2], 3), s.r);
      runs.push_back(s);
    }
    std::size_t best = runs.size();
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const SweepRun& r = runs[i].r;
      if (r.stable && r.avg_density_error <= 0.2 && (best == runs.size() || r.avg_iterations < runs[best].r.avg_iterations)) best = i;
    }
    for (std::size_t i = 0; i < runs.size(); ++i) {
      const SweepRun& r = runs[i].r;
      csv.row({method, fmt(runs[i].g[0], 4), fmt(runs[i].g[1], 4), fmt(runs[i].g[2], 4), r.stable ? "1" : "0",
               fmt(r.avg_iterations, 4), fmt(r.avg_density_error, 4), fmt(r.seconds_per_simulated_second(), 4),
               i == best ? "1" : "0"});
    }
    if (best < runs.size()) {
      const Sample& b = runs[best];
      best_csv.row({method, fmt(b.g[0], 4), fmt(b.g[1], 4), fmt(b.g[2], 4), fmt(b.r.avg_iterations, 4), fmt(b.r.avg_density_error, 4)});
      c.md += std::string("| ") + method + " | " + fmt(b.g[0], 3) + " | " + fmt(b.g[1], 3) + " | " + fmt(b.g[2], 3) + " | " +
              fmt(b.r.avg_iterations, 4) + " | " + fmt(b.r.avg_density_error, 3) + " |\n";
    } else {
      c.md += std::string("| ") + method + " | no sample qualified | | | | |\n";
    }
  }
  c.md += "\n";
  csv.write(c.dir / "gamma_search.csv");
  best_csv.write(c.dir / "best.csv");
  for (const char* method : kMethods) {
    FigureSpec a = spec(FigureKind::Scatter, c.dir / "gamma_search.csv", "gamma1", {"gamma3"},
                        std::string("gamma_") + method + ".png");
    a.color = "avg_iterations";
    a.highlight = "best=1";
    a.where = {std::string("method=") + method, "stable=1"};
    a.labels = {std::string("pressure ") + method};
    c.figure(a, std::string("gamma1 against gamma3 for ") + method + ", coloured by average iterations, best ringed (thesis Figure 9)");
  }
}

void boundary_iterations(Context& c) {
  // The gammas of boundary-gamma when it ran into the same output directory.
  std::map<std::string, std::vector<std::string>> gammas;
  const fs::path best = c.root / "boundary-gamma" / "best.csv";
  if (fs::exists(best)) {
    const auto t = analysis::read_csv_table(best.string());
    for (const auto& row : t.rows)
      gammas[row[static_cast<std::size_t>(t.column("method"))]] = {
          "solver.gamma1=" + row[static_cast<std::size_t>(t.column("gamma1"))],
          "solver.gamma2=" + row[static_cast<std::size_t>(t.column("gamma2"))],
          "solver.gamma3=" + row[static_cast<std::size_t>(t.column("gamma3"))]};
  }
  Csv steps("method,time,iterations,density_error_percent");
  Csv means("method,gammas,stable,steps,avg_iterations,avg_density_error_percent");
  for (const char* method : kMethods) {
    auto own = boundary_scene(c, 2.0);
    own.push_back(std::string("solver.boundary_pressure=") + method);
    const auto g = gammas.find(method);
    if (g != gammas.end()) own.insert(own.end(), g->second.begin(), g->second.end());
    const SweepRun r = analysis::run_sweep_point(c.load("dam_break.json", own), {}, [&](const StepStats& st) {
      steps.row({method, fmt(st.time), std::to_string(st.iterations), fmt(st.density_error_percent, 5)});
    });
    print_run(method, r);
    means.row({method, g == gammas.end() ? "scene" : analysis::csv_quote(analysis::join(g->second, " ")), r.stable ? "1" : "0",
               std::to_string(r.steps), fmt(r.avg_iterations, 4), fmt(r.avg_density_error, 4)});
  }
  steps.write(c.dir / "iterations.csv");
  means.write(c.dir / "means.csv");
  c.md += std::string("The breaking dam at h = 0.02, dt = 2 ms, with each boundary method, ") +
          (gammas.empty() ? "with the scene's gammas (run boundary-gamma first into the same output directory to use "
                            "its best ones)"
                          : "with boundary-gamma's best gammas") +
          ". Compare with the thesis' Figure 10 (extrapolation 20.5, mirroring 21.2, zero pressure 21.4 iterations on "
          "average).\n\n";
  c.table(c.dir / "means.csv", {});
  FigureSpec a = spec(FigureKind::Box, c.dir / "iterations.csv", "", {"iterations"}, "iterations_by_method.png");
  a.group = "method";
  c.figure(a, "Distribution of the solver iterations per step for each boundary method; the dot is the mean (thesis Figure 10)");
}

// --- Table 3 and Figure 12: WCSPH ---------------------------------------------------------------

void wcsph(Context& c) {
  const std::vector<double> ks = c.quick ? std::vector<double>{1e5, 1e6} : std::vector<double>{1e5, 3e5, 1e6, 3e6, 1e7};
  const double duration = c.quick ? 0.05 : 1.0;
  Csv series("stiffness,time,density_error_percent");
  Csv by_k("stiffness,stable,steps,avg_density_error_percent,max_density_error_percent,s_per_simulated_s,message");
  for (double k : ks) {
    Scene scene;
    try {
      scene = c.load("column.json", {"solver.type=wcsph", override_number("solver.stiffness", k), "time.dt=1e-4",
                                     override_number("time.duration", duration)});
    } catch (const SceneError& e) {  // a step beyond WCSPH's acoustic limit is refused at load
      std::printf("  k = %s: refused: %s\n", fmt(k).c_str(), e.what());
      by_k.row({fmt(k), "0", "0", "", "", "", analysis::csv_quote(std::string("refused: ") + e.what())});
      continue;
    }
    long n = 0;
    const SweepRun r = analysis::run_sweep_point(scene, {}, [&](const StepStats& st) {
      // Every 10th step from 10 ms on (the first steps start from the lattice's zero error,
      // which a log axis would stretch over ten decades).
      if (n++ % 10 == 0 && st.time >= 0.01) series.row({fmt(k), fmt(st.time), fmt(st.density_error_percent, 5)});
    });
    print_run("k = " + fmt(k), r);
    by_k.row({fmt(k), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4), fmt(r.max_density_error, 4),
              fmt(r.seconds_per_simulated_second(), 4), analysis::csv_quote(r.message)});
  }
  series.write(c.dir / "error_over_time.csv");
  by_k.write(c.dir / "stiffness.csv");

  const std::vector<double> dts = c.quick ? std::vector<double>{1e-4, 2e-4} : std::vector<double>{2.5e-5, 5e-5, 1e-4, 2e-4, 4e-4};
  const double k = 1e6;
  const double dt_duration = c.quick ? 0.05 : 0.5;
  Csv by_dt("dt,stable,steps,avg_density_error_percent,pressure_s,neighbors_s,overall_s,s_per_simulated_s,message");
  for (double dt : dts) {
    Scene scene;
    try {
      scene = c.load("column.json", {"solver.type=wcsph", override_number("solver.stiffness", k),
                                     override_number("time.dt", dt), override_number("time.duration", dt_duration)});
    } catch (const SceneError& e) {
      std::printf("  k = 1e6, dt = %s: refused: %s\n", fmt(dt).c_str(), e.what());
      by_dt.row({fmt(dt), "0", "0", "", "", "", "", "", analysis::csv_quote(std::string("refused: ") + e.what())});
      continue;
    }
    const SweepRun r = analysis::run_sweep_point(scene, {});
    print_run("k = 1e6, dt = " + fmt(dt), r);
    const double n = static_cast<double>(r.steps) / 1000.0;
    by_dt.row({fmt(dt), r.stable ? "1" : "0", std::to_string(r.steps), fmt(r.avg_density_error, 4), fmt(r.ms_phase[2] * n, 4),
               fmt(r.ms_phase[0] * n, 4), fmt(r.ms_phase[4] * n, 4), fmt(r.seconds_per_simulated_second(), 4),
               analysis::csv_quote(r.message)});
  }
  by_dt.write(c.dir / "time_step.csv");
  c.md += "WCSPH on the 5000-particle column, " + fmt(duration, 3) + " simulated seconds per stiffness run and " +
          fmt(dt_duration, 3) + " per time-step run (the thesis' Table 3 uses 100 frames). First the stiffness k at dt = 0.1 ms "
          "(thesis Figure 12: the error falls as k grows), then the time step at k = 1e6 (thesis Table 3: WCSPH's "
          "pressure is cheap, its step is small; an unstable run is reported, not hidden). Load average at the end " +
          fmt(load_average(), 3) + ".\n\n";
  c.table(c.dir / "stiffness.csv", {"stiffness", "stable", "avg_density_error_percent", "max_density_error_percent", "s_per_simulated_s"});
  c.table(c.dir / "time_step.csv", {"dt", "stable", "steps", "avg_density_error_percent", "pressure_s", "neighbors_s", "overall_s"});
  FigureSpec a = spec(FigureKind::Series, c.dir / "error_over_time.csv", "time", {"density_error_percent"}, "error_over_time.png");
  a.group = "stiffness";
  a.mean = true;
  a.logy = true;
  c.figure(a, "WCSPH average density error over time for each stiffness k at dt = 0.1 ms (thesis Figure 12)");
}

// --- Section 5.5: IISPH or WCSPH, speed against error --------------------------------------------

// Names where the combined Pareto front changes solver: below which error each one is the
// faster choice.
std::string crossover_text(std::vector<SweepRun> runs) {
  analysis::mark_pareto_front(runs);
  std::vector<const SweepRun*> front;
  for (const auto& r : runs)
    if (r.pareto) front.push_back(&r);
  std::sort(front.begin(), front.end(), [](const SweepRun* a, const SweepRun* b) {
    return a->seconds_per_simulated_second() < b->seconds_per_simulated_second();
  });
  if (front.empty()) return "No stable run: no front.";
  std::string s = "Pareto front from fastest to most accurate: ";
  for (std::size_t i = 0; i < front.size(); ++i)
    s += (i ? ", " : "") + front[i]->solver + " (" + fmt(front[i]->seconds_per_simulated_second(), 3) + " s, " +
         fmt(front[i]->avg_density_error, 3) + " %)";
  // Runs of the same solver along the front: each is the faster choice over its errors.
  std::vector<std::pair<std::size_t, std::size_t>> segments;
  for (std::size_t i = 0; i < front.size(); ++i)
    if (i == 0 || front[i]->solver != front[i - 1]->solver) segments.push_back({i, i});
    else segments.back().second = i;
  if (segments.size() == 1) return s + ". No crossover: " + front[0]->solver + " is faster at every error reached.";
  s += ". The faster solver by the error asked for: ";
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const SweepRun* a = front[segments[k].first];
    const SweepRun* b = front[segments[k].second];
    s += (k ? "; " : "") + a->solver + " " +
         (a == b ? "at " + fmt(a->avg_density_error, 3) + " %" : "from " + fmt(a->avg_density_error, 3) + " % down to " + fmt(b->avg_density_error, 3) + " %");
  }
  return s + ". Crossovers lie between neighbouring segments.";
}

void speed_error(Context& c) {
  struct Case {
    std::string label, base;
    std::vector<std::string> own;
  };
  const double duration = c.quick ? 0.05 : 0.5;
  std::vector<Case> cases = {{"dam_break_20k", "dam_break.json", {}}, {"column_1m", "column.json", {}},
                             {"column_2m", "column.json", column_height(0.5, 2.0)}};
  if (c.quick) cases = {{"dam_break", "dam_break.json", {}}};
  const std::vector<std::vector<std::string>> iisph =
      c.quick ? std::vector<std::vector<std::string>>{{"time.dt=1e-3", "solver.tolerance=0.1"}}
              : analysis::sweep_combinations({analysis::parse_sweep("time.dt=5e-4,1e-3,2e-3"),
                                              analysis::parse_sweep("solver.tolerance=0.01,0.1,1")});
  const std::vector<std::vector<std::string>> wc =
      c.quick ? std::vector<std::vector<std::string>>{{"solver.stiffness=1e6", "time.dt=1e-4"}}
              : analysis::sweep_combinations({analysis::parse_sweep("solver.stiffness=1e5,1e6,1e7"),
                                              analysis::parse_sweep("time.dt=5e-5,1e-4,2e-4")});
  c.md += "Each scene runs " + fmt(duration, 3) +
          " simulated seconds per combination: IISPH over dt x tolerance, WCSPH over stiffness x dt. Time is wall seconds "
          "per simulated second (" + std::to_string(omp_get_max_threads()) + " threads), error is the average of Eq. 15's "
          "density error over the steps. Load average at the start " + fmt(load_average(), 3) + ".\n\n";
  for (const Case& k : cases) {
    std::vector<SweepRun> runs;
    for (const auto* grid : {&iisph, &wc})
      for (const auto& combo : *grid) {
        auto own = k.own;
        own.push_back(override_number("time.duration", duration));
        own.push_back(std::string("solver.type=") + (grid == &iisph ? "iisph" : "wcsph"));
        own.insert(own.end(), combo.begin(), combo.end());
        runs.push_back(analysis::run_sweep_point(c.load(k.base, own), combo));
        runs.back().scene = k.label;
        print_run(k.label + " " + analysis::join(combo, " "), runs.back());
      }
    analysis::mark_pareto_front(runs);
    const fs::path csv = c.dir / (k.label + ".csv");
    write_file_atomic(csv.string(), analysis::sweep_csv(runs));
    c.md += "### " + k.label + " (" + std::to_string(runs.front().particles) + " particles)\n\n" +
            analysis::sweep_markdown(runs) + "\n" + crossover_text(runs) + "\n\n";
    FigureSpec a = spec(FigureKind::Scatter, csv, "s_per_simulated_s", {"avg_density_error_percent"}, k.label + ".png");
    a.group = "solver";
    a.where = {"stable=1"};
    a.pareto = true;
    a.logx = a.logy = true;
    c.figure(a, k.label + ": time per simulated second against average density error, Pareto front dashed");
  }
}

// --- Figure 11 and the 2-thread target: parallel speed-up ---------------------------------------

int available_threads() { return std::max(1, omp_get_num_procs()); }

// Wall milliseconds per step of `scene` for each thread count, `repeat` rounds with the
// thread counts interleaved (1, 2, 1, 2, ...), so that a slow spell of a shared machine
// hits every thread count alike. ms[t][r]: thread count t, round r. after_run(t, run),
// when given, runs right after each run, still with threads[t] threads (reference loops
// timed in the same spell of load, per-thread-count results).
std::vector<std::vector<double>> interleaved_ms_per_step(const Scene& scene, const std::vector<int>& threads, int repeat,
                                                         SweepRun* last = nullptr,
                                                         const std::function<void(std::size_t, const SweepRun&)>& after_run = {}) {
  std::vector<std::vector<double>> ms(threads.size());
  for (int r = 0; r < repeat; ++r)
    for (std::size_t t = 0; t < threads.size(); ++t) {
      omp_set_num_threads(threads[t]);
      const SweepRun run = analysis::run_sweep_point(scene, {});
      ms[t].push_back(run.ms_phase[4]);
      if (last) *last = run;
      if (after_run) after_run(t, run);
    }
  return ms;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double mean(const std::vector<double>& v) {
  double sum = 0.0;
  for (double x : v) sum += x;
  return v.empty() ? 0 : sum / static_cast<double>(v.size());
}

void parallel(Context& c) {
  const int restore = omp_get_max_threads();
  std::vector<int> threads = {1, 2};
  if (available_threads() > 2) threads.push_back(available_threads());
  const double start_load = load_average();
  // Thesis Figure 11: columns of growing height, sequential against parallel. Every
  // height runs in turn within each round (the thread counts interleaved), so that a slow
  // spell hits every height alike; short columns repeat their run within a round (the
  // round's figure is the mean per step over the repeats).
  const std::vector<double> heights = c.quick ? std::vector<double>{0.25} : std::vector<double>{0.25, 0.5, 1, 1.5, 2, 2.4};
  struct Column {
    double height;
    Scene scene;
    int repeat;
    std::vector<std::vector<double>> ms;  // ms[t][round]
    std::vector<SweepRun> r;              // the last run of each thread count
  };
  std::vector<Column> columns;
  for (double h : heights) {
    auto own = column_height(0.5, h);
    own.push_back("time.dt=1e-3");
    own.push_back(c.quick ? "time.duration=0.01" : "time.duration=0.1");
    // 50 particles per row at h = 0.01: the 0.25 m column (1250 particles) runs 4 times.
    const int repeat = c.quick ? 1 : std::max(1, static_cast<int>(std::lround(1.0 / h)));
    columns.push_back({h, c.load("column.json", own), repeat, std::vector<std::vector<double>>(threads.size()),
                       std::vector<SweepRun>(threads.size())});
  }
  const int column_rounds = c.quick ? 1 : 5;
  for (int k = 0; k < column_rounds; ++k)
    for (Column& col : columns) {
      std::vector<std::vector<double>> sum(threads.size());
      for (int rep = 0; rep < col.repeat; ++rep) {
        const auto ms = interleaved_ms_per_step(col.scene, threads, 1, nullptr,
                                                [&](std::size_t t, const SweepRun& run) { col.r[t] = run; });
        for (std::size_t t = 0; t < threads.size(); ++t) sum[t].push_back(ms[t][0]);
      }
      for (std::size_t t = 0; t < threads.size(); ++t) col.ms[t].push_back(mean(sum[t]));
    }
  Csv csv("particles,height,threads,avg_iterations,ms_per_step,s_per_simulated_s,speedup");
  for (const Column& col : columns)
    for (std::size_t t = 0; t < threads.size(); ++t) {
      const SweepRun& r = col.r[t];
      const double m = median(col.ms[t]);
      std::vector<double> ratio;  // per round: 1-thread time over t-thread time
      for (std::size_t k = 0; k < col.ms[t].size(); ++k) ratio.push_back(col.ms[0][k] / col.ms[t][k]);
      std::printf("  %6ld particles %d threads %8.3f ms/step %6.2f iters speed-up %.3f\n", r.particles, threads[t], m,
                  r.avg_iterations, median(ratio));
      csv.row({std::to_string(r.particles), fmt(col.height), std::to_string(threads[t]), fmt(r.avg_iterations, 4), fmt(m, 5),
               fmt(m * static_cast<double>(r.steps) / 1000.0 / std::max(r.simulated, 1e-12), 5), fmt(median(ratio), 4)});
    }
  csv.write(c.dir / "column_threads.csv");
  // The target: 2-thread efficiency on the 130k breaking dam (30 steps, 9 interleaved rounds).
  const Scene big = c.quick ? c.load("dam_break.json", {"time.duration=0.01", "time.dt=1e-3"})
                            : load_scene(c.scenes + "/dam_break_130k.json", [&] {
                                auto s = c.set;
                                s.insert(s.begin(), {"time.cfl=null", "time.dt=1e-3", "time.duration=0.03"});
                                return s;
                              }());
  // Speed-up: the median over the rounds of (1-thread time / t-thread time) within a round.
  // Each round also times the machine's reference loops (analysis/machine.h) with the same
  // thread counts, so that the solver's speed-up can be read against what the machine
  // gives a memory-bound and an arithmetic loop in the same spell of load.
  Csv eff("scene,particles,threads,ms_per_step,speedup,efficiency,speedup_min,speedup_max");
  Csv machine("loop,threads,ms,speedup,speedup_min,speedup_max,gb_per_s");
  std::string eff_text, machine_text;
  SweepRun r;
  const int rounds = c.quick ? 1 : 9;  // the ratio of one round varies by ±20 % on a shared 2-core VM
  const std::size_t stream_bytes = c.quick ? (std::size_t(8) << 20) : (std::size_t(64) << 20);
  const int stream_passes = c.quick ? 2 : 10;
  const long compute_iterations = c.quick ? 1000000L : 100000000L;
  analysis::StreamArrays arrays(stream_bytes);
  std::vector<std::vector<double>> stream(threads.size()), compute(threads.size());
  double checksum = 0.0;
  const auto ms = interleaved_ms_per_step(big, threads, rounds, &r, [&](std::size_t t, const SweepRun&) {
    stream[t].push_back(analysis::stream_triad_ms(arrays, 0.5, threads[t], stream_passes));
    compute[t].push_back(analysis::compute_ms(threads[t], compute_iterations, &checksum));
  });
  struct Speedup {
    double median, lo, hi;
  };
  auto speedup_of = [&](const std::vector<std::vector<double>>& times, std::size_t t) {
    std::vector<double> ratio;
    for (int k = 0; k < rounds; ++k) ratio.push_back(times[0][static_cast<std::size_t>(k)] / times[t][static_cast<std::size_t>(k)]);
    return Speedup{median(ratio), *std::min_element(ratio.begin(), ratio.end()), *std::max_element(ratio.begin(), ratio.end())};
  };
  for (std::size_t t = 0; t < threads.size(); ++t) {
    const Speedup sp = speedup_of(ms, t);
    const double speedup = sp.median, lo = sp.lo, hi = sp.hi;
    eff.row({big.name, std::to_string(r.particles), std::to_string(threads[t]), fmt(median(ms[t]), 5), fmt(speedup, 4),
             fmt(speedup / threads[t], 4), fmt(lo, 4), fmt(hi, 4)});
    std::printf("  %s %ld particles, %d threads: %.2f ms/step, speed-up %.3f (rounds %.3f to %.3f), efficiency %.1f %%\n",
                big.name.c_str(), r.particles, threads[t], median(ms[t]), speedup, lo, hi, 100 * speedup / threads[t]);
    if (threads[t] > 1)
      eff_text += std::to_string(threads[t]) + " threads: speed-up " + fmt(speedup, 3) + "x (rounds " + fmt(lo, 3) + " to " +
                  fmt(hi, 3) + "), efficiency " + fmt(100 * speedup / threads[t], 3) + " %. ";
    const double stream_gb = 3.0 * static_cast<double>(stream_bytes) * stream_passes / (median(stream[t]) * 1e6);
    const Speedup ss = speedup_of(stream, t), sc = speedup_of(compute, t);
    machine.row({"memory stream", std::to_string(threads[t]), fmt(median(stream[t]), 5), fmt(ss.median, 4), fmt(ss.lo, 4),
                 fmt(ss.hi, 4), fmt(stream_gb, 4)});
    machine.row({"arithmetic", std::to_string(threads[t]), fmt(median(compute[t]), 5), fmt(sc.median, 4), fmt(sc.lo, 4),
                 fmt(sc.hi, 4), ""});
    std::printf("  machine, %d threads: memory stream %.1f GB/s, speed-up %.3f; arithmetic speed-up %.3f\n", threads[t],
                stream_gb, ss.median, sc.median);
    if (threads[t] > 1)
      machine_text += "The machine in the same rounds, " + std::to_string(threads[t]) + " threads: a memory stream (a = b + s c over three " +
                      std::to_string(stream_bytes >> 20) + " MB arrays) speeds up " + fmt(ss.median, 3) + "x (rounds " + fmt(ss.lo, 3) +
                      " to " + fmt(ss.hi, 3) + "), an arithmetic loop " + fmt(sc.median, 3) + "x (rounds " + fmt(sc.lo, 3) + " to " +
                      fmt(sc.hi, 3) + "). ";
  }
  eff.write(c.dir / "efficiency.csv");
  omp_set_num_threads(restore);
  c.md += std::string(c.quick ? "Quick run: one round of each (a first look, not a measurement). "
                               : "Columns (100 steps each): medians of 5 rounds, each running every height in turn with the "
                                 "thread counts interleaved (the columns under 1 m repeat their run within a round); speed-up: "
                                 "the median of the per-round ratios. The 130k dam break (30 steps): medians of 9 interleaved "
                                 "rounds. ") +
          std::to_string(available_threads()) + " cores, load average " + fmt(start_load, 3) +
          " at the start and " + fmt(load_average(), 3) + " at the end (timings are only meaningful on an idle machine). "
          "Compare with the thesis' Figure 11. Target: at least 1.8x (90 %) on 2 threads for the 130k breaking dam. " +
          eff_text + machine_text + "\n\n";
  machine.write(c.dir / "machine.csv");
  c.table(c.dir / "efficiency.csv", {});
  c.table(c.dir / "machine.csv", {});
  c.table(c.dir / "column_threads.csv", {});
  FigureSpec a = spec(FigureKind::Series, c.dir / "column_threads.csv", "particles", {"ms_per_step"}, "time_vs_particles.png");
  a.group = "threads";
  a.style = "linespoints";
  a.ylabel = "wall time per step [ms]";
  c.figure(a, "Wall time per step against particle count for 1 and 2 threads (thesis Figure 11, left; groups are thread counts)");
  FigureSpec b = spec(FigureKind::Series, c.dir / "column_threads.csv", "particles", {"avg_iterations"}, "iterations_vs_particles.png");
  b.group = "threads";
  b.style = "linespoints";
  c.figure(b, "Average iterations against particle count (thesis Figure 11, right: identical for every thread count)");
}

// --- O(n): time per particle-step from 10k to 1M particles ----------------------------------------

void scaling(Context& c) {
  // A layer 0.5 m deep (50 rows at h = 0.01) widened to the particle count: the work per
  // particle (neighbours, pairs) stays the same. The solver's iterations still grow a
  // little with the width (the tolerance is on the average error), so each width also
  // runs with a fixed number of Jacobi iterations: then the work per particle-step is
  // exactly the same and any growth of its time is the implementation's.
  const std::vector<long> counts = c.quick ? std::vector<long>{2000, 8000} : std::vector<long>{10000, 30000, 100000, 300000, 1000000};
  constexpr int kFixedIterations = 6;
  const double start_load = load_average();
  Csv csv("particles,width,steps,avg_iterations,ms_per_step,us_per_particle_step,ratio_to_first,us_neighbors_per_particle,"
          "us_pressure_per_particle_iteration,fixed_iterations,us_per_particle_step_fixed_iterations,ratio_to_first_fixed_iterations");
  // Every width with and without fixed iterations, the runs of one round in a row and the
  // rounds repeated, so that a slow spell of a shared machine hits every width alike.
  // Small widths repeat their run within a round (the round's figure is the mean per
  // step over its repeats): 20 steps of 10k particles take tens of milliseconds.
  struct Width {
    double width;
    Scene scene, fixed;
    int repeat;
    std::vector<double> ms_natural, ms_fixed;
    SweepRun r, rf;
  };
  std::vector<Width> widths;
  for (long n : counts) {
    const double width = static_cast<double>(n) / 50.0 * 0.01;
    auto own = column_height(width, 0.5);
    own.insert(own.end(), {"time.dt=5e-4", "time.duration=0.01"});
    Scene scene = c.load("column.json", own);
    own.insert(own.end(), {"solver.min_iterations=" + std::to_string(kFixedIterations),
                           "solver.max_iterations=" + std::to_string(kFixedIterations)});
    Scene fixed = c.load("column.json", own);
    const int repeat = c.quick ? 1 : static_cast<int>(std::max(1L, 300000L / n));
    widths.push_back({width, std::move(scene), std::move(fixed), repeat, {}, {}, {}, {}});
  }
  const int rounds = c.quick ? 1 : 5;
  const int threads = omp_get_max_threads();
  for (int k = 0; k < rounds; ++k)
    for (Width& w : widths) {
      w.ms_natural.push_back(mean(interleaved_ms_per_step(w.scene, {threads}, w.repeat, &w.r)[0]));
      w.ms_fixed.push_back(mean(interleaved_ms_per_step(w.fixed, {threads}, w.repeat, &w.rf)[0]));
    }
  double first = 0, first_fixed = 0, lo = HUGE_VAL, hi = 0, lo_fixed = HUGE_VAL, hi_fixed = 0;
  for (const Width& w : widths) {
    const SweepRun &r = w.r, &rf = w.rf;
    const double np = static_cast<double>(r.particles);
    const double us = 1000.0 * median(w.ms_natural) / np, us_fixed = 1000.0 * median(w.ms_fixed) / np;
    if (first == 0) first = us, first_fixed = us_fixed;
    lo = std::min(lo, us), hi = std::max(hi, us);
    lo_fixed = std::min(lo_fixed, us_fixed), hi_fixed = std::max(hi_fixed, us_fixed);
    std::printf("  %8ld particles: %.4f us per particle-step (%.2f iterations), %.4f with %d fixed iterations\n", r.particles,
                us, r.avg_iterations, us_fixed, kFixedIterations);
    // The split of the last fixed-iteration run: the neighbour phase per particle, and the
    // pressure solve per particle and iteration.
    csv.row({std::to_string(r.particles), fmt(w.width, 5), std::to_string(r.steps), fmt(r.avg_iterations, 4),
             fmt(median(w.ms_natural), 5), fmt(us, 5), fmt(us / first, 4), fmt(1000.0 * rf.ms_phase[0] / np, 4),
             fmt(1000.0 * rf.ms_phase[2] / (np * kFixedIterations), 4), fmt(rf.avg_iterations, 4), fmt(us_fixed, 5),
             fmt(us_fixed / first_fixed, 4)});
  }
  csv.write(c.dir / "scaling.csv");
  c.md += "A layer 0.5 m deep widened from " + std::to_string(counts.front()) + " to " + std::to_string(counts.back()) +
          " particles, 20 steps of 0.5 ms, at the solver's tolerance and with " + std::to_string(kFixedIterations) +
          " fixed Jacobi iterations (the same work per particle at every width); " +
          (c.quick ? "1 round" : "median of 5 rounds, each round running every width and variant in turn (widths under 300k "
                                 "repeat their run 300k / n times within a round)") + ", " + std::to_string(omp_get_max_threads()) +
          " threads, load average " + fmt(start_load, 3) +
          " at the start. Target: the time per particle-step within 25 % over the range (O(n)). Measured: largest / "
          "smallest = " + fmt(hi / lo, 3) + " at the tolerance (iterations grow with the width), " +
          fmt(hi_fixed / lo_fixed, 3) + " with fixed iterations.\n\n";
  c.table(c.dir / "scaling.csv", {});
  FigureSpec a = spec(FigureKind::Series, c.dir / "scaling.csv", "particles",
                      {"us_per_particle_step", "us_per_particle_step_fixed_iterations", "us_neighbors_per_particle",
                       "us_pressure_per_particle_iteration"},
                      "scaling.png");
  a.ylabel = "wall time [µs]";
  a.style = "linespoints";
  a.logx = true;
  c.figure(a, "Wall time per particle-step against particle count (flat = O(n)), at the tolerance and with fixed iterations");
}

// --- Figure 14: naive against hashed neighbour search ----------------------------------------------

void neighbour_search(Context& c) {
  const std::vector<long> counts = c.quick ? std::vector<long>{200, 400} : std::vector<long>{500, 1000, 2000, 4000, 8000, 12000};
  const double start_load = load_average();
  Csv csv("particles,method,ms_neighbors");
  for (long n : counts) {
    // 50 particles per row at h = 0.01 in a 0.5 m wide column.
    auto own = column_height(0.5, static_cast<double>(n) / 50.0 * 0.01);
    own.insert(own.end(), {"time.dt=5e-4", "time.duration=0.0025"});
    const Scene scene = c.load("column.json", own);
    for (bool brute : {true, false}) {
      const SweepRun r = analysis::run_sweep_point(scene, {}, {}, brute);
      std::printf("  %6ld particles %-8s %9.3f ms per neighbour search\n", r.particles, brute ? "naive" : "hashing", r.ms_phase[0]);
      csv.row({std::to_string(r.particles), brute ? "naive" : "hashing", fmt(r.ms_phase[0], 5)});
    }
  }
  csv.write(c.dir / "neighbour_search.csv");
  c.md += "Columns of growing height, 5 steps each, the neighbour phase's mean wall time per step (fluid-fluid, "
          "fluid-boundary and boundary-fluid lists). Load average " + fmt(start_load, 3) +
          " at the start. Compare with the thesis' Figure 14: the naive search grows quadratically, hashing linearly.\n\n";
  c.table(c.dir / "neighbour_search.csv", {});
  FigureSpec a = spec(FigureKind::Series, c.dir / "neighbour_search.csv", "particles", {"ms_neighbors"}, "neighbour_search.png");
  a.group = "method";
  a.style = "linespoints";
  c.figure(a, "Neighbour search time per step against particle count, naive O(n^2) against spatial hashing (thesis Figure 14)");
}

// --- Figures 2 and 8: snapshot montages ----------------------------------------------------------

void montage_figure(Context& c, MontageOptions m, const std::string& file, const std::string& caption) {
  m.output = (c.dir / file).string();
  m.set.insert(m.set.end(), c.set.begin(), c.set.end());
  const int status = run_montage(m);
  if (status != 0) throw OutputError(m.output + ": montage failed with status " + std::to_string(status));
  c.md += "![" + caption + "](" + file + ")\n\n*" + caption + "*\n\n";
}

void snapshots(Context& c) {
  MontageOptions m;
  m.scene = c.scene_path("dam_break.json");
  m.times = c.quick ? "0,0.25" : "0,0.5,1,1.5,2,2.5,3,3.5";
  m.cols = c.quick ? 2 : 4;
  m.cell = c.quick ? "160x160" : "320x320";
  if (c.quick) m.set = {"spacing=0.04"};
  m.title = "Dam break, coloured by CFL number";
  c.md += "The breaking dam (`" + m.scene + "`) at " + m.times + " s, coloured by CFL number. Compare with the thesis' "
          "Figure 2 (130k particles: `--scene scenes/dam_break_130k.json`).\n\n";
  montage_figure(c, m, "dam_break_snapshots.png", "Breaking dam snapshots with their times (thesis Figure 2)");
}

void boundary_pressure(Context& c) {
  MontageOptions m;
  m.scene = c.scene.empty() ? c.scenes + "/hydrostatic.json" : c.scene;
  m.times = c.quick ? "0.1" : "3";
  m.vary = "solver.boundary_pressure=extrapolation,mirroring,zero";
  m.cols = 3;  // side by side, as in the thesis
  m.color_by = "pressure";
  m.cell = c.quick ? "120x132" : "240x264";
  if (c.quick) m.set = {"time.duration=0.1"};
  m.title = "Pressure by boundary method";
  c.md += "The hydrostatic tank (`" + m.scene + "`) at t = " + m.times +
          " s, coloured by pressure on one shared scale, once per boundary method. Compare with the thesis' Figure 8: "
          "extrapolation continues the pressure into the wall, zero pressure loads the first fluid rows instead.\n\n";
  montage_figure(c, m, "pressure_by_method.png", "Pressure field for pressure extrapolation, mirroring and zero pressure (thesis Figure 8)");
}

struct Experiment {
  const char* name;
  const char* thesis;
  const char* what;
  std::function<void(Context&)> run;
};

const std::vector<Experiment>& experiments() {
  static const std::vector<Experiment> list = {
      {"snapshots", "Figure 2", "breaking dam snapshots at eight times (montage)", snapshots},
      {"dam-break-iterations", "Figure 3", "solver iterations and compression error over time, breaking dam", dam_break_iterations},
      {"iisph-dt", "Figure 6a, Table 2", "IISPH iterations and pressure/neighbour/overall time against dt, column", iisph_dt},
      {"column-height", "Figure 6b", "IISPH iterations against column height at fixed dt", column_height_experiment},
      {"fixed-iterations", "Figure 7", "compression error against a fixed number of Jacobi iterations", fixed_iterations},
      {"boundary-pressure", "Figure 8", "pressure field of the three boundary methods side by side (montage)", boundary_pressure},
      {"boundary-gamma", "Figure 9", "gamma1-3 search for each boundary method, best values", boundary_gamma},
      {"boundary-iterations", "Figure 10", "iteration distributions per boundary method", boundary_iterations},
      {"wcsph", "Table 3, Figure 12", "WCSPH error against stiffness, time against dt", wcsph},
      {"speed-error", "Section 5.5", "IISPH against WCSPH: time against error, Pareto front and crossover", speed_error},
      {"parallel", "Figure 11", "1 against 2 threads: column sizes and the 130k breaking dam's efficiency", parallel},
      {"scaling", "(O(n) target)", "time per particle-step from 10k to 1M particles", scaling},
      {"neighbour-search", "Figure 14", "naive against spatial-hashing neighbour search", neighbour_search},
  };
  return list;
}

}  // namespace

std::vector<std::string> experiment_names() {
  std::vector<std::string> names;
  for (const auto& e : experiments()) names.push_back(e.name);
  return names;
}

int run_experiment(const ExperimentOptions& o) {
  if (o.names.empty() || (o.names.size() == 1 && o.names[0] == "list")) {
    std::printf("%-22s %-20s %s\n", "experiment", "thesis", "what");
    for (const auto& e : experiments()) std::printf("%-22s %-20s %s\n", e.name, e.thesis, e.what);
    return 0;
  }
  std::vector<const Experiment*> chosen;
  for (const auto& n : o.names) {
    if (n == "all") {
      for (const auto& e : experiments()) chosen.push_back(&e);
      continue;
    }
    const auto it = std::find_if(experiments().begin(), experiments().end(), [&](const Experiment& e) { return n == e.name; });
    if (it == experiments().end())
      throw view::FlagError("name", n, "one of: " + analysis::join(experiment_names(), ", ") + ", all, list");
    chosen.push_back(&*it);
  }
  if (!o.scene.empty() && chosen.size() > 1)
    throw view::FlagError("--scene", o.scene, "one experiment at a time (each has its own base scene)");
  set_threads(o.threads);
  const fs::path root(o.output_dir);
  std::string index = "# sluice: the experiments of the thesis' chapter 5\n\nWritten by `sluice experiment` "
                      "(scripts/experiments.sh runs them all). Each section's figures and CSV files are in its folder.\n\n";
  for (const Experiment* e : chosen) {
    Context c;
    c.root = root;
    c.dir = root / e->name;
    c.quick = o.quick;
    c.scenes = o.scenes;
    c.scene = o.scene;
    c.set = o.set;
    make_directory(c.dir);
    std::printf("%s (%s): %s\n", e->name, e->thesis, e->what);
    c.md = "## " + std::string(e->name) + " (thesis " + e->thesis + ")\n\n" + e->what + ". Command: `sluice experiment " +
           e->name + (o.quick ? " --quick" : "") + "`.\n\n";
    e->run(c);
    write_file_atomic((c.dir / "summary.md").string(), c.md);
    std::printf("  wrote %s\n", (c.dir / "summary.md").string().c_str());
  }
  // The index holds every experiment whose summary is in DIR, in the list's order, so that
  // rerunning one experiment keeps the others' sections.
  for (const auto& e : experiments()) {
    const fs::path summary = root / e.name / "summary.md";
    if (!fs::exists(summary)) continue;
    std::ifstream in(summary);
    std::string linked((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The index links the figures from the root folder.
    for (std::size_t p = 0; (p = linked.find("](", p)) != std::string::npos; p += 2) linked.insert(p + 2, std::string(e.name) + "/");
    index += linked;
  }
  write_file_atomic((root / "README.md").string(), index);
  std::printf("wrote %s\n", (root / "README.md").string().c_str());
  return 0;
}

}  // namespace sluice::app
