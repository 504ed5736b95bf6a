// `sluice bench`: time scenes side by side; print a table and write CSV.
// Each scene runs `repeat` times from its initial state for `steps` steps; the run with
// the median wall time is reported, with its per-phase split per particle-step.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "analysis/plot.h"
#include "analysis/sweep.h"
#include "app/commands.h"
#include "app/output_dir.h"
#include "app/run.h"
#include "io/output.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::app {

namespace {

struct BenchRow {
  std::string scene;
  std::string solver;
  int threads = 0;
  long particles = 0;
  RunTotals totals;
  double us_per_particle_step(int phase) const {
    const double ps = static_cast<double>(totals.steps) * static_cast<double>(particles);
    return ps > 0 ? 1000.0 * totals.sum_ms[phase] / ps : 0.0;
  }
};

BenchRow run_once(const Scene& scene, long steps, bool brute_force) {
  Simulation sim(scene);
  sim.set_brute_force_neighbors(brute_force);
  BenchRow row;
  row.scene = scene.name;
  row.solver = to_string(scene.solver.type);
  row.threads = omp_get_max_threads();
  row.particles = static_cast<long>(scene.fluid_x.size());
  const auto t0 = std::chrono::steady_clock::now();
  while (!sim.finished() && (steps == 0 || row.totals.steps < steps)) row.totals.add(sim.step());
  row.totals.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return row;
}

// --- sweep mode -----------------------------------------------------------------------------

namespace fs = std::filesystem;

std::string shell_quote(const std::string& s) {
  if (!s.empty() && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-./=:+,") ==
                        std::string::npos)
    return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string self_executable() {
  std::error_code ec;
  const fs::path p = fs::read_symlink("/proc/self/exe", ec);
  return ec ? std::string("sluice") : p.string();
}

// What a sweep or --collect writes into its directory.
const std::vector<std::string> kSweepFiles = {"bench.csv", "bench.md", "bench.png", "bench.gp"};

void print_sweep_header() {
  std::printf("%4s %-44s %-6s %5s %10s %7s %10s %7s %10s %10s  %s\n", "run", "overrides", "solver", "stable", "s/sim_s",
              "steps", "avg_dt_s", "iters", "avg_err_%", "max_err_%", "pareto");
}

void print_sweep_row(std::size_t i, const analysis::SweepRun& r) {
  std::string set;
  for (const auto& s : r.set) set += (set.empty() ? "" : " ") + s;
  std::printf("%4zu %-44s %-6s %5s %10.3f %7ld %10.4g %7.2f %10.4f %10.4f  %s\n", i + 1, set.c_str(), r.solver.c_str(),
              r.stable ? "yes" : "NO", r.seconds_per_simulated_second(), r.steps, r.avg_dt, r.avg_iterations,
              r.avg_density_error, r.max_density_error, r.pareto ? "*" : "");
  std::fflush(stdout);
}

void write_sweep_outputs(std::vector<analysis::SweepRun>& runs, const fs::path& dir, const std::string& title) {
  analysis::mark_pareto_front(runs);
  write_file_atomic((dir / "bench.csv").string(), analysis::sweep_csv(runs));
  write_file_atomic((dir / "bench.md").string(), analysis::sweep_markdown(runs));
  const std::string why =
      analysis::run_gnuplot((dir / "bench.gp").string(),
                            analysis::gnuplot_png_preamble("bench.png") + analysis::sweep_plot_script(runs, title));
  if (!why.empty())
    std::fprintf(stderr, "sluice: warning: no plot: %s (bench.csv and bench.md are written)\n", why.c_str());
  std::printf("wrote %s, bench.md%s\n", (dir / "bench.csv").string().c_str(), why.empty() ? ", bench.png" : "");
}

// The path an override sets, as a JSON pointer: "time.dt=1e-3" and "/time/dt=1e-3" give
// "/time/dt".
std::string override_pointer(const std::string& text) {
  std::string path = text.substr(0, text.find('='));
  if (!path.starts_with("/")) {
    std::replace(path.begin(), path.end(), '.', '/');
    path.insert(0, "/");
  }
  return path;
}

// Loads one run of a sweep. A scene's fixed time.dt is chosen for its own solver: where
// the sweep varies solver.type, a WCSPH run whose step (from the scene, not from --set or
// the sweep) exceeds the acoustic limit 0.4 h / c (Monaghan 1992) takes the adaptive step
// instead, which keeps that limit. "time.dt=null" joins its overrides, so that the table,
// bench.csv and the --jobs lines show and repeat it; `note` says why.
Scene load_sweep_run(const std::string& file, const std::vector<std::string>& common, std::vector<std::string>& combo,
                     bool solver_varies, std::string& note) {
  std::vector<std::string> set = common;
  set.insert(set.end(), combo.begin(), combo.end());
  const bool step_set = std::any_of(set.begin(), set.end(), [](const std::string& s) {
    const std::string p = override_pointer(s);
    return p == "/time" || p == "/time/dt" || p == "/time/cfl";
  });
  if (!solver_varies || step_set) return load_scene(file, set);
  std::vector<std::string> adaptive_set = set;
  adaptive_set.push_back("time.dt=null");
  Scene adaptive = load_scene(file, adaptive_set);
  if (adaptive.solver.type != SolverType::WCSPH) return load_scene(file, set);
  // The scene's own step: the same overrides as IISPH, which has no acoustic limit.
  std::vector<std::string> iisph_set = set;
  iisph_set.push_back("solver.type=iisph");
  const double dt = load_scene(file, iisph_set).time.dt, limit = wcsph_acoustic_limit(adaptive);
  if (!(dt > 0 && dt > limit)) return load_scene(file, set);
  char text[512];
  std::snprintf(text, sizeof text,
                "the scene's time.dt %g s exceeds WCSPH's acoustic limit 0.4 h / c = %.3g s (stiffness %.4g Pa*m), so "
                "this run takes the adaptive step (time.dt=null); --set time.dt=... gives every run one fixed step",
                dt, limit, adaptive.solver.stiffness);
  note = text;
  combo.push_back("time.dt=null");
  return adaptive;
}

int run_sweep(const BenchOptions& o) {
  if (o.scenes.size() != 1)
    throw view::FlagError("scenes", std::to_string(o.scenes.size()) + " given", "exactly one scene in sweep mode");
  std::vector<analysis::SweepAxis> axes;
  for (const auto& s : o.sweep) {
    try {
      axes.push_back(analysis::parse_sweep(s));
    } catch (const SceneError& e) {
      // A malformed --sweep is the flag's mistake, not the scene's (exit 1, as --export xyz).
      throw view::FlagError("--sweep", s, e.what());
    }
  }
  auto combos = analysis::sweep_combinations(axes);
  const bool solver_varies = std::any_of(axes.begin(), axes.end(), [](const analysis::SweepAxis& a) {
    return override_pointer(a.key) == "/solver/type" || override_pointer(a.key) == "/solver";
  });
  std::vector<std::string> common = o.set;
  if (o.duration > 0) common.push_back("time.duration=" + std::to_string(o.duration));
  // Every combination must load before anything runs: a typo in the last value should
  // not cost the sweep's first hours.
  std::vector<Scene> scenes;
  std::vector<std::string> notes;
  for (std::size_t i = 0; i < combos.size(); ++i) {
    std::string note;
    scenes.push_back(load_sweep_run(o.scenes[0], common, combos[i], solver_varies, note));
    if (!note.empty()) notes.push_back("run " + std::to_string(i + 1) + ": " + note);
  }
  for (const auto& n : notes) std::printf("%s\n", n.c_str());
  const fs::path dir = o.output_dir.empty() ? fs::path("renders/bench") / scenes[0].name : fs::path(o.output_dir);
  if (!o.jobs.empty()) {
    std::string text;
    for (std::size_t i = 0; i < combos.size(); ++i) {
      std::string line = shell_quote(self_executable()) + " bench " + shell_quote(o.scenes[0]);
      for (const auto& s : common) line += " --set " + shell_quote(s);
      // Each swept value as a sweep of one value, not a --set: the run's bench.csv then
      // names its settings in the `set` column, and --collect can tell the runs apart.
      for (const auto& s : combos[i]) line += " --sweep " + shell_quote(s);
      if (o.threads > 0) line += " --threads " + std::to_string(o.threads);
      if (o.overwrite) line += " --overwrite";
      char run[32];
      std::snprintf(run, sizeof run, "run_%04zu", i + 1);
      line += " -o " + shell_quote((dir / run).string());
      text += line + "\n";
    }
    const fs::path jobs(o.jobs);
    if (jobs.has_parent_path()) make_directory(jobs.parent_path());
    write_file_atomic(o.jobs, text);
    std::printf(
        "wrote %zu command lines to %s; run them (e.g. parallel -j1 < %s), then: sluice bench --collect %s/run_* -o "
        "%s\n",
        combos.size(), o.jobs.c_str(), o.jobs.c_str(), dir.string().c_str(), dir.string().c_str());
    return 0;
  }
  make_directory(dir);
  // Checked before the first run: a sweep may take hours before its first bench.csv.
  refuse_previous_files(dir, kSweepFiles, o.overwrite);
  std::printf("sweep of %s: %zu runs, %d threads\n", o.scenes[0].c_str(), combos.size(), omp_get_max_threads());
  print_sweep_header();
  std::vector<analysis::SweepRun> runs;
  for (std::size_t i = 0; i < combos.size(); ++i) {
    runs.push_back(analysis::run_sweep_point(scenes[i], combos[i]));
    print_sweep_row(i, runs.back());
    // Kept current after every run: an interrupted sweep keeps what it measured.
    write_file_atomic((dir / "bench.csv").string(), analysis::sweep_csv(runs));
  }
  std::printf("Pareto front (no other run both faster and more accurate):\n");
  analysis::mark_pareto_front(runs);
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].pareto) print_sweep_row(i, runs[i]);
  write_sweep_outputs(runs, dir, scenes[0].name + ": time against error");
  return 0;
}

int run_collect(const BenchOptions& o) {
  if (o.output_dir.empty()) throw view::FlagError("-o", "(missing)", "--collect needs -o DIR for the merged results");
  std::vector<analysis::SweepRun> runs;
  for (const auto& d : o.collect) {
    const auto part = analysis::read_sweep_csv((fs::path(d) / "bench.csv").string());
    runs.insert(runs.end(), part.begin(), part.end());
  }
  const fs::path dir(o.output_dir);
  make_directory(dir);
  refuse_previous_files(dir, kSweepFiles, o.overwrite);
  analysis::mark_pareto_front(runs);
  print_sweep_header();
  for (std::size_t i = 0; i < runs.size(); ++i) print_sweep_row(i, runs[i]);
  write_sweep_outputs(runs, dir, (runs.empty() ? std::string("bench") : runs[0].scene) + ": time against error");
  return 0;
}

}  // namespace

// `sluice bench --end-to-end`: the render of a scene, from the command to the video, with
// render's own split (DIR/timing.json). PNG encoding runs on its own thread beside the
// simulation, so its time is not a share of the total; the run only waits png_wait_s.
int run_end_to_end(const BenchOptions& o) {
  if (o.scenes.size() > 1) throw view::FlagError("scenes", o.scenes[1], "--end-to-end takes one scene");
  // render would suggest --no-video or --format gif, which bench does not take.
  int width = 0, height = 0;
  view::parse_resolution(o.resolution, width, height);
  if (width % 2 != 0 || height % 2 != 0)
    throw view::FlagError("--resolution", o.resolution,
                          "bench --end-to-end encodes H.264 (yuv420p), which needs even width and height, e.g. " +
                              std::to_string(width + width % 2) + "x" + std::to_string(height + height % 2));
  RenderOptions r;
  r.scene = o.scenes.empty() ? "scenes/dam_break_130k.json" : o.scenes[0];
  r.output_dir = o.output_dir.empty() ? "renders/bench/end_to_end" : o.output_dir;
  r.duration = o.duration > 0 ? o.duration : 5.0;
  r.fps = o.fps;
  r.image.resolution = o.resolution;
  r.threads = o.threads;
  r.set = o.set;
  r.quiet = true;
  // As for render: an earlier run's frames and exports in -o DIR go only with --overwrite.
  r.overwrite = o.overwrite;
  refuse_previous_files(r.output_dir, {"end_to_end.csv"}, o.overwrite);
  const auto t0 = std::chrono::steady_clock::now();
  run_render(r);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const std::filesystem::path dir(r.output_dir);
  std::ifstream in(dir / "timing.json");
  const nlohmann::json t = nlohmann::json::parse(in);
  const nlohmann::json summary = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  const nlohmann::json& totals = summary.at("totals");
  const double steps = totals.value("steps", 0.0);
  std::printf("%-22s %6s %6s %8s %7s %9s %9s %9s %9s %9s %9s\n", "scene", "frames", "steps", "iters", "wall_s",
              "simul_s", "draw_s", "png_s", "png_wait", "video_s", "other_s");
  const double other = wall - t.at("simulation_s").get<double>() - t.at("drawing_s").get<double>() -
                       t.at("png_wait_s").get<double>() - t.at("exports_s").get<double>() -
                       t.at("video_s").get<double>();
  const std::string name = summary.at("scene").value("name", "");
  std::printf("%-22s %6ld %6.0f %8.2f %7.1f %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f\n", name.c_str(),
              t.at("frames").get<long>(), steps, totals.value("average_iterations", 0.0), wall,
              t.at("simulation_s").get<double>(), t.at("drawing_s").get<double>(), t.at("png_s").get<double>(),
              t.at("png_wait_s").get<double>(), t.at("video_s").get<double>(), other);
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%g,%g,%ld,%.0f,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%.6g,%d\n", name.c_str(),
                o.resolution.c_str(), r.fps, r.duration, t.at("frames").get<long>(), steps, wall,
                t.at("simulation_s").get<double>(), t.at("drawing_s").get<double>(), t.at("png_s").get<double>(),
                t.at("png_wait_s").get<double>(), t.at("exports_s").get<double>(), t.at("video_s").get<double>(), other,
                omp_get_max_threads());
  const std::string csv = (dir / "end_to_end.csv").string();
  write_file_atomic(csv, std::string("scene,resolution,fps,duration_s,frames,steps,wall_s,simulation_s,drawing_s,png_s,"
                                     "png_wait_s,exports_s,video_s,other_s,threads\n") +
                             line);
  std::printf("wrote %s\n", csv.c_str());
  return 0;
}

int run_bench(const BenchOptions& o) {
  set_threads(o.threads);
  if (o.end_to_end) return run_end_to_end(o);
  if (!o.collect.empty()) return run_collect(o);
  if (!o.sweep.empty() || !o.output_dir.empty() || !o.jobs.empty() || o.duration > 0) return run_sweep(o);
  if (o.scenes.empty()) throw view::FlagError("scenes", "(none)", "one or more scene files");
  std::vector<BenchRow> rows;
  std::printf("%-18s %-6s %3s %8s %6s %7s %9s %9s %9s | %8s %8s %8s %8s %8s\n", "scene", "solver", "thr", "particles",
              "steps", "iters", "err_%", "dens_err%", "us/p-step", "neighb", "nonpres", "pressure", "integr", "moving");
  for (const std::string& file : o.scenes) {
    const Scene scene = load_scene(file, o.set);
    std::vector<BenchRow> runs;
    for (int r = 0; r < o.repeat; ++r) runs.push_back(run_once(scene, o.steps, o.brute_force));
    std::sort(runs.begin(), runs.end(),
              [](const BenchRow& a, const BenchRow& b) { return a.totals.sum_ms[4] < b.totals.sum_ms[4]; });
    const BenchRow& m = runs[runs.size() / 2];
    const double ns = std::max(1.0, static_cast<double>(m.totals.steps));
    std::printf("%-18s %-6s %3d %8ld %6ld %7.2f %9.4f %9.4f %9.4f | %8.4f %8.4f %8.4f %8.4f %8.4f\n", m.scene.c_str(),
                m.solver.c_str(), m.threads, m.particles, m.totals.steps, m.totals.sum_iterations / ns,
                m.totals.sum_avg_error / ns, m.totals.sum_density_error / ns, m.us_per_particle_step(4),
                m.us_per_particle_step(0), m.us_per_particle_step(1), m.us_per_particle_step(2),
                m.us_per_particle_step(3), m.us_per_particle_step(5));
    std::fflush(stdout);
    rows.push_back(m);
  }
  const std::filesystem::path csv(o.csv);
  if (csv.has_parent_path()) std::filesystem::create_directories(csv.parent_path());
  std::string text =
      "scene,solver,threads,particles,steps,avg_iterations,avg_error_percent,density_error_percent,"
      "us_per_particle_step,us_neighbors,us_nonpressure,us_pressure,us_integrate,us_moving_boundaries,ms_per_step,"
      "repeats\n";
  for (const BenchRow& m : rows) {
    const double ns = std::max(1.0, static_cast<double>(m.totals.steps));
    char line[512];
    std::snprintf(line, sizeof line, "%s,%s,%d,%ld,%ld,%.4f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%.4f,%d\n",
                  m.scene.c_str(), m.solver.c_str(), m.threads, m.particles, m.totals.steps,
                  m.totals.sum_iterations / ns, m.totals.sum_avg_error / ns, m.totals.sum_density_error / ns,
                  m.us_per_particle_step(4), m.us_per_particle_step(0), m.us_per_particle_step(1),
                  m.us_per_particle_step(2), m.us_per_particle_step(3), m.us_per_particle_step(5),
                  m.totals.sum_ms[4] / ns, o.repeat);
    text += line;
  }
  write_file_atomic(o.csv, text);
  std::printf("wrote %s\n", o.csv.c_str());
  return 0;
}

}  // namespace sluice::app
