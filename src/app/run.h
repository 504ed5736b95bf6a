#pragma once
// The run loop shared by `simulate` and `render`: steps a scene to its duration,
// writes stats.csv and summary.json, prints progress, and calls back at t = 0 and at
// every frame time.
#include <filesystem>
#include <functional>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "io/checkpoint.h"
#include "io/export.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::app {

// `last` is the step that landed on the frame time (nullptr for frame 0 at t = 0).
using FrameCallback = std::function<void(const Simulation& sim, Index frame, const StepStats* last)>;

// std::bad_alloc with what was being allocated; the message follows "out of memory".
class OutOfMemory : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Refuses a scene whose simulation would need more memory than the machine (or the
// process's RLIMIT_AS / RLIMIT_DATA) allows, with both figures; throws SceneError.
void check_memory(const Scene& scene);

// The OutOfMemory message for a bad_alloc while building the scene's simulation.
std::string allocating_message(const Scene& scene);

// Creates `dir` and its parents; throws OutputError.
void make_directory(const std::filesystem::path& dir);

// Checkpoints of a run (app/resume.h); the default writes none and starts at t = 0.
struct RunControl {
  int checkpoint_every = 0;                // frames between checkpoints; 0: none
  std::optional<LoadedCheckpoint> resume;  // continue from this checkpoint
  nlohmann::json record;  // the command's flags, written to DIR/checkpoints/run.json for --resume (null: none)
  std::string command = "simulate";  // for the resume hint of an interrupted run
  // --threads or OMP_NUM_THREADS fixed the thread count; otherwise a ThreadGovernor
  // chooses it between steps.
  bool threads_fixed = false;
};

// A frame sink that writes in the background (render's PNG encoding): run_scene waits for
// it before the run's record is written, and summary.json counts what it wrote.
struct FrameOutput {
  std::function<void()> wait;     // finishes the writes in flight; throws their error
  std::function<long()> written;  // frames written so far
};

// `--export csv,vtk` as a scene override: it replaces output.export, so that the run
// exports what summary.json's parameters say. A format given twice: FlagError.
std::string export_override(const std::vector<std::string>& formats);

// The scene's output.export into DIR/particles. For a resumed run, the frames from
// `first` to `last` before the checkpoint's are listed in the collection, as the run
// that wrote them left them. Throws OutputError.
ParticleExporter make_exporter(const Scene& scene, const std::filesystem::path& dir, const RunControl& control,
                               Index first = 0, Index last = std::numeric_limits<Index>::max());

// Throws SimulationUnstable (after renaming stats.csv.tmp to stats.csv and writing
// summary.json with "status": "unstable"; the message says what is kept where). Other
// exceptions pass through after the same with "status": "failed", where that can be written.
// After SIGINT or SIGTERM (catch_interrupts) it stops at the next step, writes the same
// with "status": "interrupted", and throws Interrupted.
void run_scene(const Scene& scene, const std::filesystem::path& dir, bool quiet, const FrameCallback& on_frame,
               const RunControl& control = {}, const FrameOutput& output = {});

}  // namespace sluice::app
