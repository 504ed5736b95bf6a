// `sluice montage`: its flags; the grid is run_montage (app/montage.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_montage(CLI::App& app) {
  auto mont = std::make_shared<MontageOptions>();
  CLI::App* montagecmd =
      app.add_subcommand("montage", "Render snapshots at several times (and settings) into one grid PNG");
  montagecmd->add_option("scene", mont->scene, "Scene file (JSON)")->required();
  montagecmd
      ->add_option("--times", mont->times,
                   "Simulated times T1,T2,... [s], strictly increasing, within 0..time.duration")
      ->required();
  montagecmd->add_option("--vary", mont->vary, "One fresh run per value: KEY=V1,V2,... (each applied as --set KEY=V)");
  montagecmd->add_option("--cols", mont->cols, "Cells per row (default: the number of times with --vary, else up to 4)")
      ->check(number_check(true, 1, false, 4096));
  montagecmd->add_option("--set", mont->set, "Override a scene value: path=value")->take_all();
  montagecmd->add_option("--cell", mont->cell, "Size of each cell WxH (default 480x270)");
  montagecmd->add_option("--color-by", mont->color_by, "cfl, speed, pressure, density_error (default: render.color_by)")
      ->check(CLI::IsMember({"cfl", "speed", "pressure", "density_error"}));
  montagecmd->add_option("--colormap", mont->colormap, "spectrum, viridis, turbo (default: render.colormap)")
      ->check(CLI::IsMember({"spectrum", "viridis", "turbo"}));
  montagecmd->add_option("--range", mont->range,
                         "Colour range lo:hi or auto, shared by all cells (default: render.range)");
  montagecmd->add_option("--title", mont->title, "Title line above the grid");
  montagecmd
      ->add_option("--overlay", mont->overlay,
                   "Each cell's label band: time (default), full (also frame, step, iterations), none")
      ->check(CLI::IsMember({"full", "time", "none"}));
  montagecmd->add_option("-o,--output", mont->output, "PNG file (default: <output directory>/montage.png)");
  montagecmd->add_option("--threads", mont->threads, "OpenMP threads")->check(threads_check());
  return {montagecmd, [mont] { return run_montage(*mont); }};
}

}  // namespace sluice::app
