// Checkpoints (src/io/checkpoint.h, Simulation::state/restore, `--checkpoint-every` and
// `--resume`): a state survives the file bit for bit; a run resumed after frame k ends
// bit-identical to an uninterrupted one (IISPH, WCSPH with viscosity, a swinging paddle
// with an adaptive step); refused files (flipped byte, truncated, other version, other
// scene, not a checkpoint) name the file and the problem; the older checkpoint takes
// over when the newest is corrupt; and through the program itself, rendered frames,
// stats.csv, exports and summary totals after `--resume` equal an uninterrupted run's.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "io/checkpoint.h"
#include "scene/scene.h"
#include "solver/simulation.h"
#include "temp_dir.h"
#include "test_process.h"
#include "test_util.h"

namespace sluice {
namespace {

namespace fs = std::filesystem;
using test::scene_from_json;

using test::TempDir;

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void write_bytes(const fs::path& p, const std::string& bytes) {
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << bytes;
}

template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Every field, bit for bit (memcmp: -0.0 and 0.0 or two NaNs would not pass as equal).
void expect_same_state(const SimulationState& a, const SimulationState& b) {
  EXPECT_EQ(std::memcmp(&a.time, &b.time, sizeof a.time), 0) << a.time << " vs " << b.time;
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_TRUE(same_bits(a.fluid.x, b.fluid.x)) << "fluid positions";
  EXPECT_TRUE(same_bits(a.fluid.v, b.fluid.v)) << "fluid velocities";
  EXPECT_TRUE(same_bits(a.fluid.rho, b.fluid.rho)) << "fluid densities";
  EXPECT_TRUE(same_bits(a.fluid.p, b.fluid.p)) << "fluid pressures";
  EXPECT_TRUE(same_bits(a.fluid.id, b.fluid.id)) << "fluid ids (order)";
  EXPECT_TRUE(same_bits(a.boundary_x, b.boundary_x)) << "boundary positions";
  EXPECT_TRUE(same_bits(a.boundary_v, b.boundary_v)) << "boundary velocities";
  EXPECT_TRUE(same_bits(a.boundary_a, b.boundary_a)) << "boundary accelerations";
  EXPECT_TRUE(same_bits(a.boundary_volume, b.boundary_volume)) << "boundary volumes";
  EXPECT_TRUE(same_bits(a.boundary_p, b.boundary_p)) << "boundary pressures";
  EXPECT_TRUE(same_bits(a.near_moving, b.near_moving)) << "near-moving flags";
}

// The message of the CheckpointError `f` throws ("" when it throws none).
std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

std::string hex(std::uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

// A 200-particle dam break; steps of 2 ms, 25 per frame, so frame 3 (step 75) falls
// between two spatial sorts (every 16 steps).
const char* kDamBreak = R"({
  "spacing": 0.02,
  "solver": {"type": "iisph"},
  "time": {"duration": 0.3, "fps": 20, "dt": 2e-3},
  "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.2, 0.4]}],
  "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.6, 0.6]}]
})";

Scene dam_break(const std::vector<std::string>& overrides = {}) { return scene_from_json(kDamBreak, overrides); }

// One checkpoint, written and read back through the file.
Checkpoint through_file(const fs::path& dir, const Checkpoint& c, const Scene& scene) {
  write_checkpoint(dir, c, scene_hash(scene));
  return read_checkpoint(list_checkpoints(dir).front(), scene_hash(scene));
}

// --- the state survives the file --------------------------------------------------------

TEST(Checkpoint, StateRoundTripIsBitIdentical) {
  const TempDir dir;
  const Scene scene = dam_break();
  Simulation sim(scene);
  Checkpoint c;
  for (int k = 0; k < 37; ++k) {  // mid-frame and after two spatial sorts
    c.last_step = sim.step();
    c.totals.add(c.last_step);
  }
  c.state = sim.state();
  c.totals.wall_seconds = 1.25;
  const Checkpoint back = through_file(dir.path(), c, scene);
  expect_same_state(c.state, back.state);
  EXPECT_EQ(back.totals.steps, 37);
  EXPECT_EQ(back.totals.sum_iterations, c.totals.sum_iterations);
  EXPECT_EQ(back.totals.sum_avg_error, c.totals.sum_avg_error);
  EXPECT_EQ(back.totals.max_error, c.totals.max_error);
  EXPECT_EQ(back.totals.wall_seconds, 1.25);
  for (int k = 0; k < 6; ++k) EXPECT_EQ(back.totals.sum_ms[k], c.totals.sum_ms[k]);
  EXPECT_EQ(back.last_step.step, 37);
  EXPECT_EQ(back.last_step.dt, c.last_step.dt);
  EXPECT_EQ(back.last_step.iterations, c.last_step.iterations);
  EXPECT_EQ(back.last_step.avg_error_percent, c.last_step.avg_error_percent);
  EXPECT_EQ(back.last_step.frame, c.last_step.frame);

  // Restored into a fresh simulation, the state reads back the same.
  Simulation other(scene);
  other.restore(back.state);
  expect_same_state(c.state, other.state());
  EXPECT_EQ(other.time(), sim.time());
  EXPECT_EQ(other.steps(), 37);
}

// Simulation::solver_settings() may switch the pressure solver between steps: the steps
// after it solve with the new one (its loop and its warm start), as a simulation built
// with that solver does from the same state. Both ways, Jacobi to Chebyshev and back.
TEST(Checkpoint, PressureSolverSwitchedBetweenStepsTakesEffect) {
  for (const auto& [from, to] : {std::pair{"jacobi", "chebyshev"}, std::pair{"chebyshev", "jacobi"}}) {
    const Scene before = dam_break({std::string("solver.pressure_solver=") + from});
    const Scene after = dam_break({std::string("solver.pressure_solver=") + to});
    Simulation a(before);
    for (int k = 0; k < 20; ++k) a.step();
    const SimulationState at_switch = a.state();
    a.solver_settings().pressure_solver = after.solver.pressure_solver;
    Simulation b(after), stayed(before);
    b.restore(at_switch);
    stayed.restore(at_switch);
    int extrapolated = 0;  // steps past Chebyshev's 3 plain iterations
    for (int k = 0; k < 20; ++k) {
      const StepStats sa = a.step(), sb = b.step();
      stayed.step();
      EXPECT_EQ(sa.iterations, sb.iterations) << from << " to " << to << ", step " << sa.step;
      extrapolated += sa.iterations > 3;
    }
    EXPECT_EQ(test::state_hash(a), test::state_hash(b)) << from << " to " << to;
    EXPECT_NE(test::state_hash(a), test::state_hash(stayed)) << from << " to " << to << ": the switch changed nothing";
    EXPECT_GT(extrapolated, 0);
  }
}

// --- resuming after frame k ends where the uninterrupted run ends -----------------------

struct ResumeCase {
  std::string name;
  std::function<Scene()> scene;
  Index frame;  // the checkpoint's frame
};

std::ostream& operator<<(std::ostream& os, const ResumeCase& c) { return os << c.name; }

class Resume : public ::testing::TestWithParam<ResumeCase> {};

TEST_P(Resume, FinalStateIsBitIdentical) {
  const ResumeCase& c = GetParam();
  const TempDir dir;
  const Scene scene = c.scene();
  // Uninterrupted, writing a checkpoint at frame k and keeping the steps after it.
  Simulation a(scene);
  std::vector<StepStats> after;
  bool written = false;
  while (!a.finished()) {
    const StepStats st = a.step();
    if (written) after.push_back(st);
    if (st.frame == c.frame) {
      write_checkpoint(dir.path(), Checkpoint{a.state(), {}, st}, scene_hash(scene));
      written = true;
    }
  }
  ASSERT_TRUE(written) << "the run never reached frame " << c.frame;
  ASSERT_FALSE(after.empty());

  // A new process, as it were: a simulation built from the scene, then the checkpoint.
  Simulation b(scene);
  b.restore(read_checkpoint(list_checkpoints(dir.path()).front(), scene_hash(scene)).state);
  std::vector<StepStats> resumed;
  while (!b.finished()) resumed.push_back(b.step());

  expect_same_state(a.state(), b.state());
  EXPECT_EQ(test::state_hash(a), test::state_hash(b));
  ASSERT_EQ(resumed.size(), after.size());
  for (size_t k = 0; k < after.size(); ++k) {  // what stats.csv gets
    EXPECT_EQ(resumed[k].step, after[k].step);
    EXPECT_EQ(resumed[k].dt, after[k].dt);
    EXPECT_EQ(resumed[k].iterations, after[k].iterations);
    EXPECT_EQ(resumed[k].avg_error_percent, after[k].avg_error_percent);
    EXPECT_EQ(resumed[k].max_cfl, after[k].max_cfl);
    EXPECT_EQ(resumed[k].frame, after[k].frame);
  }
}

Scene paddle() {
  // scenes/paddle.json at a coarse spacing (about 1 100 particles), its flap swinging,
  // the CFL step of Eq. 14 varying from step to step.
  const Scene s = load_scene(std::string(SLUICE_SOURCE_DIR) + "/scenes/paddle.json",
                             {"spacing=0.04", "boundaries.1.spacing=0.03", "time.duration=0.2", "time.fps=30"});
  EXPECT_TRUE(s.objects.at(1).moving);
  EXPECT_FALSE(s.time.dt > 0) << "paddle.json uses the adaptive step";
  return s;
}

INSTANTIATE_TEST_SUITE_P(Checkpoint, Resume,
                         ::testing::Values(ResumeCase{"iisph", [] { return dam_break(); }, 3},
                                           ResumeCase{"wcsph_viscosity",
                                                      [] {
                                                        return dam_break({"solver.type=wcsph", "solver.stiffness=5e5",
                                                                          "solver.viscosity=0.01", "time.dt=2e-4",
                                                                          "time.duration=0.1", "time.fps=50"});
                                                      },
                                                      2},
                                           ResumeCase{"moving_paddle_adaptive", paddle, 3}),
                         [](const ::testing::TestParamInfo<ResumeCase>& param_info) { return param_info.param.name; });

// --- refused checkpoints ----------------------------------------------------------------

TEST(Checkpoint, RefusedFilesNameTheFileAndTheProblem) {
  const TempDir dir;
  const Scene scene = dam_break();
  Simulation sim(scene);
  StepStats st;
  while (sim.frame() < 1) st = sim.step();
  write_checkpoint(dir.path(), Checkpoint{sim.state(), {}, st}, scene_hash(scene));
  const fs::path file = list_checkpoints(dir.path()).front();
  EXPECT_EQ(file.filename(), "checkpoint_00001.bin");
  const std::string good = read_bytes(file);
  const std::uint64_t hash = scene_hash(scene);
  auto refusal = [&](const std::string& bytes) {
    write_bytes(file, bytes);
    return error_of([&] { read_checkpoint(file, hash); });
  };
  auto expect_refusal = [&](const std::string& bytes, const std::string& what) {
    const std::string msg = refusal(bytes);
    EXPECT_NE(msg.find("checkpoint " + file.string() + " "), std::string::npos) << msg;
    EXPECT_NE(msg.find(what), std::string::npos) << msg;
  };

  EXPECT_EQ(refusal(good), "");

  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;  // a bit in the middle of the fluid arrays
  expect_refusal(flipped, "is corrupt: checksum mismatch");

  std::string last = good;
  last[good.size() - 1] ^= 0x01;  // the checksum itself
  expect_refusal(last, "is corrupt: checksum mismatch");

  expect_refusal(good.substr(0, good.size() - 100), "is truncated: " + std::to_string(good.size() - 100) + " bytes");
  expect_refusal(good.substr(0, 5), "is truncated");
  expect_refusal("", "is truncated");

  std::string version = good;
  version[8] = static_cast<char>(kCheckpointVersion + 1);  // u32 version, little-endian
  expect_refusal(version, "has format version " + std::to_string(kCheckpointVersion + 1) +
                              "; this sluice reads version " + std::to_string(kCheckpointVersion));

  std::string magic = good;
  magic.replace(0, 8, "PNG\r\n\x1a\n\0", 8);
  expect_refusal(magic, "is not a sluice checkpoint");

  // Another scene, or the same scene with another override.
  write_bytes(file, good);
  for (const Scene& other : {dam_break({"solver.tolerance=0.05"}), dam_break({"spacing=0.025"})}) {
    const std::uint64_t h = scene_hash(other);
    ASSERT_NE(h, hash);
    EXPECT_EQ(error_of([&] { read_checkpoint(file, h); }), "checkpoint " + file.string() +
                                                               " was written for a different scene (hash " + hex(hash) +
                                                               ", this scene " + hex(h) + ")");
  }
  EXPECT_EQ(scene_hash(dam_break()), hash) << "the same scene hashes the same";
}

TEST(Checkpoint, RestoreRefusesAnotherScenesState) {
  const Scene scene = dam_break();
  Simulation small(scene), large(dam_break({"spacing=0.015"}));
  small.step();
  try {
    large.restore(small.state());
    FAIL() << "restored 200 particles into a simulation of " << large.fluid().size();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("fluid particles: the state has 200"), std::string::npos) << e.what();
  }
  EXPECT_EQ(large.steps(), 0) << "a refused state changes nothing";

  SimulationState bad = small.state();
  bad.fluid.id[0] = bad.fluid.id[1];
  Simulation fresh(scene);
  EXPECT_THROW(fresh.restore(bad), std::invalid_argument);
  bad = small.state();
  bad.boundary_x[0].x() += 0.5;  // a wall at rest elsewhere
  EXPECT_THROW(fresh.restore(bad), std::invalid_argument);
  EXPECT_EQ(fresh.steps(), 0);
}

// --- two kept, the older one takes over ---------------------------------------------------

TEST(Checkpoint, NewestTwoKeptAndOlderTakesOverWhenNewestIsCorrupt) {
  const TempDir dir;
  const Scene scene = dam_break();
  const std::uint64_t hash = scene_hash(scene);
  Simulation sim(scene);
  EXPECT_THROW(load_newest_checkpoint(dir.path(), hash), CheckpointError) << "no checkpoint yet";
  while (sim.frame() < 3) {
    const StepStats st = sim.step();
    if (st.frame > 0) write_checkpoint(dir.path(), Checkpoint{sim.state(), {}, st}, hash);
  }
  const std::vector<fs::path> files = list_checkpoints(dir.path());
  ASSERT_EQ(files.size(), 2u) << "frames 2 and 3 kept, frame 1 deleted";
  EXPECT_EQ(files[0].filename(), "checkpoint_00003.bin");
  EXPECT_EQ(files[1].filename(), "checkpoint_00002.bin");

  const LoadedCheckpoint newest = load_newest_checkpoint(dir.path(), hash);
  EXPECT_EQ(newest.checkpoint.state.frame, 3);
  EXPECT_TRUE(newest.rejected.empty());

  // A temporary file of a crash during writing is never taken for a checkpoint.
  write_bytes(dir.path() / "checkpoints" / "checkpoint_00004.bin.tmp", "SLUICECK half");
  std::string bytes = read_bytes(files[0]);
  bytes[bytes.size() / 3] ^= 0x04;
  write_bytes(files[0], bytes);
  const LoadedCheckpoint older = load_newest_checkpoint(dir.path(), hash);
  EXPECT_EQ(older.checkpoint.state.frame, 2);
  EXPECT_EQ(older.file, files[1]);
  ASSERT_EQ(older.rejected.size(), 1u);
  EXPECT_NE(older.rejected[0].find("checkpoint_00003.bin is corrupt: checksum mismatch"), std::string::npos)
      << older.rejected[0];

  write_bytes(files[1], read_bytes(files[1]).substr(0, 40));
  const std::string msg = error_of([&] { load_newest_checkpoint(dir.path(), hash); });
  EXPECT_NE(msg.find("no usable checkpoint in"), std::string::npos) << msg;
  EXPECT_NE(msg.find("checkpoint_00003.bin is corrupt"), std::string::npos) << msg;
  EXPECT_NE(msg.find("checkpoint_00002.bin is truncated"), std::string::npos) << msg;
}

TEST(Checkpoint, StatsCsvCutBackToTheCheckpointsStep) {
  const TempDir dir;
  const fs::path csv = dir.path() / "stats.csv";
  const std::string header = std::string(StatsCsv::header()) + "\n";
  std::string rows;
  for (int s = 1; s <= 12; ++s) rows += std::to_string(s) + ",0.1,0.001\n";
  write_bytes(csv, header + rows + "13,0.1");  // a row cut off when the run stopped
  truncate_stats_csv(csv, 10);
  EXPECT_EQ(read_bytes(csv), header + rows.substr(0, rows.find("11,")));
  EXPECT_NE(error_of([&] { truncate_stats_csv(csv, 11); }).find("has no row for step 11"), std::string::npos);
  write_bytes(csv, "step,time\n1,0\n");
  EXPECT_NE(error_of([&] { truncate_stats_csv(csv, 1); }).find("header"), std::string::npos);
  fs::remove(csv);
  EXPECT_NE(error_of([&] { truncate_stats_csv(csv, 1); }).find("cannot be read"), std::string::npos);
}

// --- through the program: render and simulate with --resume -------------------------------

// The program run in `dir`'s working folder (test::run_sluice): its exit status, its
// stderr in `err`.
int sluice(const test::CaseDir& dir, const std::vector<std::string>& args, std::string* err = nullptr) {
  const test::Result r = test::run_sluice(dir, args);
  if (err) *err = r.err;
  return r.status;
}

// stats.csv without its wall-clock columns (ms_*), which differ between any two runs.
std::string stats_without_timings(const fs::path& csv) {
  std::istringstream in(read_bytes(csv));
  std::string line, out;
  while (std::getline(in, line)) {
    int field = 0;
    std::string kept;
    for (char c : line) {
      if (c == ',') ++field;
      if (field < 10) kept += c;  // step .. frame
    }
    out += kept + "\n";
  }
  return out;
}

// summary.json's totals that do not depend on the wall clock.
nlohmann::json deterministic_totals(const fs::path& summary) {
  nlohmann::json t = nlohmann::json::parse(read_bytes(summary)).at("totals");
  t.erase("wall_seconds");
  t.erase("us_per_particle_step");
  t.erase("ms_per_step");
  return t;
}

// Every file of `sub` in `a` also in `b`, byte for byte, and no other.
void expect_same_files(const fs::path& a, const fs::path& b, const std::string& sub) {
  size_t count = 0;
  for (const fs::directory_entry& e : fs::directory_iterator(a / sub)) {
    const fs::path other = b / sub / e.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(read_bytes(e.path()) == read_bytes(other)) << e.path() << " differs from " << other;
    ++count;
  }
  size_t count_b = 0;
  for ([[maybe_unused]] const fs::directory_entry& e : fs::directory_iterator(b / sub)) ++count_b;
  EXPECT_EQ(count, count_b) << sub;
  EXPECT_GT(count, 0u);
}

const char* kRenderScene = R"({
  "name": "checkpoint_test",
  "spacing": 0.01,
  "solver": { "type": "iisph" },
  "time": { "duration": 0.3, "fps": 20, "dt": 1e-3 },
  "output": { "export": [] },
  "fluid": [ { "shape": "rectangle", "min": [0, 0], "max": [0.15, 0.2] } ],
  "boundaries": [ { "name": "tank", "shape": "box", "min": [0, 0], "max": [0.4, 0.25], "lid": false, "layers": 2 } ]
})";

// An interrupted run, as a crash leaves it: checkpoints at frames 2 and 4 (the run got
// past frame 5 before it stopped), frame 5's PNG half written, frame 6 missing, stats.csv
// rows past the checkpoint's step with a last one cut off, no summary.json, a temporary
// checkpoint file. `sluice render --resume` must end with the uninterrupted run's files.
// (Named Render* so that the sanitizer build of CI leaves it out, as the other renderer
// tests: Mesa's llvmpipe is not ours to sanitize.)
TEST(RenderCheckpoint, ResumeGivesByteIdenticalFrames) {
  const test::CaseDir dir;
  const fs::path scene = dir.work() / "scene.json", a = dir.work() / "a", b = dir.work() / "b";
  write_bytes(scene, kRenderScene);
  std::string err;
  ASSERT_EQ(sluice(dir,
                   {"render", scene.string(), "-o", a.string(), "--resolution", "160x96", "--no-video",
                    "--checkpoint-every", "2", "-q"},
                   &err),
            0)
      << err;
  const std::vector<fs::path> kept = list_checkpoints(a);
  ASSERT_EQ(kept.size(), 2u);
  EXPECT_EQ(kept[0].filename(), "checkpoint_00004.bin") << "none at the final frame 6";
  EXPECT_TRUE(fs::exists(a / "checkpoints" / "run.json"));

  fs::copy(a, b, fs::copy_options::recursive);
  fs::remove(b / "frames" / "frame_00006.png");
  const std::string png5 = read_bytes(b / "frames" / "frame_00005.png");
  write_bytes(b / "frames" / "frame_00005.png", png5.substr(0, png5.size() / 2));
  write_bytes(b / "frames" / "frame_00004.png", "not a png");  // in flight at the checkpoint
  fs::remove(b / "summary.json");
  std::ofstream(b / "stats.csv", std::ios::app) << "999,0.5,0.00";
  write_bytes(b / "checkpoints" / "checkpoint_00006.bin.tmp", "SLUICECK");

  ASSERT_EQ(sluice(dir, {"render", "--resume", b.string()}, &err), 0) << err;
  EXPECT_NE(err.find("resuming"), std::string::npos) << err;
  expect_same_files(a, b, "frames");
  EXPECT_EQ(stats_without_timings(a / "stats.csv"), stats_without_timings(b / "stats.csv"));
  EXPECT_EQ(deterministic_totals(a / "summary.json"), deterministic_totals(b / "summary.json"));
  const nlohmann::json summary = nlohmann::json::parse(read_bytes(b / "summary.json"));
  EXPECT_EQ(summary.at("resumed_from").at("frame"), 4);
  EXPECT_EQ(summary.at("frames_written"), 7);

  // The newest checkpoint corrupt: a warning, then the older one, the same frames.
  const fs::path c = dir.work() / "c";
  fs::copy(a, c, fs::copy_options::recursive);
  std::string bytes = read_bytes(c / "checkpoints" / "checkpoint_00004.bin");
  bytes[1000] ^= 0x20;
  write_bytes(c / "checkpoints" / "checkpoint_00004.bin", bytes);
  fs::remove_all(c / "frames");
  fs::create_directories(c / "frames");
  for (int f = 0; f <= 2; ++f) {
    const std::string name = "frame_0000" + std::to_string(f) + ".png";
    fs::copy_file(a / "frames" / name, c / "frames" / name);
  }
  ASSERT_EQ(sluice(dir, {"render", "--resume", c.string(), "-q"}, &err), 0) << err;
  EXPECT_NE(err.find("checkpoint_00004.bin is corrupt: checksum mismatch"), std::string::npos) << err;
  EXPECT_NE(err.find("falling back"), std::string::npos) << err;
  expect_same_files(a, c, "frames");
  EXPECT_EQ(stats_without_timings(a / "stats.csv"), stats_without_timings(c / "stats.csv"));
  // The refused file set aside, the resumed run's own checkpoint of frame 4 in its place.
  EXPECT_TRUE(fs::exists(c / "checkpoints" / "checkpoint_00004.bin.rejected"));
  const std::uint64_t hash = scene_hash(load_scene(scene.string()));
  const LoadedCheckpoint again = load_newest_checkpoint(c, hash);
  EXPECT_EQ(again.checkpoint.state.frame, 4);
  expect_same_state(load_newest_checkpoint(a, hash).checkpoint.state, again.checkpoint.state);

  // Both corrupt: exit status 7, each file's problem named.
  const fs::path d = dir.work() / "d";
  fs::copy(a, d, fs::copy_options::recursive);
  for (const fs::path& f : list_checkpoints(d)) write_bytes(f, read_bytes(f).substr(0, 64));
  EXPECT_EQ(sluice(dir, {"render", "--resume", d.string(), "-q"}, &err), 7);
  EXPECT_NE(err.find("sluice: checkpoint error: no usable checkpoint"), std::string::npos) << err;
  EXPECT_NE(err.find("checkpoint_00004.bin is truncated"), std::string::npos) << err;
  EXPECT_NE(err.find("checkpoint_00002.bin is truncated"), std::string::npos) << err;

  // Another scene file given with --resume: refused by its hash.
  const fs::path other = dir.work() / "other.json";
  std::string text = kRenderScene;
  text.replace(text.find("0.15, 0.2"), 9, "0.15, 0.1");
  write_bytes(other, text);
  EXPECT_EQ(sluice(dir, {"render", other.string(), "--resume", a.string(), "-q"}, &err), 7);
  EXPECT_NE(err.find("was written for a different scene (hash "), std::string::npos) << err;

  // A run of `render` is not resumed by `simulate`; flags that shape the result are
  // taken from the run, not given again.
  EXPECT_EQ(sluice(dir, {"simulate", "--resume", a.string(), "-q"}, &err), 7);
  EXPECT_NE(err.find("resume it with `sluice render --resume"), std::string::npos) << err;
  EXPECT_NE(sluice(dir, {"render", "--resume", a.string(), "--fps", "10", "-q"}, &err), 0);
  EXPECT_NE(err.find("excludes"), std::string::npos) << err;
}

TEST(CheckpointProgram, SimulateResumeGivesByteIdenticalExports) {
  const test::CaseDir dir;
  const fs::path scene = dir.work() / "scene.json", a = dir.work() / "a", b = dir.work() / "b";
  write_bytes(scene, kRenderScene);
  std::string err;
  ASSERT_EQ(sluice(dir,
                   {"simulate", scene.string(), "-o", a.string(), "--export", "csv,vtk", "--checkpoint-every", "3",
                    "-q", "--threads", "2"},
                   &err),
            0)
      << err;
  fs::copy(a, b, fs::copy_options::recursive);
  fs::remove(b / "particles" / "frame_00004.csv");
  fs::remove(b / "particles" / "frame_00006.csv");
  fs::remove(b / "particles" / "frame_00006_fluid.vtp");
  // The collection as the run left it after frame 4; the resumed run lists frames 0-2
  // again (written before the checkpoint of frame 3) and its own from 3 on.
  const std::string pvd = read_bytes(a / "particles" / "particles.pvd");
  write_bytes(b / "particles" / "particles.pvd", pvd.substr(0, pvd.find("frame_00005")) + "\n");
  fs::remove(b / "summary.json");
  ASSERT_EQ(sluice(dir, {"simulate", "--resume", b.string(), "-q", "--threads", "1"}, &err), 0) << err;
  expect_same_files(a, b, "particles");
  EXPECT_EQ(stats_without_timings(a / "stats.csv"), stats_without_timings(b / "stats.csv"));
  EXPECT_EQ(deterministic_totals(a / "summary.json"), deterministic_totals(b / "summary.json"));
}

}  // namespace
}  // namespace sluice
