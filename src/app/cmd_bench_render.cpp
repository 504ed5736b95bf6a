// `sluice bench-render`: its flags; the timing is run_bench_render (app/render.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_bench_render(CLI::App& app) {
  auto brender = std::make_shared<BenchRenderOptions>();
  CLI::App* benchrender = app.add_subcommand("bench-render", "Time the renderer: draw, read-back, PNG per frame");
  benchrender->add_option("--particles", brender->particles, "Particle counts (default 10000 130000)")
      ->delimiter(',')
      ->check(number_check(true, 1, false));
  benchrender->add_option("--resolution", brender->resolutions, "Resolutions WxH (default 1280x720 1920x1080)")
      ->delimiter(',');
  benchrender->add_option("--repeat", brender->repeat, "Frames timed per case; the median is reported")
      ->check(number_check(true, 1, false));
  benchrender->add_option("--msaa", brender->msaa, "0 or 4")->check(CLI::IsMember({0, 4}));
  benchrender->add_option("--egl", brender->egl, "auto, surfaceless, device")
      ->check(CLI::IsMember({"auto", "surfaceless", "device"}));
  benchrender->add_option("--csv", brender->csv, "CSV output file");
  return {benchrender, [brender] { return run_bench_render(*brender); }};
}

}  // namespace sluice::app
