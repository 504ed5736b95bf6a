// Checkpoints during a run and `--resume DIR` for `simulate` and `render`.
#include "app/resume.h"

#include <chrono>
#include <cstdio>
#include <fstream>

namespace sluice::app {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

fs::path record_path(const fs::path& dir) { return checkpoint_directory(dir) / "run.json"; }

// The scene as an absolute path, so that --resume works from any directory.
std::string absolute_scene(const std::string& scene) {
  std::error_code ec;
  const fs::path p = fs::absolute(scene, ec);
  return ec ? scene : p.lexically_normal().string();
}

// DIR/checkpoints/run.json of a run of `command`.
json read_record(const std::string& dir, const std::string& command) {
  const fs::path path = record_path(dir);
  std::ifstream in(path);
  if (!in)
    throw CheckpointError(path.string() + " cannot be read: " + dir + " holds no run started with --checkpoint-every");
  json r;
  try {
    r = json::parse(in);
  } catch (const json::exception& e) {
    throw CheckpointError(path.string() + " is not valid JSON: " + e.what());
  }
  const std::string written_by = r.value("command", std::string());
  if (written_by != command)
    throw CheckpointError(dir + " holds a run of `sluice " + written_by + "`; resume it with `sluice " + written_by +
                          " --resume " + dir + "`");
  return r;
}

// Reads the recorded fields; a missing or mistyped one names the file.
template <class F>
void from_record(const std::string& dir, F&& read) {
  try {
    read();
  } catch (const json::exception& e) {
    throw CheckpointError(record_path(dir).string() + " is malformed: " + e.what());
  }
}

}  // namespace

json run_record(const SimulateOptions& o) {
  return {{"command", "simulate"}, {"scene", absolute_scene(o.scene)},      {"duration", o.duration}, {"set", o.set},
          {"exports", o.exports},  {"checkpoint_every", o.checkpoint_every}};
}

json run_record(const RenderOptions& o) {
  const ImageOptions& i = o.image;
  return {{"command", "render"},
          {"scene", absolute_scene(o.scene)},
          {"fps", o.fps},
          {"duration", o.duration},
          {"frames", o.frames},
          {"image",
           {{"resolution", i.resolution},
            {"color_by", i.color_by},
            {"colormap", i.colormap},
            {"range", i.range},
            {"no_overlay", i.no_overlay},
            {"overlay", i.overlay},
            {"title", i.title},
            {"particle_scale", i.particle_scale},
            {"background", i.background},
            {"object_colors", i.object_colors},
            {"no_colorbar", i.no_colorbar},
            {"msaa", i.msaa},
            {"egl", i.egl}}},
          {"no_video", o.no_video},
          {"format", o.format},
          {"crf", o.crf},
          {"frame_pattern", o.frame_pattern},
          {"exports", o.exports},
          {"set", o.set},
          {"checkpoint_every", o.checkpoint_every}};
}

SimulateOptions resumed_options(const SimulateOptions& given) {
  const json r = read_record(given.resume, "simulate");
  SimulateOptions o = given;
  o.output_dir = given.resume;
  from_record(given.resume, [&] {
    if (o.scene.empty()) o.scene = r.at("scene").get<std::string>();
    o.duration = r.at("duration").get<double>();
    o.set = r.at("set").get<std::vector<std::string>>();
    o.exports = r.at("exports").get<std::vector<std::string>>();
    if (o.checkpoint_every <= 0) o.checkpoint_every = r.at("checkpoint_every").get<int>();
  });
  return o;
}

RenderOptions resumed_options(const RenderOptions& given) {
  const json r = read_record(given.resume, "render");
  RenderOptions o = given;
  o.output_dir = given.resume;
  from_record(given.resume, [&] {
    if (o.scene.empty()) o.scene = r.at("scene").get<std::string>();
    o.fps = r.at("fps").get<double>();
    o.duration = r.at("duration").get<double>();
    o.frames = r.at("frames").get<std::string>();
    const json& i = r.at("image");
    o.image.resolution = i.at("resolution").get<std::string>();
    o.image.color_by = i.at("color_by").get<std::string>();
    o.image.colormap = i.at("colormap").get<std::string>();
    o.image.range = i.at("range").get<std::string>();
    o.image.no_overlay = i.at("no_overlay").get<bool>();
    // Added later: records of older runs lack them and take the defaults.
    o.image.overlay = i.value("overlay", std::string());
    o.image.title = i.value("title", std::string());
    o.image.particle_scale = i.value("particle_scale", 1.0);
    o.image.background = i.value("background", std::string());
    o.image.object_colors = i.value("object_colors", std::vector<std::string>());
    o.image.no_colorbar = i.at("no_colorbar").get<bool>();
    o.image.msaa = i.at("msaa").get<int>();
    o.image.egl = i.at("egl").get<std::string>();
    o.no_video = r.at("no_video").get<bool>();
    o.format = r.value("format", std::string("mp4"));
    o.crf = r.value("crf", -1);
    o.frame_pattern = r.value("frame_pattern", std::string("frame_%05d.png"));
    o.exports = r.value("exports", std::vector<std::string>());
    o.set = r.at("set").get<std::vector<std::string>>();
    if (o.checkpoint_every <= 0) o.checkpoint_every = r.at("checkpoint_every").get<int>();
  });
  return o;
}

RunControl make_run_control(const std::string& resume, int checkpoint_every, const json& record, const fs::path& dir,
                            const Scene& scene, bool quiet) {
  RunControl c;
  c.checkpoint_every = checkpoint_every;
  if (resume.empty()) {
    if (checkpoint_every > 0) c.record = record;
    return c;
  }
  c.resume = load_newest_checkpoint(dir, scene_hash(scene));
  const LoadedCheckpoint& loaded = *c.resume;
  for (const std::string& why : loaded.rejected)
    std::fprintf(stderr, "sluice: warning: %s; falling back to an older checkpoint\n", why.c_str());
  // Refused checkpoints newer than the one restored would otherwise stay "newest" and
  // push the resumed run's own checkpoints out of the two kept.
  for (const fs::path& f : list_checkpoints(dir)) {
    if (f == loaded.file) break;
    std::error_code ec;
    fs::rename(f, f.string() + ".rejected", ec);
    if (ec)
      std::fprintf(stderr, "sluice: warning: cannot set %s aside: %s\n", f.c_str(), ec.message().c_str());
    else
      std::fprintf(stderr, "sluice: warning: set %s aside as %s.rejected\n", f.c_str(), f.c_str());
  }
  if (!quiet) {
    const SimulationState& s = loaded.checkpoint.state;
    std::fprintf(stderr, "sluice: resuming %s from %s (frame %d, t = %.4f s, step %ld)\n", dir.c_str(),
                 loaded.file.c_str(), s.frame, s.time, s.step);
  }
  return c;
}

const StepStats* resume_run(Simulation& sim, RunTotals& totals, const fs::path& dir, const LoadedCheckpoint& loaded) {
  try {
    sim.restore(loaded.checkpoint.state);
  } catch (const std::invalid_argument& e) {
    throw CheckpointError("checkpoint " + loaded.file.string() + " does not fit this scene: " + e.what());
  }
  totals = loaded.checkpoint.totals;
  // The rows continue in stats.csv.tmp (StatsCsv renames it when the run ends): a run
  // that was killed left its rows there; one that stopped or finished, under the real name.
  const fs::path csv = dir / "stats.csv", tmp = dir / "stats.csv.tmp";
  std::error_code ec;
  if (!fs::exists(tmp, ec) && fs::exists(csv, ec)) {
    fs::rename(csv, tmp, ec);
    if (ec) throw OutputError(csv.string() + ": cannot move aside to continue its rows: " + ec.message());
  }
  truncate_stats_csv(tmp, loaded.checkpoint.state.step);
  return &loaded.checkpoint.last_step;
}

json resume_summary(const LoadedCheckpoint& loaded) {
  const SimulationState& s = loaded.checkpoint.state;
  return {{"file", loaded.file.string()}, {"frame", s.frame}, {"step", s.step}, {"time", s.time}};
}

Checkpointer::Checkpointer(const Scene& scene, const fs::path& dir, const RunControl& control)
    : dir_(dir), every_(control.checkpoint_every) {
  if (!control.resume) {
    // A fresh run replaces the previous run in DIR: its checkpoints, left in place,
    // would be newer than this run's own and --resume would pick them.
    std::error_code ec;
    for (const fs::path& f : list_checkpoints(dir)) fs::remove(f, ec);
    fs::remove(record_path(dir), ec);
  }
  if (every_ <= 0) return;
  hash_ = scene_hash(scene);
  if (!control.record.is_null()) {
    make_directory(checkpoint_directory(dir));
    write_file_atomic(record_path(dir).string(), control.record.dump(2) + "\n");
  }
}

void Checkpointer::at_frame(const Simulation& sim, const StepStats& st, const RunTotals& totals, double wall_seconds) {
  if (every_ <= 0 || st.frame < 0 || st.frame % every_ != 0 || sim.finished()) return;
  const auto t0 = std::chrono::steady_clock::now();
  Checkpoint c{sim.state(), totals, st};
  c.totals.wall_seconds = wall_seconds;
  last_bytes_ = write_checkpoint(dir_, c, hash_);
  ++written_;
  ms_ += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

json Checkpointer::summary() const {
  return {{"every_frames", every_},
          {"written", written_},
          {"bytes", last_bytes_},
          {"ms_per_checkpoint", written_ ? ms_ / static_cast<double>(written_) : 0.0}};
}

}  // namespace sluice::app
