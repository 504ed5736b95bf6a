// `sluice render`: its flags; the run is run_render (app/render.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_render(CLI::App& app) {
  auto ren = std::make_shared<RenderOptions>();
  CLI::App* render =
      app.add_subcommand("render", "Simulate a scene and render PNG frames and a video (MP4, WebM or GIF)");
  render->add_option("scene", ren->scene, "Scene file (JSON); with --resume, the recorded one by default");
  render->add_option("-o,--output", ren->output_dir, "Output directory (default: the scene's output.directory)");
  render->add_option("--fps", ren->fps, "Frames per second (overrides time.fps)")->check(positive_check());
  render->add_option("--duration", ren->duration, "Simulated seconds (overrides time.duration)")
      ->check(positive_check());
  render->add_option("--frames", ren->frames, "Render only frames A:B (the run stops at frame B)");
  add_image_options(render, ren->image);
  render->add_flag("--no-video", ren->no_video, "PNG frames only, no video");
  render->add_option("--format", ren->format, "Video container: mp4 (H.264, default), webm (VP9), gif");
  render->add_option("--crf", ren->crf, "Video quality, lower is better: mp4 0-51 (default 18), webm 0-63 (default 31)")
      ->check(number_check(true, 0, false, 63));
  render->add_option("--frame-pattern", ren->frame_pattern,
                     "Names of the PNG frames, one %d or %0Nd (default frame_%05d.png)");
  add_export_option(render, ren->exports);
  render
      ->add_option("--threads", ren->threads,
                   "OpenMP threads (default: 1 or all cores, chosen by measuring while it runs)")
      ->check(threads_check());
  render->add_option("--set", ren->set, "Override a scene value: path=value")->take_all();
  render->add_flag("-q,--quiet", ren->quiet, "No progress output");
  render->add_flag("--overwrite", ren->overwrite, "Replace a previous run in the output directory");
  add_checkpoint_options(render, ren->checkpoint_every, ren->resume, ren->scene);
  return {render, [ren] { return run_render(*ren); }};
}

}  // namespace sluice::app
