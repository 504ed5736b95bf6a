// `sluice still`: its flags; the frame is run_still (app/render.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_still(CLI::App& app) {
  auto still = std::make_shared<StillOptions>();
  CLI::App* stillcmd = app.add_subcommand("still", "Render one frame at a simulated time to a PNG");
  stillcmd->add_option("scene", still->scene, "Scene file (JSON)")->required();
  stillcmd->add_option("--time", still->time, "Simulated time [s]")->required()->check(number_check(false, 0, false));
  stillcmd->add_option("-o,--output", still->output, "PNG file (default: <output directory>/still.png)");
  add_image_options(stillcmd, still->image);
  stillcmd->add_option("--threads", still->threads, "OpenMP threads")->check(threads_check());
  stillcmd->add_option("--set", still->set, "Override a scene value: path=value")->take_all();
  return {stillcmd, [still] { return run_still(*still); }};
}

}  // namespace sluice::app
