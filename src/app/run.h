#pragma once
// The run loop shared by `simulate` and `render`: steps a scene to its duration,
// writes stats.csv and summary.json, prints progress, and calls back at t = 0 and at
// every frame time.
#include <filesystem>
#include <functional>
#include <optional>

#include "io/checkpoint.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace sluice::app {

// `last` is the step that landed on the frame time (nullptr for frame 0 at t = 0).
using FrameCallback = std::function<void(const Simulation& sim, Index frame, const StepStats* last)>;

// Creates `dir` and its parents; throws OutputError.
void make_directory(const std::filesystem::path& dir);

// Checkpoints of a run (app/resume.h); the default writes none and starts at t = 0.
struct RunControl {
  int checkpoint_every = 0;                // frames between checkpoints; 0: none
  std::optional<LoadedCheckpoint> resume;  // continue from this checkpoint
  nlohmann::json record;  // the command's flags, written to DIR/checkpoints/run.json for --resume (null: none)
};

// Throws SimulationUnstable (after renaming stats.csv.tmp to stats.csv and writing
// summary.json with "status": "unstable"; the message says what is kept where). Other
// exceptions pass through after the same with "status": "failed", where that can be written.
void run_scene(const Scene& scene, const std::filesystem::path& dir, bool quiet, const FrameCallback& on_frame,
               const RunControl& control = {});

}  // namespace sluice::app
