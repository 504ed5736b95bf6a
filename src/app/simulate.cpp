// `sluice simulate`: run a scene, writing stats.csv, summary.json and particle exports.
#include <omp.h>
#include <sys/resource.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>

#include "app/commands.h"
#include "app/eta.h"
#include "app/interrupt.h"
#include "app/output_dir.h"
#include "app/resume.h"
#include "app/run.h"
#include "app/thread_governor.h"
#include "app/wait_policy.h"
#include "io/export.h"
#include "io/output.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::app {

namespace fs = std::filesystem;

void set_threads(int threads) {
  if (threads > 0) omp_set_num_threads(threads);
}

std::string number_override(const std::string& path, double value) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", value);
  return path + "=" + buf;
}

namespace {

// The command that continues an interrupted run, for summary.json.
std::string resume_command(const std::string& command, const fs::path& dir) {
  return "sluice " + command + " --resume " + dir.string();
}

// "0:01:23", or "--:--" while there is no estimate yet.
std::string clock_string(std::optional<double> left) {
  if (!left) return "--:--";
  const double seconds = *left;
  char buf[32];
  const long s = static_cast<long>(seconds + 0.5);
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

// A figure in MiB for messages.
std::string mib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / (1024.0 * 1024.0));
  return buf;
}

// Bytes a simulation holds per particle: its arrays and its neighbour lists (IISPH on
// dam_break takes about 0.5 kB per fluid particle). Four times that, on purpose: the
// estimate is there to refuse what cannot fit, not to predict.
constexpr double kBytesPerFluidParticle = 2048;
constexpr double kBytesPerBoundarySample = 1024;

// The memory the process may use: physical memory, or less under a resource limit.
double memory_limit(std::string& what) {
  const double pages = static_cast<double>(sysconf(_SC_PHYS_PAGES)), page = static_cast<double>(sysconf(_SC_PAGESIZE));
  double limit = pages > 0 && page > 0 ? pages * page : HUGE_VAL;
  what = "physical memory";
  for (const auto& [resource, name] :
       {std::pair{RLIMIT_AS, "RLIMIT_AS (ulimit -v)"}, std::pair{RLIMIT_DATA, "RLIMIT_DATA (ulimit -d)"}}) {
    rlimit rl{};
    if (getrlimit(resource, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY && static_cast<double>(rl.rlim_cur) < limit) {
      limit = static_cast<double>(rl.rlim_cur);
      what = name;
    }
  }
  return limit;
}

}  // namespace

std::string allocating_message(const Scene& scene) {
  return "while allocating the simulation of " + std::to_string(scene.fluid_x.size()) + " fluid particles and " +
         std::to_string(scene.boundary_x.size()) + " boundary samples of " + scene.file +
         "; increase /spacing or give the process more memory";
}

void check_memory(const Scene& scene) {
  const double need = kBytesPerFluidParticle * static_cast<double>(scene.fluid_x.size()) +
                      kBytesPerBoundarySample * static_cast<double>(scene.boundary_x.size());
  std::string what;
  const double limit = memory_limit(what);
  if (need > limit)
    throw SceneError(scene.file + ": /spacing: " + std::to_string(scene.fluid_x.size()) + " fluid particles and " +
                     std::to_string(scene.boundary_x.size()) + " boundary samples need about " + mib(need) +
                     " of memory; the limit is " + mib(limit) + " (" + what + "); increase /spacing");
}

std::string export_override(const std::vector<std::string>& formats) {
  // A flag mistake, reported as one (exit 1, as --export xyz): as a scene override it would
  // read as the scene file's duplicate output.export entry (exit 2).
  std::string given;
  for (const std::string& f : formats) given += (given.empty() ? "" : ",") + f;
  for (std::size_t i = 0; i < formats.size(); ++i)
    for (std::size_t k = 0; k < i; ++k)
      if (formats[i] == formats[k])
        throw view::FlagError("--export", given,
                              "\"" + formats[i] + "\" is given twice; each of csv, vtk at most once");
  return "output.export=" + nlohmann::json(formats).dump();
}

ParticleExporter make_exporter(const Scene& scene, const fs::path& dir, const RunControl& control, Index first,
                               Index last) {
  ParticleExporter exporter(dir / "particles", scene.output.export_formats);
  if (!control.resume) return exporter;
  // The frames before the checkpoint's were written by the earlier run, at the times
  // Simulation::step lands on: frame / fps, the last one at the duration.
  const Index resumed = control.resume->checkpoint.state.frame;
  for (Index k = first; k < resumed && k <= last; ++k)
    exporter.add_earlier(k, std::min(static_cast<double>(k) / scene.time.fps, scene.time.duration));
  return exporter;
}

void make_directory(const fs::path& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw OutputError(dir.string() + ": cannot create directory: " + ec.message());
}

int run_simulate(const SimulateOptions& given) {
  const SimulateOptions o = given.resume.empty() ? given : resumed_options(given);
  set_threads(o.threads);
  std::vector<std::string> overrides = o.set;
  if (o.duration > 0) overrides.push_back(number_override("time.duration", o.duration));
  if (!o.exports.empty()) overrides.push_back(export_override(o.exports));
  const Scene scene = load_scene(o.scene, overrides);
  const fs::path dir = o.output_dir.empty() ? fs::path(scene.output.directory) : fs::path(o.output_dir);
  // A resumed run continues the run in `dir`; a fresh one must not mix with an old one.
  if (o.resume.empty()) prepare_output_directory(dir, o.overwrite, scene.name, scene.file);
  catch_interrupts();
  RunControl control = make_run_control(o.resume, o.checkpoint_every, run_record(o), dir, scene, o.quiet);
  control.threads_fixed = o.threads > 0 || std::getenv("OMP_NUM_THREADS") != nullptr;
  control.command = "simulate";
  ParticleExporter exporter = make_exporter(scene, dir, control);
  auto export_frame = [&](const Simulation& sim, Index frame, const StepStats*) {
    exporter.write(frame, sim.time(), sim.fluid(), sim.boundary());
  };
  run_scene(scene, dir, o.quiet, export_frame, control);
  return 0;
}

void run_scene(const Scene& scene, const fs::path& dir, bool quiet, const FrameCallback& on_frame,
               const RunControl& control, const FrameOutput& output) {
  make_directory(dir);
  const bool tty = isatty(fileno(stderr)) && !quiet;
  if (!quiet)
    std::fprintf(
        stderr,
        "sluice: %s: %zu fluid particles (%d removed inside boundaries), %zu boundary particles, %s, %d threads\n",
        scene.file.c_str(), scene.fluid_x.size(), scene.fluid_removed, scene.boundary_x.size(),
        to_string(scene.solver.type), omp_get_max_threads());
  if (!quiet && scene.fluid_near_samples > 0)
    std::fprintf(stderr,
                 "sluice: note: %d of the removed fluid particles were closer than %g spacings to a boundary sample "
                 "(they would start compressed)\n",
                 scene.fluid_near_samples, shapes::kMinSampleDistance);
  if (!quiet && !scene.time.auto_settle && scene.time.settle > 0)
    std::fprintf(stderr, "sluice: settling for %g s before t = 0 (time.settle)\n", scene.time.settle);

  // The settling phase runs in the constructor: if it goes unstable, the run's record
  // says so before the error reaches main (exit status 4).
  check_memory(scene);
  std::optional<Simulation> built;
  try {
    built.emplace(scene);
  } catch (const std::bad_alloc&) {
    throw OutOfMemory(allocating_message(scene));
  } catch (const SimulationUnstable& e) {
    const nlohmann::json summary = {{"sluice_version", SLUICE_VERSION},
                                    {"scene", {{"file", scene.file}, {"name", scene.name}}},
                                    {"parameters", scene.resolved},
                                    {"status", "unstable"},
                                    {"message", e.what()},
                                    {"frames_written", 0}};
    write_file_atomic((dir / "summary.json").string(),
                      summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    throw;
  }
  Simulation& sim = *built;
  if (!quiet && sim.relax_stats().rounds > 0) {
    const RelaxStats& r = sim.relax_stats();
    std::fprintf(stderr,
                 "sluice: relaxed the start in %d rounds: largest compression %.2f %% -> %.2f %% (time.relax_start)",
                 r.rounds, r.largest_before_percent, r.largest_after_percent);
    std::fprintf(stderr, "\n");
  }
  // The constructor runs time.settle (or the automatic settle) to its end; a signal that came
  // meanwhile is seen here.
  const double settled = sim.settled_seconds();
  if (!quiet && scene.time.auto_settle && settled > 0)
    std::fprintf(stderr,
                 "sluice: settled for %g s before t = 0, as the fluid starts at rest (time.settle \"auto\"; 0: none)\n",
                 settled);
  const bool interrupted_settling = settled > 0 && interrupt_signal() != 0;
  RunTotals totals;
  totals.initial_energy = sim.mechanical_energy();
  // Resumed: the checkpoint's state and totals, stats.csv cut back to its step, and its
  // frame drawn again (the PNG may have been in flight when the run stopped).
  const StepStats* resumed = control.resume ? resume_run(sim, totals, dir, *control.resume) : nullptr;
  StatsCsv csv((dir / "stats.csv").string(), /*append=*/resumed != nullptr);
  Checkpointer checkpointer(scene, dir, control);

  nlohmann::json summary = {
      {"sluice_version", SLUICE_VERSION},
      {"scene", {{"file", scene.file}, {"name", scene.name}}},
      {"parameters", scene.resolved},
      {"threads", omp_get_max_threads()},
      {"thread_wait", thread_wait_policy()},
      {"fluid_particles", scene.fluid_x.size()},
      {"fluid_removed", scene.fluid_removed},
      {"fluid_removed_near_samples", scene.fluid_near_samples},
      {"boundary_particles", scene.boundary_x.size()},
      {"frames", sim.frame_count() + 1},
  };
  if (control.resume) summary["resumed_from"] = resume_summary(*control.resume);
  if (sim.relax_stats().rounds > 0)
    summary["start_relaxation"] = {{"rounds", sim.relax_stats().rounds},
                                   {"largest_compression_before_percent", sim.relax_stats().largest_before_percent},
                                   {"largest_compression_after_percent", sim.relax_stats().largest_after_percent}};
  if (settled > 0) summary["settle"] = {{"seconds", settled}, {"automatic", scene.time.auto_settle}};
  const auto t0 = std::chrono::steady_clock::now();
  const double wall_before = totals.wall_seconds;  // of the run a checkpoint continues
  auto elapsed = [&] {
    return wall_before + std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  // Frames whose callback returned (all of them written, for a sink without FrameOutput),
  // after those of the run a checkpoint continues (its own frame is drawn again).
  long frames_done = control.resume ? control.resume->checkpoint.state.frame : 0;
  auto frames_written = [&] { return output.written ? output.written() : frames_done; };
  // stats.csv under its real name first, then summary.json: a stats.csv without a
  // summary.json is a run that was killed. A stats.csv that could not be completed (full
  // disk) is kept with the rows it has, and the summary says the run failed.
  ThreadGovernor governor(omp_get_max_threads(), control.threads_fixed);
  auto finish_files = [&](std::string status, std::string message) {
    totals.wall_seconds = elapsed();
    if (governor.active())
      summary["thread_governor"] = {{"switches", governor.switches()},
                                    {"steps_on_1_thread", governor.steps_on_one()},
                                    {"steps_on_all", governor.steps_on_max()}};
    std::exception_ptr csv_error;
    try {
      csv.finish();
    } catch (const OutputError& e) {
      csv_error = std::current_exception();
      if (status == "completed") {
        status = "failed";
        message = e.what();
      }
    }
    summary["status"] = status;
    if (!message.empty()) summary["message"] = message;
    summary["frames_written"] = frames_written();
    summary["totals"] = totals.to_json(static_cast<long>(scene.fluid_x.size()));
    if (checkpointer.enabled()) summary["checkpoints"] = checkpointer.summary();
    // replace: a name or --set value that is not UTF-8 must not stop the summary
    write_file_atomic((dir / "summary.json").string(),
                      summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
    if (csv_error) std::rethrow_exception(csv_error);
  };
  // Stops the run at a step after SIGINT or SIGTERM: frames in flight are finished, the
  // record says where the run stopped and how to go on.
  auto stop_if_interrupted = [&] {
    const int signal = interrupt_signal();
    if (signal == 0) return;
    if (tty) std::fprintf(stderr, "\n");
    if (output.wait) output.wait();
    const bool resumable = checkpointer.written() > 0 || control.resume;
    const std::string how = resumable ? "resume with: sluice " + control.command + " --resume " + dir.string()
                                      : "no checkpoint was written (pass --checkpoint-every N to be able to resume); "
                                        "run again with --overwrite";
    char where[96];
    std::snprintf(where, sizeof where, "at step %ld, t = %.9g s", sim.steps(), sim.time());
    const std::string message = "interrupted by " + signal_name(signal) + " " + where + "; stats.csv, summary.json" +
                                (resumable ? ", the checkpoints" : "") + " and the output up to frame " +
                                std::to_string(sim.frame()) + " are kept in " + dir.string() + "; " + how;
    summary["interrupted"] = {
        {"signal", signal_name(signal)},
        {"step", sim.steps()},
        {"time", sim.time()},
        {"resume", resumable ? nlohmann::json(resume_command(control.command, dir)) : nlohmann::json(nullptr)}};
    finish_files("interrupted", message);
    throw Interrupted(signal, message);
  };

  // Stops before frame 0 when the signal came while settling. Checkpoints start at t = 0:
  // the settled state is not one (a resumed run settles again from the scene), so none is
  // written and the message says why rather than asking for --checkpoint-every.
  auto stop_after_settling = [&] {
    const int signal = interrupt_signal();
    const bool resumable = control.resume.has_value();  // the earlier run's checkpoints
    char where[160];
    std::snprintf(where, sizeof where, "while settling (%s%g s, run to its end), before t = 0",
                  settle_origin(scene.time), settled);
    const std::string how =
        resumable ? "its checkpoints are kept; resume with: sluice " + control.command + " --resume " + dir.string()
                  : "no frame and no checkpoint was written (checkpoints start at t = 0, after "
                    "settling); run again with --overwrite";
    const std::string message = "interrupted by " + signal_name(signal) + " " + where +
                                "; stats.csv and summary.json are kept in " + dir.string() + "; " + how;
    summary["interrupted"] = {
        {"signal", signal_name(signal)},
        {"step", sim.steps()},
        {"time", sim.time()},
        {"settling", true},
        {"resume", resumable ? nlohmann::json(resume_command(control.command, dir)) : nlohmann::json(nullptr)}};
    finish_files("interrupted", message);
    throw Interrupted(signal, message);
  };

  EtaEstimate eta_estimate;
  try {
    if (interrupted_settling) stop_after_settling();
    on_frame(sim, sim.frame(), resumed);
    ++frames_done;
    eta_estimate.add(elapsed(), sim.time());
    while (!sim.finished()) {
      stop_if_interrupted();
      governor.before_step();
      const auto step_start = std::chrono::steady_clock::now();
      const StepStats st = sim.step();
      governor.after_step(std::chrono::duration<double>(std::chrono::steady_clock::now() - step_start).count(),
                          st.iterations);
      csv.write(st);
      totals.add(st);
      if (st.frame < 0) continue;
      on_frame(sim, st.frame, &st);
      ++frames_done;
      csv.flush();
      checkpointer.at_frame(sim, st, totals, elapsed());
      const double wall = elapsed();
      eta_estimate.add(wall, sim.time());
      const std::optional<double> eta = eta_estimate.seconds_left(scene.time.duration);
      if (tty) {
        std::fprintf(stderr,
                     "\r  t = %.3f / %.3f s   frame %d / %d   step %ld   iterations %d   error %.3f%%   ETA %s   ",
                     sim.time(), scene.time.duration, st.frame, sim.frame_count(), st.step, st.iterations,
                     st.avg_error_percent, clock_string(eta).c_str());
      } else if (!quiet && (st.frame % 10 == 0 || st.frame == sim.frame_count())) {
        std::fprintf(stderr, "  t = %.3f s, frame %d/%d, step %ld, avg iterations %.2f, wall %.1f s, ETA %s\n",
                     sim.time(), st.frame, sim.frame_count(), st.step,
                     totals.sum_iterations / static_cast<double>(totals.steps), wall, clock_string(eta).c_str());
      }
    }
    if (output.wait) output.wait();  // the last frame's write must succeed before "completed"
  } catch (const Interrupted&) {
    throw;
  } catch (const SimulationUnstable& e) {
    if (tty) std::fprintf(stderr, "\n");
    try {
      if (output.wait) output.wait();
    } catch (const std::exception&) {
      // the instability is the error to report; the count says what was written
    }
    finish_files("unstable", e.what());
    // One message: what happened and what is kept.
    throw SimulationUnstable(std::string(e.what()) + "; stats.csv, summary.json and the output up to frame " +
                             std::to_string(sim.frame()) + " are kept in " + dir.string());
  } catch (const std::exception& e) {
    // A failure that is not the simulation's (a frame that cannot be rendered or
    // written): the files of the run end with it, marked "failed".
    if (tty) std::fprintf(stderr, "\n");
    try {
      if (output.wait) output.wait();  // the write in flight: completed or failed, it counts right
    } catch (const std::exception&) {
    }
    try {
      finish_files("failed", e.what());
    } catch (const std::exception&) {
      // the first error is the one to report; ~StatsCsv removes what could not be finished
    }
    throw;
  }
  if (tty) std::fprintf(stderr, "\n");
  finish_files("completed", "");
  if (!quiet)
    std::fprintf(stderr, "sluice: %ld steps in %.1f s, %.2f iterations and %.4f%% error on average; wrote %s\n",
                 totals.steps, totals.wall_seconds, totals.sum_iterations / std::max(1.0, double(totals.steps)),
                 totals.sum_avg_error / std::max(1.0, double(totals.steps)), dir.c_str());
}

}  // namespace sluice::app
