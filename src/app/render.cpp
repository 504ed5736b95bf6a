// `sluice render`, `still` and `bench-render`: the simulation's frames as images through
// the headless renderer, the video, renderer timing.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <future>
#include <memory>
#include <stdexcept>

#include "app/commands.h"
#include "app/interrupt.h"
#include "app/output_dir.h"
#include "app/resume.h"
#include "app/run.h"
#include "io/output.h"
#include "render/frame.h"
#include "render/image.h"
#include "render/video.h"
#include "scene/scene.h"
#include "solver/simulation.h"
#include "view/scene_view.h"

namespace sluice::app {

namespace fs = std::filesystem;
using namespace sluice::render;
using namespace sluice::view;

namespace {

// The frame names of --frame-pattern: one integer conversion (%d or %0Nd, N <= 9), a
// .png name without a folder; ffmpeg reads the same pattern back. Throws FlagError.
void check_frame_pattern(const std::string& p) {
  const char* allowed =
      "expected a PNG file name with one %d or %0Nd (N <= 9) for the frame number, e.g. frame_%05d.png";
  const size_t pct = p.find('%');
  if (pct == std::string::npos || p.find('/') != std::string::npos || !p.ends_with(".png"))
    throw FlagError("--frame-pattern", p, allowed);
  size_t k = pct + 1;
  if (k < p.size() && p[k] == '0') {
    ++k;
    if (k < p.size() && p[k] >= '1' && p[k] <= '9')
      ++k;
    else
      throw FlagError("--frame-pattern", p, allowed);
  }
  if (k >= p.size() || p[k] != 'd' || p.find('%', k) != std::string::npos)
    throw FlagError("--frame-pattern", p, allowed);
}

std::string frame_file(const std::string& pattern, Index frame) {
  char buf[512];
  std::snprintf(buf, sizeof buf, pattern.c_str(), frame);  // checked by check_frame_pattern
  return buf;
}

std::string read_text_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// An -o that names a folder: the PNG would be written beside it as FOLDER.tmp and fail.
void check_png_path(const fs::path& out) {
  std::error_code ec;
  if (fs::is_directory(out, ec)) throw OutputError(out.string() + ": is a directory; -o takes the PNG file to write");
}

// --format and --crf: the container and the encoder's quality, checked before the run.
VideoFormat video_format(const RenderOptions& o) {
  VideoFormat f = VideoFormat::mp4;
  if (!parse_video_format(o.format, f)) throw FlagError("--format", o.format, "allowed: mp4, webm, gif");
  if (o.crf >= 0 && max_crf(f) < 0)
    throw FlagError("--crf", std::to_string(o.crf), "GIF has no CRF; --crf applies to --format mp4 and webm");
  if (o.crf > max_crf(f))
    throw FlagError("--crf", std::to_string(o.crf),
                    std::string("allowed for ") + extension(f) + ": 0 (best) to " + std::to_string(max_crf(f)));
  return f;
}

// PNG encoding of frame k overlaps the simulation of frame k + 1 (one write in flight).
// written() counts the PNGs completed, for summary.json (not a frame whose write failed).
class FrameWriter {
 public:
  void write(std::string path, Image img) {
    wait();
    pending_ = std::async(std::launch::async, [path = std::move(path), img = std::move(img)] {
      const auto t0 = std::chrono::steady_clock::now();
      write_png(path, img);
      return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    });
  }
  void wait() {
    if (!pending_.valid()) return;
    const auto t0 = std::chrono::steady_clock::now();
    encode_seconds_ += pending_.get();
    wait_seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ++written_;
  }
  long written() const { return written_; }
  double encode_seconds() const { return encode_seconds_; }  // PNG encoding, on its own thread
  double wait_seconds() const { return wait_seconds_; }      // the run waiting for it
  ~FrameWriter() {
    if (pending_.valid()) pending_.wait();
  }

 private:
  std::future<double> pending_;
  long written_ = 0;
  double encode_seconds_ = 0, wait_seconds_ = 0;
};

// Where a render's wall time went (DIR/timing.json; `sluice bench --end-to-end` reads it).
struct RenderTiming {
  double total = 0, simulation = 0, drawing = 0, png = 0, png_wait = 0, exports = 0, video = 0;
  long frames = 0;
};

void write_timing(const fs::path& dir, const RenderTiming& t) {
  const nlohmann::json j = {{"frames", t.frames},     {"total_s", t.total}, {"simulation_s", t.simulation},
                            {"drawing_s", t.drawing}, {"png_s", t.png},     {"png_wait_s", t.png_wait},
                            {"exports_s", t.exports}, {"video_s", t.video}};
  write_file_atomic((dir / "timing.json").string(), j.dump(2) + "\n");
}

// The frame index of `scene`'s end, as Simulation::frame_count() counts it.
Index last_frame_of(const Scene& scene) {
  return static_cast<Index>(std::ceil(scene.time.duration * scene.time.fps - 1e-9));
}

// The video was stopped by a signal after the run completed: summary.json says so and how
// to make the video from the frames that are all there.
[[noreturn]] void video_interrupted(const fs::path& dir, const VideoJob& job, int signal) {
  std::vector<std::string> args = ffmpeg_arguments(job);
  args.back() = job.output;
  const std::string message = "interrupted by " + signal_name(signal) + " while ffmpeg encoded " + job.output +
                              "; the run is complete and its frames are kept in " + (dir / "frames").string() +
                              "; make the video with: " + command_line(args);
  const fs::path path = dir / "summary.json";
  nlohmann::json summary = nlohmann::json::parse(read_text_file(path), nullptr, false);
  if (summary.is_object()) {
    summary["status"] = "interrupted";
    summary["message"] = message;
    summary["interrupted"] = {{"signal", signal_name(signal)}, {"while", "encoding the video"}, {"resume", nullptr}};
    write_file_atomic(path.string(), summary.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n");
  }
  throw Interrupted(signal, message);
}

}  // namespace

int run_render(const RenderOptions& given) {
  const auto start = std::chrono::steady_clock::now();
  auto since = [](std::chrono::steady_clock::time_point t) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
  };
  const RenderOptions o = given.resume.empty() ? given : resumed_options(given);
  set_threads(o.threads);
  std::vector<std::string> overrides = o.set;
  if (o.duration > 0) overrides.push_back(number_override("time.duration", o.duration));
  if (o.fps > 0) overrides.push_back(number_override("time.fps", o.fps));
  if (!o.exports.empty()) overrides.push_back(export_override(o.exports));
  Scene scene = load_scene(o.scene, overrides);

  Index first = 0, last = std::numeric_limits<Index>::max();
  if (!o.frames.empty()) {
    double a = 0, b = 0;
    if (!parse_pair(o.frames, a, b) || a < 0 || b < a || a != std::floor(a) || b != std::floor(b))
      throw FlagError("--frames", o.frames, "expected A:B, whole frame numbers with 0 <= A <= B");
    // Frames the run never reaches would render nothing and still report success.
    const Index end_frame = last_frame_of(scene);
    if (b > end_frame)
      throw FlagError("--frames", o.frames,
                      "the scene's last frame is " + std::to_string(end_frame) + " (time.duration " +
                          number_text(scene.time.duration) + " s at " + number_text(scene.time.fps) +
                          " frames/s); allowed: 0 <= A <= B <= " + std::to_string(end_frame));
    first = static_cast<Index>(a);
    last = static_cast<Index>(b);
    // Stop the run at frame B: no need to simulate what is not rendered.
    const double end = b / scene.time.fps;
    if (end < scene.time.duration && end > 0) {
      overrides.push_back(number_override("time.duration", end));
      scene = load_scene(o.scene, overrides);
    }
  }
  const ImageConfig config = resolve_image(o.image, scene);
  const VideoFormat format = video_format(o);
  check_frame_pattern(o.frame_pattern);
  if (!o.no_video && format != VideoFormat::gif && (config.frame.width % 2 != 0 || config.frame.height % 2 != 0))
    throw FlagError("--resolution", o.image.resolution,
                    std::string(format == VideoFormat::mp4 ? "H.264" : "VP9") +
                        " (yuv420p) needs even width and height; or pass --no-video or --format gif");
  const fs::path dir = o.output_dir.empty() ? fs::path(scene.output.directory) : fs::path(o.output_dir);
  const fs::path frames_dir = dir / "frames";
  // A resumed run continues the run in `dir`; a fresh one must not mix with an old one.
  if (o.resume.empty()) prepare_output_directory(dir, o.overwrite, scene.name, scene.file);
  make_directory(frames_dir);

  FrameRenderer renderer(config.frame);  // before the run: EGL problems show at once
  if (!o.quiet)
    std::fprintf(stderr, "sluice: rendering %dx%d with %s\n", config.frame.width, config.frame.height,
                 renderer.description().c_str());
  std::unique_ptr<FrameBuilder> builder;
  FrameWriter writer;
  Image image;
  Index rendered = 0;
  RenderTiming timing;
  double frame_seconds = 0;  // in the frame callback, all of it
  catch_interrupts();
  RunControl control = make_run_control(o.resume, o.checkpoint_every, run_record(o), dir, scene, o.quiet);
  control.threads_fixed = o.threads > 0 || std::getenv("OMP_NUM_THREADS") != nullptr;
  control.command = "render";
  // Exports of the frames rendered, as `simulate` writes them.
  ParticleExporter exporter = make_exporter(scene, dir, control, first, last);
  auto on_frame = [&](const Simulation& sim, Index frame, const StepStats* st) {
    if (frame < first || frame > last) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (!builder) builder = std::make_unique<FrameBuilder>(config, sim);
    renderer.render(builder->build(sim, frame, st), image);
    timing.drawing += since(t0);
    writer.write((frames_dir / frame_file(o.frame_pattern, frame)).string(), image);
    ++rendered;
    const auto t1 = std::chrono::steady_clock::now();
    exporter.write(frame, sim.time(), sim.fluid(), sim.boundary());
    timing.exports += since(t1);
    frame_seconds += since(t0);
  };
  // A resumed run's PNGs before the checkpoint's frame were written by the earlier run.
  const long earlier =
      control.resume ? std::max<long>(0, std::min<long>(last, control.resume->checkpoint.state.frame - 1) - first + 1)
                     : 0;
  const auto run_start = std::chrono::steady_clock::now();
  run_scene(scene, dir, o.quiet, on_frame, control,
            FrameOutput{[&] { writer.wait(); }, [&] { return earlier + writer.written(); }});
  timing.simulation = since(run_start) - frame_seconds;
  timing.frames = rendered;
  timing.png = writer.encode_seconds();
  timing.png_wait = writer.wait_seconds();
  auto finish_timing = [&] {
    timing.total = since(start);
    write_timing(dir, timing);
  };
  if (!o.quiet)
    std::fprintf(stderr, "sluice: %d frames in %s (render + read-back %.1f ms per frame; PNG encoding overlapped)\n",
                 rendered, frames_dir.c_str(), rendered ? 1000 * timing.drawing / rendered : 0.0);
  if (o.no_video || rendered == 0) {
    finish_timing();
    return 0;
  }

  VideoJob job;
  job.frames_pattern = (frames_dir / o.frame_pattern).string();
  job.start_number = first;
  job.fps = scene.time.fps;
  job.format = format;
  job.crf = o.crf;
  job.output = (dir / (scene.name + "." + extension(format))).string();
  job.log = (dir / "ffmpeg.log").string();
  job.cancelled = [] { return interrupt_signal() != 0; };
  const auto video_start = std::chrono::steady_clock::now();
  try {
    encode_video(job);
    timing.video = since(video_start);
  } catch (const VideoInterrupted&) {
    video_interrupted(dir, job, interrupt_signal());
  } catch (const VideoError& e) {
    // One line: the cause, then where the work done so far is.
    throw VideoError(std::string(e.what()) + "; the frames are kept in " + frames_dir.string());
  }
  if (!o.quiet) std::fprintf(stderr, "sluice: wrote %s\n", job.output.c_str());
  finish_timing();
  return 0;
}

int run_still(const StillOptions& o) {
  set_threads(o.threads);
  if (!(o.time >= 0)) throw FlagError("--time", std::to_string(o.time), "must be >= 0");
  std::vector<std::string> overrides = o.set;
  // The time is checked against the scene as it is (as montage checks its times): a
  // still after the scene's end is a mistake in --time, not in time.duration.
  const double duration = load_scene(o.scene, overrides).time.duration;
  if (o.time > duration)
    throw FlagError("--time", number_text(o.time),
                    "the time is after the scene's end; allowed: 0 to time.duration = " + number_text(duration) + " s");
  if (o.time > 0 && o.time < kMinDuration)
    throw FlagError("--time", number_text(o.time),
                    "allowed: 0, or " + number_text(kMinDuration) + " s to time.duration");
  if (o.time > 0) overrides.push_back(number_override("time.duration", o.time));
  const Scene scene = load_scene(o.scene, overrides);
  const ImageConfig config = resolve_image(o.image, scene);
  const fs::path out = o.output.empty() ? fs::path(scene.output.directory) / "still.png" : fs::path(o.output);
  check_png_path(out);
  check_memory(scene);
  if (out.has_parent_path()) make_directory(out.parent_path());
  FrameRenderer renderer(config.frame);
  Simulation sim(scene);
  FrameBuilder builder(config, sim);
  StepStats st;
  bool stepped = false;
  while (o.time > 0 && !sim.finished()) {
    st = sim.step();
    stepped = true;
  }
  Image image;
  renderer.render(builder.build(sim, sim.frame(), stepped ? &st : nullptr), image);
  write_png(out.string(), image);
  std::fprintf(stderr, "sluice: t = %.4f s after %ld steps: wrote %s\n", sim.time(), sim.steps(), out.c_str());
  return 0;
}

int run_bench_render(const BenchRenderOptions& o) {
  const auto egl = parse_egl_platform(o.egl);
  if (!egl) throw FlagError("--egl", o.egl, "allowed: auto, surfaceless, device");
  struct Row {
    std::string resolution;
    long particles;
    double draw, read, annotate, png, total;
    size_t png_bytes;
  };
  std::vector<Row> rows;
  std::string device;
  for (const std::string& res : o.resolutions) {
    FrameSettings fs_;
    parse_resolution(res, fs_.width, fs_.height);
    fs_.egl = *egl;
    fs_.msaa = o.msaa;
    for (long n : o.particles) {
      // A square block of touching discs in row order, speeds varying across it.
      const long side = std::max(1L, static_cast<long>(std::ceil(std::sqrt(static_cast<double>(n)))));
      const double h = 1.0 / static_cast<double>(side);
      std::vector<double> xy;
      std::vector<float> val;
      xy.reserve(2 * n);
      for (long k = 0; k < n; ++k) {
        xy.push_back((static_cast<double>(k % side) + 0.5) * h);
        xy.push_back((static_cast<double>(k / side) + 0.5) * h);
        val.push_back(static_cast<float>(static_cast<double>(k % side) / double(side)));
      }
      fs_.bounds_min[0] = fs_.bounds_min[1] = 0;
      fs_.bounds_max[0] = fs_.bounds_max[1] = 1;
      FrameRenderer r(fs_);
      device = r.description();
      FrameData d;
      d.fluid_xy = xy;
      d.fluid_value = val;
      d.diameter = h;
      d.overlay = overlay_text(Overlay::full, 1.0, 30, 1000, 5);
      std::vector<double> draw, read, annotate, png;
      size_t bytes = 0;
      Image img;
      for (int rep = 0; rep < o.repeat + 1; ++rep) {  // the first run warms up
        r.render(d, img);
        const auto t0 = std::chrono::steady_clock::now();
        bytes = encode_png(img).size();
        const double ms_png = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        if (rep == 0) continue;
        draw.push_back(r.timings().draw);
        read.push_back(r.timings().read);
        annotate.push_back(r.timings().annotate);
        png.push_back(ms_png);
      }
      auto median = [](std::vector<double> v) {
        std::sort(v.begin(), v.end());
        return v[v.size() / 2];
      };
      Row row{res, n, median(draw), median(read), median(annotate), median(png), 0, bytes};
      row.total = row.draw + row.read + row.annotate + row.png;
      rows.push_back(row);
      std::fprintf(stderr, "  %s %ld particles done\n", res.c_str(), n);
    }
  }
  std::printf("renderer: %s, msaa %d, median of %d frames\n", device.c_str(), o.msaa, o.repeat);
  std::printf("%-10s %10s %9s %9s %9s %9s %9s %9s\n", "resolution", "particles", "draw_ms", "read_ms", "annot_ms",
              "png_ms", "total_ms", "png_kB");
  for (const Row& r : rows)
    std::printf("%-10s %10ld %9.1f %9.1f %9.1f %9.1f %9.1f %9.0f\n", r.resolution.c_str(), r.particles, r.draw, r.read,
                r.annotate, r.png, r.total, static_cast<double>(r.png_bytes) / 1024.0);
  if (!o.csv.empty()) {
    const fs::path p(o.csv);
    if (p.has_parent_path()) make_directory(p.parent_path());
    std::string text = "resolution,particles,draw_ms,read_ms,annotate_ms,png_ms,total_ms,png_bytes\n";
    char buf[256];
    for (const Row& r : rows) {
      std::snprintf(buf, sizeof buf, "%s,%ld,%.3f,%.3f,%.3f,%.3f,%.3f,%zu\n", r.resolution.c_str(), r.particles, r.draw,
                    r.read, r.annotate, r.png, r.total, r.png_bytes);
      text += buf;
    }
    write_file_atomic(o.csv, text);
    std::printf("wrote %s\n", o.csv.c_str());
  }
  return 0;
}

}  // namespace sluice::app
