// sluice: 2D IISPH / WCSPH fluid simulator. Command-line entry point (CLI11): each
// subcommand's flags are in app/cmd_<name>.cpp; here they are listed, parsed and run, and
// errors become the documented exit statuses (docs/cli.md).
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "app/cli.h"
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

}  // namespace

int main(int argc, char** argv) {
  using namespace sluice::app;
  set_thread_wait_policy(argv);
  CLI::App app{"sluice: 2D implicit incompressible SPH (IISPH) and WCSPH fluid simulator"};
  app.set_version_flag("--version", SLUICE_VERSION);
  app.require_subcommand(1);

  // In the order `sluice --help` lists them.
  const std::vector<Command> commands = {add_simulate(app), add_bench(app),   add_render(app),       add_still(app),
                                         add_montage(app),  add_compare(app), add_bench_render(app), add_suite(app),
                                         add_validate(app), add_figures(app), add_experiment(app)};
  const CLI::App* compare = nullptr;
  for (const Command& c : commands)
    if (c.cli->get_name() == "compare") compare = c.cli;

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    return flag_error(app, e);
  }
  try {
    for (const Command& c : commands)
      if (*c.cli) return c.run();
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
    std::fprintf(stderr,
                 "sluice: out of memory (std::bad_alloc) while running the command; a smaller scene "
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
