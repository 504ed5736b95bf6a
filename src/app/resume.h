#pragma once
// Checkpoints and --resume for `simulate` and `render` (the file format is in
// io/checkpoint.h). A run started with --checkpoint-every records its scene file and
// flags in DIR/checkpoints/run.json; `--resume DIR` reads them back, so the resumed run
// is the same run: same scene, overrides and image settings. The scene's hash in each
// checkpoint refuses a scene file edited in between.
#include <filesystem>
#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/run.h"
#include "io/checkpoint.h"
#include "io/output.h"
#include "solver/simulation.h"

namespace sluice::app {

// DIR/checkpoints/run.json: the command and the flags that shape its results (not
// --threads, -q or -o: results are bit-identical for any thread count).
nlohmann::json run_record(const SimulateOptions& o);
nlohmann::json run_record(const RenderOptions& o);

// The options recorded in `given.resume`, with `given`'s --threads, -q and, when given,
// --checkpoint-every and SCENE (a scene file moved since; its hash must still match).
// The output directory is the resumed one. Throws CheckpointError.
SimulateOptions resumed_options(const SimulateOptions& given);
RenderOptions resumed_options(const RenderOptions& given);

// What run_scene needs: for a resumed run the newest usable checkpoint of `dir` (each
// refused one is reported as a warning and set aside as *.rejected, so that the
// resumed run's own checkpoints are again the newest); else the record to write when
// checkpoints are on. Throws CheckpointError.
RunControl make_run_control(const std::string& resume, int checkpoint_every, const nlohmann::json& record,
                            const std::filesystem::path& dir, const Scene& scene, bool quiet);

// Puts `sim` and `totals` in the checkpoint's state and cuts DIR/stats.csv back to its
// step. Returns the step that reached the checkpoint's frame. Throws CheckpointError.
const StepStats* resume_run(Simulation& sim, RunTotals& totals, const std::filesystem::path& dir,
                            const LoadedCheckpoint& loaded);
nlohmann::json resume_summary(const LoadedCheckpoint& loaded);

// Writes a checkpoint at every frame that is a multiple of N (not the final one: a
// finished run needs none), and counts their size and time for summary.json.
class Checkpointer {
 public:
  Checkpointer(const Scene& scene, const std::filesystem::path& dir, const RunControl& control);
  void at_frame(const Simulation& sim, const StepStats& st, const RunTotals& totals, double wall_seconds);
  bool enabled() const { return every_ > 0; }
  long written() const { return written_; }
  nlohmann::json summary() const;

 private:
  std::filesystem::path dir_;
  int every_ = 0;
  std::uint64_t hash_ = 0;
  long written_ = 0;
  size_t last_bytes_ = 0;
  double ms_ = 0;
};

}  // namespace sluice::app
