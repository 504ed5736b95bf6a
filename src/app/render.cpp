// `sluice render`, `still`, `compare` and `bench-render`: the simulation's frames as
// images through the headless renderer, the MP4, image comparison, renderer timing.
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
#include "app/run.h"
#include "io/output.h"
#include "render/frame.h"
#include "render/image.h"
#include "render/video.h"
#include "scene/scene.h"
#include "sim/simulation.h"

namespace sluice::app {

namespace fs = std::filesystem;
using namespace sluice::render;

namespace {

// A mistake in a command-line flag; main reports it with exit status 1.
std::runtime_error usage(const std::string& flag, const std::string& value, const std::string& allowed) {
  return std::runtime_error(flag + " " + value + ": " + allowed);
}

void parse_resolution(const std::string& s, int& w, int& h) {
  char x = 0, extra = 0;
  if (std::sscanf(s.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w < 2 || h < 2 ||
      w > 16384 || h > 16384)
    throw usage("--resolution", s, "expected WxH with 2 <= W, H <= 16384, e.g. 1280x720");
}

bool parse_pair(const std::string& s, double& a, double& b) {
  const size_t colon = s.find(':');
  if (colon == std::string::npos) return false;
  try {
    size_t n1 = 0, n2 = 0;
    a = std::stod(s.substr(0, colon), &n1);
    b = std::stod(s.substr(colon + 1), &n2);
    return n1 == colon && n2 == s.size() - colon - 1;
  } catch (const std::exception&) {
    return false;
  }
}

enum class Field { cfl, speed, pressure, density_error };

Field parse_field(const std::string& s) {
  if (s == "cfl") return Field::cfl;
  if (s == "speed") return Field::speed;
  if (s == "pressure") return Field::pressure;
  if (s == "density_error") return Field::density_error;
  throw usage("--color-by", s, "allowed: cfl, speed, pressure, density_error");
}

const char* field_label(Field f) {
  switch (f) {
    case Field::cfl: return "CFL";
    case Field::speed: return "SPEED M/S";
    case Field::pressure: return "PRESSURE PA M";
    case Field::density_error: return "DENSITY ERROR %";
  }
  return "";
}

// Everything the image flags resolve to.
struct ImageConfig {
  FrameSettings frame;
  Field field = Field::cfl;
  double lo = 0, hi = 1;  // colour range, fixed for the run
};

// The automatic colour range: fixed for the whole run (no flicker between frames) and
// derived from the scene's scales. H is the fluid's height at t = 0: sqrt(2 g H) is the
// speed of a free fall from the top of the fluid, rho0 g H the hydrostatic pressure at
// its bottom (2D pressure, Pa*m). CFL: 0..1, the stability scale of Eq. 14.
void automatic_range(Field f, const Scene& scene, double& lo, double& hi) {
  double ymin = scene.fluid_x.front().y(), ymax = ymin;
  for (const Vec2& p : scene.fluid_x) {
    ymin = std::min(ymin, p.y());
    ymax = std::max(ymax, p.y());
  }
  const double height = ymax - ymin + scene.spacing, g = scene.solver.gravity.norm();
  double vmax0 = 0;
  for (const Vec2& v : scene.fluid_v) vmax0 = std::max(vmax0, v.norm());
  lo = 0;
  switch (f) {
    case Field::cfl: hi = 1; break;
    case Field::speed: hi = std::max(std::sqrt(2 * g * height), vmax0); break;
    case Field::pressure: hi = scene.solver.rest_density * g * height; break;
    case Field::density_error: hi = 1; break;
  }
  if (!(hi > 0)) hi = 1;  // no gravity and no motion: any scale
}

ImageConfig resolve_image(const ImageOptions& o, const Scene& scene) {
  const RenderSettings& rs = scene.render;
  ImageConfig c;
  if (o.resolution.empty()) {
    c.frame.width = rs.width;
    c.frame.height = rs.height;
  } else {
    parse_resolution(o.resolution, c.frame.width, c.frame.height);
  }
  c.field = parse_field(o.color_by.empty() ? rs.color_by : o.color_by);
  const std::string cmap_name = o.colormap.empty() ? rs.colormap : o.colormap;
  const auto cmap = parse_colormap(cmap_name);
  if (!cmap) throw usage("--colormap", cmap_name, "allowed: spectrum, viridis, turbo");
  c.frame.colormap = *cmap;
  const auto egl = parse_egl_platform(o.egl);
  if (!egl) throw usage("--egl", o.egl, "allowed: auto, surfaceless, device");
  c.frame.egl = *egl;
  if (o.msaa != 0 && o.msaa != 4) throw usage("--msaa", std::to_string(o.msaa), "allowed: 0 or 4");
  c.frame.msaa = o.msaa;
  if (o.range == "auto" || (o.range.empty() && !rs.fixed_range)) {
    automatic_range(c.field, scene, c.lo, c.hi);
  } else if (o.range.empty()) {
    c.lo = rs.range_lo;
    c.hi = rs.range_hi;
  } else if (!parse_pair(o.range, c.lo, c.hi) || !(c.hi > c.lo)) {
    throw usage("--range", o.range, "expected lo:hi with lo < hi, e.g. 0:1, or auto");
  }
  c.frame.field_label = field_label(c.field);
  c.frame.colorbar = !o.no_colorbar;
  c.frame.overlay = !o.no_overlay;
  const Vec2 lo = rs.fixed_view ? rs.view_min : scene.bounds_min, hi = rs.fixed_view ? rs.view_max : scene.bounds_max;
  c.frame.fit_margin = !rs.fixed_view;
  c.frame.bounds_min[0] = lo.x();
  c.frame.bounds_min[1] = lo.y();
  c.frame.bounds_max[0] = hi.x();
  c.frame.bounds_max[1] = hi.y();
  return c;
}

std::span<const double> as_doubles(const std::vector<Vec2>& v) {
  return {v.empty() ? nullptr : v.front().data(), 2 * v.size()};
}

// Per-frame particle arrays of a simulation, in the renderer's terms.
class FrameBuilder {
 public:
  FrameBuilder(const ImageConfig& c, const Simulation& sim) : c_(c) {
    // The simulation keeps boundary samples in its own (spatial) order.
    const BoundaryParticles& b = sim.boundary();
    moving_.assign(b.moving.begin(), b.moving.end());
  }

  FrameData build(const Simulation& sim, Index frame, const StepStats* last) {
    const Scene& scene = sim.scene();
    const FluidParticles& f = sim.fluid();
    const double dt = last ? last->dt : (scene.time.dt > 0 ? scene.time.dt : scene.time.dt_max);
    const double rho0 = scene.solver.rest_density;
    values_.resize(f.x.size());
    for (size_t i = 0; i < values_.size(); ++i) {
      double v = 0;
      switch (c_.field) {
        case Field::cfl: v = f.v[i].norm() * dt / scene.spacing; break;
        case Field::speed: v = f.v[i].norm(); break;
        case Field::pressure: v = f.p[i]; break;
        case Field::density_error: v = std::max(f.rho[i] / rho0 - 1.0, 0.0) * 100.0; break;
      }
      values_[i] = static_cast<float>(v);
    }
    FrameData d;
    d.fluid_xy = as_doubles(f.x);
    d.fluid_value = values_;
    d.boundary_xy = as_doubles(sim.boundary().x);
    d.boundary_moving = moving_;
    d.diameter = scene.spacing;
    d.lo = c_.lo;
    d.hi = c_.hi;
    char buf[160];
    std::snprintf(buf, sizeof buf, "T = %.3f S   FRAME %d   STEP %ld   ITER %d", sim.time(), frame, sim.steps(),
                  last ? last->iterations : 0);
    d.overlay = buf;
    return d;
  }

 private:
  const ImageConfig& c_;
  std::vector<std::uint8_t> moving_;
  std::vector<float> values_;
};

std::string frame_file(Index frame) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "frame_%05d.png", frame);
  return buf;
}

// PNG encoding of frame k overlaps the simulation of frame k + 1 (one write in flight).
class FrameWriter {
 public:
  void write(std::string path, Image img) {
    wait();
    pending_ = std::async(std::launch::async, [path = std::move(path), img = std::move(img)] { write_png(path, img); });
  }
  void wait() {
    if (pending_.valid()) pending_.get();
  }
  ~FrameWriter() {
    if (pending_.valid()) pending_.wait();
  }

 private:
  std::future<void> pending_;
};

}  // namespace

int run_render(const RenderOptions& o) {
  set_threads(o.threads);
  std::vector<std::string> overrides = o.set;
  if (o.duration > 0) overrides.push_back("time.duration=" + std::to_string(o.duration));
  if (o.fps > 0) overrides.push_back("time.fps=" + std::to_string(o.fps));
  Scene scene = load_scene(o.scene, overrides);

  Index first = 0, last = std::numeric_limits<Index>::max();
  if (!o.frames.empty()) {
    double a = 0, b = 0;
    if (!parse_pair(o.frames, a, b) || a < 0 || b < a || a != std::floor(a) || b != std::floor(b))
      throw usage("--frames", o.frames, "expected A:B, whole frame numbers with 0 <= A <= B");
    first = static_cast<Index>(a);
    last = static_cast<Index>(b);
    // Stop the run at frame B: no need to simulate what is not rendered.
    const double end = b / scene.time.fps;
    if (end < scene.time.duration && end > 0) {
      overrides.push_back("time.duration=" + std::to_string(end));
      scene = load_scene(o.scene, overrides);
    }
  }
  const ImageConfig config = resolve_image(o.image, scene);
  if (!o.no_video && (config.frame.width % 2 != 0 || config.frame.height % 2 != 0))
    throw usage("--resolution", o.image.resolution, "H.264 (yuv420p) needs even width and height; or pass --no-video");
  const fs::path dir = o.output_dir.empty() ? fs::path(scene.output.directory) : fs::path(o.output_dir);
  const fs::path frames_dir = dir / "frames";
  make_directory(frames_dir);

  FrameRenderer renderer(config.frame);  // before the run: EGL problems show at once
  if (!o.quiet)
    std::fprintf(stderr, "sluice: rendering %dx%d with %s\n", config.frame.width, config.frame.height,
                 renderer.description().c_str());
  std::unique_ptr<FrameBuilder> builder;
  FrameWriter writer;
  Image image;
  Index rendered = 0;
  double ms_render = 0;
  auto on_frame = [&](const Simulation& sim, Index frame, const StepStats* st) {
    if (frame < first || frame > last) return;
    const auto t0 = std::chrono::steady_clock::now();
    if (!builder) builder = std::make_unique<FrameBuilder>(config, sim);
    renderer.render(builder->build(sim, frame, st), image);
    writer.write((frames_dir / frame_file(frame)).string(), image);
    ms_render += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    ++rendered;
  };
  run_scene(scene, dir, o.quiet, on_frame);
  writer.wait();
  if (!o.quiet)
    std::fprintf(stderr, "sluice: %d frames in %s (render + read-back %.1f ms per frame; PNG encoding overlapped)\n",
                 rendered, frames_dir.c_str(), rendered ? ms_render / rendered : 0.0);
  if (o.no_video || rendered == 0) return 0;

  VideoJob job;
  job.frames_pattern = (frames_dir / "frame_%05d.png").string();
  job.start_number = first;
  job.fps = scene.time.fps;
  job.output = (dir / (scene.name + ".mp4")).string();
  job.log = (dir / "ffmpeg.log").string();
  try {
    encode_video(job);
  } catch (const VideoError& e) {
    std::fprintf(stderr, "sluice: video error: %s\nsluice: the frames are kept in %s\n", e.what(), frames_dir.c_str());
    return 5;
  }
  if (!o.quiet) std::fprintf(stderr, "sluice: wrote %s\n", job.output.c_str());
  return 0;
}

int run_still(const StillOptions& o) {
  set_threads(o.threads);
  if (!(o.time >= 0)) throw usage("--time", std::to_string(o.time), "must be >= 0");
  std::vector<std::string> overrides = o.set;
  if (o.time > 0) overrides.push_back("time.duration=" + std::to_string(o.time));
  const Scene scene = load_scene(o.scene, overrides);
  const ImageConfig config = resolve_image(o.image, scene);
  const fs::path out = o.output.empty() ? fs::path(scene.output.directory) / "still.png" : fs::path(o.output);
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

int run_compare(const CompareOptions& o) {
  const Image a = read_png(o.a), b = read_png(o.b);
  const CompareResult r = compare_images(a, b, o.tolerance, o.max_fraction);
  if (!r.same_size) {
    std::printf("%s is %dx%d, %s is %dx%d: sizes differ\n", o.a.c_str(), a.width, a.height, o.b.c_str(), b.width,
                b.height);
    return 1;
  }
  std::printf("%s vs %s: %ld of %ld pixels (%.4f%%) differ by more than %d levels; largest difference %d: %s\n",
              o.a.c_str(), o.b.c_str(), r.differing, r.total, 100.0 * r.differing / std::max(1L, r.total), o.tolerance,
              r.max_difference, r.passed ? "match" : "DIFFER");
  if (!o.diff.empty() && r.differing > 0) {
    write_png(o.diff, diff_image(a, b, o.tolerance));
    std::printf("diff image: %s\n", o.diff.c_str());
  }
  return r.passed ? 0 : 1;
}

int run_bench_render(const BenchRenderOptions& o) {
  const auto egl = parse_egl_platform(o.egl);
  if (!egl) throw usage("--egl", o.egl, "allowed: auto, surfaceless, device");
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
      const double h = 1.0 / side;
      std::vector<double> xy;
      std::vector<float> val;
      xy.reserve(2 * n);
      for (long k = 0; k < n; ++k) {
        xy.push_back((k % side + 0.5) * h);
        xy.push_back((k / side + 0.5) * h);
        val.push_back(static_cast<float>((k % side) / double(side)));
      }
      fs_.bounds_min[0] = fs_.bounds_min[1] = 0;
      fs_.bounds_max[0] = fs_.bounds_max[1] = 1;
      FrameRenderer r(fs_);
      device = r.description();
      FrameData d;
      d.fluid_xy = xy;
      d.fluid_value = val;
      d.diameter = h;
      d.overlay = "T = 1.000 S   FRAME 30   STEP 1000   ITER 5";
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
                r.annotate, r.png, r.total, r.png_bytes / 1024.0);
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
