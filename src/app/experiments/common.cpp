#include "app/experiments/common.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <fstream>

#include "io/output.h"

namespace sluice::app::experiments {

std::string fmt(double v, int digits) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

double load_average() {
  std::ifstream in("/proc/loadavg");
  double l = -1;
  in >> l;
  return l;
}

void Context::figure(FigureSpec spec, const std::string& caption) {
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

void Context::table(const fs::path& csv, const std::vector<std::string>& columns) {
  md += analysis::markdown_table(io::read_csv_table(csv.string()), columns) + "\n";
}

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
  std::printf("  %-42s %-5s %8ld steps %8.2f iters %9.4f %% err %9.3f s/sim-s%s\n", what.c_str(), r.solver.c_str(),
              r.steps, r.avg_iterations, r.avg_density_error, r.seconds_per_simulated_second(),
              r.stable ? "" : "  UNSTABLE");
  std::fflush(stdout);
}

// The column scene of a given fluid height [m] (the tank 0.2 m higher).
std::vector<std::string> column_height(double width, double height) {
  return {"fluid.0.max=[" + fmt(width, 17) + "," + fmt(height, 17) + "]",
          "boundaries.0.max=[" + fmt(width, 17) + "," + fmt(height + 0.2, 17) + "]"};
}

const char* const kMethods[3] = {"extrapolation", "mirroring", "zero"};

// The scene of the boundary experiments: the breaking dam at h = 0.02 (5000 particles)
// with dt = 2 ms (a CFL number up to about 0.6): at the scene's 0.5 ms the solver stops
// at its minimum of 3 iterations on almost every step, and no method or gamma can show
// a difference.
std::vector<std::string> boundary_scene(const Context& c, double duration) {
  return {c.quick ? "spacing=0.05" : "spacing=0.02", "time.dt=2e-3",
          number_override("time.duration", c.quick ? 0.2 : duration)};
}

// Wall milliseconds per step of `scene` for each thread count, `repeat` rounds with the
// thread counts interleaved (1, 2, 1, 2, ...), so that a slow spell of a shared machine
// hits every thread count alike. ms[t][r]: thread count t, round r. after_run(t, run),
// when given, runs right after each run, still with threads[t] threads (reference loops
// timed in the same spell of load, per-thread-count results).
std::vector<std::vector<double>> interleaved_ms_per_step(
    const Scene& scene, const std::vector<int>& threads, int repeat, SweepRun* last,
    const std::function<void(std::size_t, const SweepRun&)>& after_run) {
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

void montage_figure(Context& c, MontageOptions m, const std::string& file, const std::string& caption) {
  m.output = (c.dir / file).string();
  m.set.insert(m.set.end(), c.set.begin(), c.set.end());
  const int status = run_montage(m);
  if (status != 0) throw OutputError(m.output + ": montage failed with status " + std::to_string(status));
  c.md += "![" + caption + "](" + file + ")\n\n*" + caption + "*\n\n";
}

}  // namespace sluice::app::experiments
