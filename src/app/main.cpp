// sluice: 2D IISPH / WCSPH fluid simulator. Command-line entry point (CLI11).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "app/commands.h"
#include "app/interrupt.h"
#include "app/run.h"
#include "app/wait_policy.h"
#include "io/checkpoint.h"
#include "io/output.h"
#include "render/image.h"
#include "render/video.h"
#include "scene/scene.h"
#include "solver/simulation.h"

namespace {

// CLI11's PositiveNumber and NonNegativeNumber print the largest double in full when a
// value fails; this check says what is allowed in words. `hi` bounds values that would
// exhaust the machine (e.g. a billion threads).
CLI::Validator number_check(bool integer, double lo, bool lo_open, double hi = HUGE_VAL) {
  std::string allowed = std::string(integer ? "an integer " : "a number ") + (lo_open ? "> " : ">= ") +
                        std::to_string(static_cast<long long>(lo));
  if (hi != HUGE_VAL) allowed += " and <= " + std::to_string(static_cast<long long>(hi));
  return CLI::Validator(
      [=](std::string& text) -> std::string {
        const char* begin = text.c_str();
        char* end = nullptr;
        errno = 0;
        const double v = integer ? static_cast<double>(std::strtoll(begin, &end, 10)) : std::strtod(begin, &end);
        const bool ok = end != begin && *end == '\0' && errno == 0 && std::isfinite(v) && (lo_open ? v > lo : v >= lo) &&
                        v <= hi;
        return ok ? std::string() : "expected " + allowed + ", got '" + text + "'";
      },
      allowed);
}

// CLI11 answers a flag mistake with a usage hint on a second line and exit codes of its
// own (105, 106, 109, ...); sluice answers with one line and exit status 1, like any
// other error that is not the scene's, the output's or the renderer's.
int flag_error(const CLI::App& app, const CLI::ParseError& e) {
  std::string what = e.what();
  std::replace(what.begin(), what.end(), '\n', ' ');
  const auto used = app.get_subcommands();
  const std::string help = used.empty() ? "sluice --help" : "sluice " + used.front()->get_name() + " --help";
  std::fprintf(stderr, "sluice: %s (see %s)\n", what.c_str(), help.c_str());
  // compare's exit status tells a CI script a usage mistake from images that differ.
  return !used.empty() && used.front()->get_name() == "compare" ? sluice::app::kCompareUsage : 1;
}

// --export of `simulate` and `render`: the particle exports at every frame (io/export.h),
// in place of the scene's output.export.
void add_export_option(CLI::App* cmd, std::vector<std::string>& exports) {
  cmd->add_option("--export", exports, "Particle exports at every frame: csv, vtk (VTK XML .vtp and a ParaView .pvd); "
                                       "default: the scene's output.export")
      ->delimiter(',')
      ->check(CLI::IsMember({"csv", "vtk"}));
}

// --checkpoint-every and --resume of `simulate` and `render`. With --resume the scene and
// every flag that shapes the results come from DIR/checkpoints/run.json: only SCENE (a
// moved scene file, checked by its hash), --threads, -q and --checkpoint-every may be
// given again. SCENE is required without --resume.
void add_checkpoint_options(CLI::App* cmd, int& every, std::string& resume, const std::string& scene) {
  cmd->add_option("--checkpoint-every", every, "Write a checkpoint every N frames to DIR/checkpoints (newest two kept)")
      ->check(number_check(true, 1, false));
  CLI::Option* res = cmd->add_option("--resume", resume,
                                     "Continue the interrupted run in DIR from its newest checkpoint, with its scene and flags");
  for (CLI::Option* opt : cmd->get_options()) {
    const std::string name = opt->get_name();
    if (opt != res && name != "scene" && name != "--help" && name != "--threads" && name != "--quiet" &&
        name != "--checkpoint-every")
      res->excludes(opt);
  }
  cmd->callback([cmd, &resume, &scene] {
    if (scene.empty() && resume.empty()) throw CLI::RequiredError(cmd->get_name() + ": SCENE (or --resume DIR)");
  });
}

}  // namespace

int main(int argc, char** argv) {
  using namespace sluice::app;
  set_thread_wait_policy(argv);
  CLI::App app{"sluice: 2D implicit incompressible SPH (IISPH) and WCSPH fluid simulator"};
  app.set_version_flag("--version", SLUICE_VERSION);
  app.require_subcommand(1);
  const CLI::Validator positive = number_check(false, 0, true);
  const CLI::Validator threads = number_check(true, 1, false, 4096);

  SimulateOptions sim;
  CLI::App* simulate = app.add_subcommand("simulate", "Simulate a scene; write stats.csv, summary.json and exports");
  simulate->add_option("scene", sim.scene, "Scene file (JSON); with --resume, the recorded one by default");
  simulate->add_option("-o,--output", sim.output_dir, "Output directory (default: the scene's output.directory)");
  simulate->add_option("--duration", sim.duration, "Simulated seconds (overrides time.duration)")
      ->check(positive);
  simulate->add_option("--threads", sim.threads, "OpenMP threads (default: 1 or all cores, chosen by measuring while it runs)")->check(threads);
  simulate->add_option("--set", sim.set, "Override a scene value: path=value, e.g. solver.tolerance=0.05")
      ->take_all();
  add_export_option(simulate, sim.exports);
  simulate->add_flag("-q,--quiet", sim.quiet, "No progress output");
  simulate->add_flag("--overwrite", sim.overwrite, "Replace a previous run in the output directory");
  add_checkpoint_options(simulate, sim.checkpoint_every, sim.resume, sim.scene);

  BenchOptions bench;
  CLI::App* benchcmd = app.add_subcommand("bench", "Time scenes; print a table and write CSV");
  benchcmd->add_option("scenes", bench.scenes, "Scene files (one in sweep mode; none with --collect)");
  benchcmd->add_option("--steps", bench.steps, "Steps per run (0: the whole duration)")->check(number_check(true, 0, false));
  benchcmd->add_option("--repeat", bench.repeat, "Runs per scene; the median is reported")
      ->check(number_check(true, 1, false));
  benchcmd->add_option("--threads", bench.threads, "OpenMP threads")->check(threads);
  benchcmd->add_option("--set", bench.set, "Override a scene value (applies to every scene)")->take_all();
  benchcmd->add_option("--csv", bench.csv, "CSV output file");
  benchcmd->add_flag("--brute-force", bench.brute_force, "O(n^2) neighbour search instead of the grid");
  benchcmd->add_option("--sweep", bench.sweep, "Sweep a scene value: KEY=V1,V2,... (repeatable; every combination runs)");
  benchcmd->add_option("--duration", bench.duration, "Sweep: simulated seconds per run (overrides time.duration)")
      ->check(positive);
  benchcmd->add_option("-o,--output", bench.output_dir, "Sweep: directory for bench.csv, bench.md, bench.png (default renders/bench/<scene>)");
  benchcmd->add_option("--jobs", bench.jobs, "Sweep: write one command line per run to this file instead of running");
  benchcmd->add_flag("--end-to-end", bench.end_to_end,
                     "Time `render` of one scene (default scenes/dam_break_130k.json, 5 s, 60 fps, 1920x1080) as a whole, split into simulation, drawing, PNG and video");
  benchcmd->add_option("--fps", bench.fps, "End-to-end: frames per second (default 60)")->check(positive);
  benchcmd->add_option("--resolution", bench.resolution, "End-to-end: WxH (default 1920x1080)");
  benchcmd->add_option("--collect", bench.collect, "Merge the bench.csv of these directories into -o DIR")->take_all();

  // Image flags shared by `render` and `still`.
  auto add_image_options = [](CLI::App* cmd, ImageOptions& io) {
    cmd->add_option("--resolution", io.resolution, "Image size WxH (default: the scene's render.resolution, 1280x720; even sizes for video)");
    cmd->add_option("--color-by", io.color_by, "Field: cfl (|v| dt / spacing), speed, pressure, density_error (default: render.color_by, cfl)")
        ->check(CLI::IsMember({"cfl", "speed", "pressure", "density_error"}));
    cmd->add_option("--colormap", io.colormap, "spectrum (blue to red), viridis, turbo (default: render.colormap, spectrum)")
        ->check(CLI::IsMember({"spectrum", "viridis", "turbo"}));
    cmd->add_option("--range", io.range, "Colour range lo:hi, or auto (fixed for the run from the scene: cfl 0:1, speed 0:sqrt(2 g H), pressure 0:rho0 g H, density_error 0:1; default: render.range)");
    cmd->add_option("--overlay", io.overlay, "Overlay line above the scene: full (time, frame, step, iterations; default), time, none")
        ->check(CLI::IsMember({"full", "time", "none"}));
    cmd->add_flag("--no-overlay", io.no_overlay, "The same as --overlay none");
    cmd->add_option("--title", io.title, "Title line above the scene (UTF-8)");
    cmd->add_option("--particle-scale", io.particle_scale, "Disc diameter as a multiple of the particle spacing (default 1; > 0, <= 10)")
        ->check(number_check(false, 0, true, 10));
    cmd->add_option("--background", io.background, "Background colour: #rrggbb or a name (white, black, grey, ...; default white)");
    cmd->add_option("--object-color", io.object_colors, "Colour of a boundary object: NAME=COLOUR (repeatable; default grey walls, slate moving objects)")
        ->take_all();
    cmd->add_flag("--no-colorbar", io.no_colorbar, "No colorbar");
    cmd->add_option("--msaa", io.msaa, "Multisampling: 0 (default) or 4")->check(CLI::IsMember({0, 4}));
    cmd->add_option("--egl", io.egl, "EGL platform: auto (default: surfaceless, then device), surfaceless, device")
        ->check(CLI::IsMember({"auto", "surfaceless", "device"}));
  };

  RenderOptions ren;
  CLI::App* render = app.add_subcommand("render", "Simulate a scene and render PNG frames and a video (MP4, WebM or GIF)");
  render->add_option("scene", ren.scene, "Scene file (JSON); with --resume, the recorded one by default");
  render->add_option("-o,--output", ren.output_dir, "Output directory (default: the scene's output.directory)");
  render->add_option("--fps", ren.fps, "Frames per second (overrides time.fps)")->check(positive);
  render->add_option("--duration", ren.duration, "Simulated seconds (overrides time.duration)")->check(positive);
  render->add_option("--frames", ren.frames, "Render only frames A:B (the run stops at frame B)");
  add_image_options(render, ren.image);
  render->add_flag("--no-video", ren.no_video, "PNG frames only, no video");
  render->add_option("--format", ren.format, "Video container: mp4 (H.264, default), webm (VP9), gif");
  render->add_option("--crf", ren.crf, "Video quality, lower is better: mp4 0-51 (default 18), webm 0-63 (default 31)")
      ->check(number_check(true, 0, false, 63));
  render->add_option("--frame-pattern", ren.frame_pattern, "Names of the PNG frames, one %d or %0Nd (default frame_%05d.png)");
  add_export_option(render, ren.exports);
  render->add_option("--threads", ren.threads, "OpenMP threads (default: 1 or all cores, chosen by measuring while it runs)")->check(threads);
  render->add_option("--set", ren.set, "Override a scene value: path=value")->take_all();
  render->add_flag("-q,--quiet", ren.quiet, "No progress output");
  render->add_flag("--overwrite", ren.overwrite, "Replace a previous run in the output directory");
  add_checkpoint_options(render, ren.checkpoint_every, ren.resume, ren.scene);

  StillOptions still;
  CLI::App* stillcmd = app.add_subcommand("still", "Render one frame at a simulated time to a PNG");
  stillcmd->add_option("scene", still.scene, "Scene file (JSON)")->required();
  stillcmd->add_option("--time", still.time, "Simulated time [s]")->required()->check(number_check(false, 0, false));
  stillcmd->add_option("-o,--output", still.output, "PNG file (default: <output directory>/still.png)");
  add_image_options(stillcmd, still.image);
  stillcmd->add_option("--threads", still.threads, "OpenMP threads")->check(threads);
  stillcmd->add_option("--set", still.set, "Override a scene value: path=value")->take_all();

  MontageOptions mont;
  CLI::App* montagecmd = app.add_subcommand("montage", "Render snapshots at several times (and settings) into one grid PNG");
  montagecmd->add_option("scene", mont.scene, "Scene file (JSON)")->required();
  montagecmd->add_option("--times", mont.times, "Simulated times T1,T2,... [s], strictly increasing, within 0..time.duration")
      ->required();
  montagecmd->add_option("--vary", mont.vary, "One fresh run per value: KEY=V1,V2,... (each applied as --set KEY=V)");
  montagecmd->add_option("--cols", mont.cols, "Cells per row (default: the number of times with --vary, else up to 4)")
      ->check(number_check(true, 1, false, 4096));
  montagecmd->add_option("--set", mont.set, "Override a scene value: path=value")->take_all();
  montagecmd->add_option("--cell", mont.cell, "Size of each cell WxH (default 480x270)");
  montagecmd->add_option("--color-by", mont.color_by, "cfl, speed, pressure, density_error (default: render.color_by)")
      ->check(CLI::IsMember({"cfl", "speed", "pressure", "density_error"}));
  montagecmd->add_option("--colormap", mont.colormap, "spectrum, viridis, turbo (default: render.colormap)")
      ->check(CLI::IsMember({"spectrum", "viridis", "turbo"}));
  montagecmd->add_option("--range", mont.range, "Colour range lo:hi or auto, shared by all cells (default: render.range)");
  montagecmd->add_option("--title", mont.title, "Title line above the grid");
  montagecmd->add_option("--overlay", mont.overlay, "Each cell's label band: time (default), full (also frame, step, iterations), none")
      ->check(CLI::IsMember({"full", "time", "none"}));
  montagecmd->add_option("-o,--output", mont.output, "PNG file (default: <output directory>/montage.png)");
  montagecmd->add_option("--threads", mont.threads, "OpenMP threads")->check(threads);

  CompareOptions cmp;
  CLI::App* compare = app.add_subcommand(
      "compare", "Compare two PNG images; exit 0 when they match, 1 when they differ, 2 usage, 3 unreadable, 4 sizes differ");
  compare->add_option("a", cmp.a, "First PNG")->required();
  compare->add_option("b", cmp.b, "Second PNG")->required();
  compare->add_option("--preset", cmp.preset, "strict: 0 levels, 0 % of pixels (default); tests: sluice's image tests' rule, 8 levels, 0.5 %")
      ->check(CLI::IsMember({"strict", "tests"}));
  compare->add_option("--tolerance", cmp.tolerance, "Channel difference a pixel may have, 0-255 levels (default: the preset's)")
      ->check(CLI::Range(0, 255));
  compare->add_option("--max-fraction", cmp.max_fraction, "Share of compared pixels allowed beyond the tolerance, 0-1 (default: the preset's)")
      ->check(number_check(false, 0, false, 1));  // CLI::Range lets nan through
  compare->add_option("--mask", cmp.mask, "PNG of the images' size: its non-black pixels are ignored");
  compare->add_option("--region", cmp.regions, "Ignore the rectangle x,y,w,h (pixels from the top left; repeatable)")
      ->allow_extra_args(false);  // one rectangle per --region: A.png and B.png may follow
  compare->add_option("--diff", cmp.diff, "Write a diff image here when pixels differ");

  BenchRenderOptions brender;
  CLI::App* benchrender = app.add_subcommand("bench-render", "Time the renderer: draw, read-back, PNG per frame");
  benchrender->add_option("--particles", brender.particles, "Particle counts (default 10000 130000)")
      ->delimiter(',')->check(number_check(true, 1, false));
  benchrender->add_option("--resolution", brender.resolutions, "Resolutions WxH (default 1280x720 1920x1080)")
      ->delimiter(',');
  benchrender->add_option("--repeat", brender.repeat, "Frames timed per case; the median is reported")
      ->check(number_check(true, 1, false));
  benchrender->add_option("--msaa", brender.msaa, "0 or 4")->check(CLI::IsMember({0, 4}));
  benchrender->add_option("--egl", brender.egl, "auto, surfaceless, device")
      ->check(CLI::IsMember({"auto", "surfaceless", "device"}));
  benchrender->add_option("--csv", brender.csv, "CSV output file");

  SuiteOptions suite;
  CLI::App* suitecmd = app.add_subcommand("suite", "Run the hard-case suite with both solvers; print a pass/fail table");
  suitecmd->add_option("file", suite.file, "Suite file (default scenes/hard/suite.json)");
  suitecmd->add_flag("--short", suite.quick, "The short version of every case (what CI runs)");
  suitecmd->add_option("--solver", suite.solver, "iisph, wcsph or both (default)")
      ->check(CLI::IsMember({"iisph", "wcsph", "both"}));
  suitecmd->add_option("--case", suite.only, "Run only this case");
  suitecmd->add_option("--threads", suite.threads, "OpenMP threads")->check(threads);
  suitecmd->add_option("--csv", suite.csv, "CSV output file (default renders/suite/suite.csv)");

  ValidateOptions val;
  CLI::App* validatecmd = app.add_subcommand("validate", "Validation against known answers: hydrostatic pressure, Martin & Moyce's dam break, Monaghan's elliptical drop");
  validatecmd->add_option("what", val.what, "hydrostatic, dam-break, elliptical-drop or thin-plate")->required()->check(CLI::IsMember({"hydrostatic", "dam-break", "elliptical-drop", "thin-plate"}));
  validatecmd->add_option("--scene", val.scene, "Scene file (default scenes/validation/hydrostatic.json, dam_break_martin_moyce.json or elliptical_drop.json)");
  validatecmd->add_option("-o,--output", val.output_dir, "Directory for the CSV files and figures (default renders/validation)");
  validatecmd->add_option("--solver", val.solver, "iisph, wcsph or both (default)")
      ->check(CLI::IsMember({"iisph", "wcsph", "both"}));
  validatecmd->add_option("--case", val.only, "hydrostatic: only this case, e.g. iisph_mirroring");
  validatecmd->add_option("--spacing", val.spacing, "dam-break, elliptical-drop: particle spacing h [m] (default: the scene's, 0.02 and 0.025)")
      ->check(positive);
  validatecmd->add_option("--max-rms", val.max_rms, "dam-break: bound on the RMS relative front error (default 0.20)")
      ->check(positive);
  validatecmd->add_option("--threads", val.threads, "OpenMP threads")->check(threads);
  validatecmd->add_option("--set", val.set, "Override a scene value: path=value")->take_all();

  FiguresOptions fig;
  CLI::App* figcmd = app.add_subcommand(
      "figures", "Figures from stats/bench/experiment CSV files with gnuplot: series, box, scatter, table, run");
  figcmd->add_option("kind", fig.kind, "series (y over x), box (distributions), scatter (points, Pareto front), "
                                       "table (Markdown), run (the standard figures of run directories)")
      ->required()->check(CLI::IsMember({"series", "box", "scatter", "table", "run"}));
  figcmd->add_option("inputs", fig.inputs, "CSV files (run: directories holding stats.csv)")->required();
  figcmd->add_option("--x", fig.x, "Column on the x axis (default time)");
  figcmd->add_option("--y", fig.y, "Column(s) to plot; each is its own series")->delimiter(',');
  figcmd->add_option("--label", fig.labels, "Legend label per input (default: its directory's name)");
  figcmd->add_option("--group", fig.group, "Split each input's rows into series by this column's value");
  figcmd->add_option("--where", fig.where, "Keep only rows with COLUMN=VALUE (repeatable)");
  figcmd->add_option("--color", fig.color, "scatter: colour the points by this column");
  figcmd->add_flag("--mean", fig.mean, "series: add a dashed line at each series' mean");
  figcmd->add_flag("--pareto", fig.pareto, "scatter: draw the Pareto front (smaller x and y are better)");
  figcmd->add_option("--highlight", fig.highlight, "scatter: ring the rows with COLUMN=VALUE in red (e.g. best=1)");
  figcmd->add_flag("--logx", fig.logx, "Logarithmic x axis");
  figcmd->add_flag("--logy", fig.logy, "Logarithmic y axis");
  figcmd->add_option("--style", fig.style, "series: lines, linespoints or points")
      ->check(CLI::IsMember({"lines", "linespoints", "points"}));
  figcmd->add_option("--title", fig.title, "Figure title (default none: papers put it in the caption)");
  figcmd->add_option("--xlabel", fig.xlabel, "x axis label (default: the column with its unit)");
  figcmd->add_option("--ylabel", fig.ylabel, "y axis label (default: the column with its unit)");
  figcmd->add_option("-o,--output", fig.output,
                     "Figure file; .png, .svg or .pdf picks the format (table: a .md file, default stdout; "
                     "run: a directory, default RUN/figures)");
  figcmd->add_option("--size", fig.size, "Figure size WxH in pixels (default 1200x800; PDF: 6x4 in)");
  figcmd->add_option("--columns", fig.columns, "table: the columns to show (default all)")->delimiter(',');
  figcmd->add_option("--format", fig.format, "run: png, svg or pdf")->check(CLI::IsMember({"png", "svg", "pdf"}));

  ExperimentOptions exp;
  CLI::App* expcmd = app.add_subcommand("experiment", "The thesis' chapter-5 experiments: CSV, figures and summary.md each");
  expcmd->add_option("names", exp.names, "Experiment names, `all`, or `list` (default: list them)");
  expcmd->add_option("-o,--output", exp.output_dir, "Output directory; each experiment writes DIR/<name>/ (default renders/experiments)");
  expcmd->add_flag("--quick", exp.quick, "Small versions: coarse particles, short runs (tests, a first look)");
  expcmd->add_option("--scenes", exp.scenes, "Folder holding the base scenes (default scenes)");
  expcmd->add_option("--scene", exp.scene, "Replace the experiment's base scene (one experiment at a time)");
  expcmd->add_option("--set", exp.set, "Override a scene value: path=value (after the experiment's own)")->take_all();
  expcmd->add_option("--threads", exp.threads, "OpenMP threads (parallel compares 1 and 2 regardless)")->check(threads);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return flag_error(app, e);
  }
  try {
    if (*simulate) return run_simulate(sim);
    if (*benchcmd) return run_bench(bench);
    if (*render) return run_render(ren);
    if (*stillcmd) return run_still(still);
    if (*montagecmd) return run_montage(mont);
    if (*compare) return run_compare(cmp);
    if (*benchrender) return run_bench_render(brender);
    if (*suitecmd) return run_suite(suite);
    if (*validatecmd) return run_validate(val);
    if (*figcmd) return run_figures(fig);
    if (*expcmd) return run_experiment(exp);
  } catch (const Interrupted& e) {
    std::fprintf(stderr, "sluice: %s\n", e.what());
    return 128 + e.signal();  // 130 for SIGINT, 143 for SIGTERM, as a shell reports them
  } catch (const sluice::render::ImageReadError& e) {
    // compare's inputs: a missing or broken image, never mistaken for a missing GPU (6)
    std::fprintf(stderr, "sluice: input image error: %s\n", e.what());
    return kCompareIo;
  } catch (const sluice::view::FlagError& e) {
    std::fprintf(stderr, "sluice: error: %s\n", e.what());
    return *compare ? kCompareUsage : 1;
  } catch (const OutOfMemory& e) {
    std::fprintf(stderr, "sluice: out of memory %s\n", e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "sluice: out of memory (std::bad_alloc) while running the command; a smaller scene "
                         "(larger spacing) or more memory is needed\n");
    return 1;
  } catch (const sluice::SceneError& e) {
    std::fprintf(stderr, "sluice: scene error: %s\n", e.what());
    return 2;
  } catch (const sluice::OutputError& e) {
    std::fprintf(stderr, "sluice: output error: %s\n", e.what());
    return 3;
  } catch (const sluice::render::VideoError& e) {
    std::fprintf(stderr, "sluice: video error: %s\n", e.what());
    return 5;
  } catch (const sluice::render::RenderError& e) {
    std::fprintf(stderr, "sluice: render error: %s\n", e.what());
    return 6;
  } catch (const sluice::CheckpointError& e) {
    std::fprintf(stderr, "sluice: checkpoint error: %s\n", e.what());
    return 7;
  } catch (const sluice::SimulationUnstable& e) {
    std::fprintf(stderr, "sluice: %s\n", e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sluice: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
