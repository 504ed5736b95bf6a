#pragma once
// Checkpoints: the full state of a run in one binary file, so that an interrupted run
// continues bit-identically (`--checkpoint-every N`, `--resume DIR`).
//
// File layout (little-endian):
//   "SLUICECK"          8 bytes, magic
//   version             u32 (kCheckpointVersion)
//   scene hash          u64 (scene_hash: resolved parameters and sampled particles)
//   payload size        u64
//   payload             SimulationState, RunTotals, the last StepStats (checkpoint.cpp)
//   checksum            u64, FNV-1a 64 over every byte before it
// A run keeps its newest two checkpoints in DIR/checkpoints/checkpoint_NNNNN.bin (NNNNN
// the frame), each written to a temporary name, flushed to disk and renamed, so a
// crash while writing one leaves the previous two intact.
#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/output.h"
#include "scene/scene.h"
#include "solver/simulation.h"
#include "solver/stats.h"

namespace sluice {

// A checkpoint that cannot be used: truncated, not a checkpoint, another version,
// corrupt, or written for another scene. The message names the file and the problem.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

constexpr std::uint32_t kCheckpointVersion = 2;  // 2: energies in the totals and the last step

// What a run needs to continue: the simulation's state and the run's own records.
struct Checkpoint {
  SimulationState state;
  RunTotals totals;     // summary.json's totals up to state.step (wall_seconds so far)
  StepStats last_step;  // the step that reached state.frame (its frame is drawn again on resume)
};

// FNV-1a 64 over `n` bytes, continuing from `h`.
constexpr std::uint64_t kFnvOffset = 1469598103934665603ULL;
std::uint64_t fnv1a64(const void* data, size_t n, std::uint64_t h = kFnvOffset);

// Identifies a scene with its overrides: the resolved parameters (every default filled
// in) and the sampled fluid and boundary particles (which also catch a change of the
// sampling code between versions).
std::uint64_t scene_hash(const Scene& scene);

// The file's bytes, and back. decode_checkpoint checks, in this order: length, magic,
// version, declared size, checksum, scene hash, payload; `file` names the file in
// CheckpointError messages.
std::string encode_checkpoint(const Checkpoint& c, std::uint64_t scene_hash);
Checkpoint decode_checkpoint(const std::string& bytes, const std::string& file, std::uint64_t scene_hash);

// DIR/checkpoints.
std::filesystem::path checkpoint_directory(const std::filesystem::path& run_dir);
// DIR/checkpoints/checkpoint_NNNNN.bin files (not temporary or rejected ones), newest
// (highest frame) first.
std::vector<std::filesystem::path> list_checkpoints(const std::filesystem::path& run_dir);

// Writes the checkpoint of frame c.state.frame (temporary name, fsync, rename), then
// deletes all but the newest `keep`. Returns the file's size. Throws OutputError.
size_t write_checkpoint(const std::filesystem::path& run_dir, const Checkpoint& c, std::uint64_t scene_hash,
                        int keep = 2);

// Reads one file; throws CheckpointError.
Checkpoint read_checkpoint(const std::filesystem::path& file, std::uint64_t scene_hash);

// The newest checkpoint of DIR that reads back, trying older ones when it does not
// (each refusal in `rejected`, newest first, as "FILE: reason" messages). Throws
// CheckpointError when DIR has none, or none is usable (naming every file's problem).
struct LoadedCheckpoint {
  Checkpoint checkpoint;
  std::filesystem::path file;
  std::vector<std::string> rejected;
};
LoadedCheckpoint load_newest_checkpoint(const std::filesystem::path& run_dir, std::uint64_t scene_hash);

// Cuts stats.csv after the row of `step`, so that a resumed run appends the rows an
// uninterrupted run would have written next. Throws CheckpointError when the file is
// missing, has another header, or has no complete row for `step`.
void truncate_stats_csv(const std::filesystem::path& path, long step);

}  // namespace sluice
