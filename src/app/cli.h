#pragma once
// The command line's pieces shared by the subcommands (app/cmd_*.cpp): each cmd file adds
// its subcommand and options to the program's CLI11 app; main.cpp lists them.
#include <CLI/CLI.hpp>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "app/commands.h"

namespace sluice::app {

// A registered subcommand: its CLI11 node (set once parsed) and what runs it. `run` holds
// the parsed options (they must outlive add_*: CLI11 writes into them while parsing).
struct Command {
  CLI::App* cli = nullptr;
  std::function<int()> run;
};

// One per subcommand, in the order `sluice --help` lists them (main.cpp).
Command add_simulate(CLI::App& app);
Command add_bench(CLI::App& app);
Command add_render(CLI::App& app);
Command add_still(CLI::App& app);
Command add_montage(CLI::App& app);
Command add_compare(CLI::App& app);
Command add_bench_render(CLI::App& app);
Command add_suite(CLI::App& app);
Command add_validate(CLI::App& app);
Command add_figures(CLI::App& app);
Command add_experiment(CLI::App& app);

// CLI11's PositiveNumber and NonNegativeNumber print the largest double in full when a
// value fails; this check says what is allowed in words. `hi` bounds values that would
// exhaust the machine (e.g. a billion threads).
CLI::Validator number_check(bool integer, double lo, bool lo_open, double hi = HUGE_VAL);
// A number > 0, and --threads' integer in 1..4096.
CLI::Validator positive_check();
CLI::Validator threads_check();

// --export of `simulate` and `render`: the particle exports at every frame (io/export.h),
// in place of the scene's output.export.
void add_export_option(CLI::App* cmd, std::vector<std::string>& exports);

// --checkpoint-every and --resume of `simulate` and `render`. With --resume the scene and
// every flag that shapes the results come from DIR/checkpoints/run.json: only SCENE (a
// moved scene file, checked by its hash), --threads, -q and --checkpoint-every may be
// given again. SCENE is required without --resume. Call it after the command's other options.
void add_checkpoint_options(CLI::App* cmd, int& every, std::string& resume, const std::string& scene);

// Image flags shared by `render` and `still`.
void add_image_options(CLI::App* cmd, ImageOptions& io);

}  // namespace sluice::app
