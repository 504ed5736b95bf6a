// `sluice simulate`: its flags; the run is run_simulate (app/simulate.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_simulate(CLI::App& app) {
  auto sim = std::make_shared<SimulateOptions>();
  CLI::App* simulate = app.add_subcommand("simulate", "Simulate a scene; write stats.csv, summary.json and exports");
  simulate->add_option("scene", sim->scene, "Scene file (JSON); with --resume, the recorded one by default");
  simulate->add_option("-o,--output", sim->output_dir, "Output directory (default: the scene's output.directory)");
  simulate->add_option("--duration", sim->duration, "Simulated seconds (overrides time.duration)")
      ->check(positive_check());
  simulate
      ->add_option("--threads", sim->threads,
                   "OpenMP threads (default: 1 or all cores, chosen by measuring while it runs)")
      ->check(threads_check());
  simulate->add_option("--set", sim->set, "Override a scene value: path=value, e.g. solver.tolerance=0.05")->take_all();
  add_export_option(simulate, sim->exports);
  simulate->add_flag("-q,--quiet", sim->quiet, "No progress output");
  simulate->add_flag("--overwrite", sim->overwrite, "Replace a previous run in the output directory");
  add_checkpoint_options(simulate, sim->checkpoint_every, sim->resume, sim->scene);
  return {simulate, [sim] { return run_simulate(*sim); }};
}

}  // namespace sluice::app
