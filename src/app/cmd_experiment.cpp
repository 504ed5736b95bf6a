// `sluice experiment`: its flags; the experiments are run_experiment (app/experiment.cpp).
#include <memory>

#include "app/cli.h"

namespace sluice::app {

Command add_experiment(CLI::App& app) {
  auto exp = std::make_shared<ExperimentOptions>();
  CLI::App* expcmd =
      app.add_subcommand("experiment", "The thesis' chapter-5 experiments: CSV, figures and summary.md each");
  expcmd->add_option("names", exp->names, "Experiment names, `all`, or `list` (default: list them)");
  expcmd->add_option("-o,--output", exp->output_dir,
                     "Output directory; each experiment writes DIR/<name>/ (default renders/experiments)");
  expcmd->add_flag("--quick", exp->quick, "Small versions: coarse particles, short runs (tests, a first look)");
  expcmd->add_option("--scenes", exp->scenes, "Folder holding the base scenes (default scenes)");
  expcmd->add_option("--scene", exp->scene, "Replace the experiment's base scene (one experiment at a time)");
  expcmd->add_option("--set", exp->set, "Override a scene value: path=value (after the experiment's own)")->take_all();
  expcmd->add_option("--threads", exp->threads, "OpenMP threads (parallel compares 1 and 2 regardless)")
      ->check(threads_check());
  return {expcmd, [exp] { return run_experiment(*exp); }};
}

}  // namespace sluice::app
