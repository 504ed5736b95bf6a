// `sluice bench`: its flags; the runs are run_bench (app/bench.cpp).
#include <algorithm>
#include <memory>

#include "app/cli.h"

namespace sluice::app {

namespace {

// bench has four modes (run_bench); a flag that the chosen mode does not read would be
// silently ignored, so it is refused, naming the mode and the flags it takes.
void check_mode_flags(const CLI::App& cmd, const BenchOptions& o) {
  const bool sweep = !o.sweep.empty() || !o.output_dir.empty() || !o.jobs.empty() || o.duration > 0;
  std::string mode;
  std::vector<std::string> takes;
  if (o.end_to_end) {
    mode = "--end-to-end";
    takes = {"scenes",   "--end-to-end", "--duration", "--fps",      "--resolution",
             "--output", "--threads",    "--set",      "--overwrite"};
  } else if (!o.collect.empty()) {
    mode = "--collect";
    takes = {"--collect", "--output", "--threads", "--overwrite"};
  } else if (sweep) {
    mode = "--sweep";  // also -o, --jobs or --duration alone: a sweep of one run
    takes = {"scenes", "--sweep", "--duration", "--output", "--jobs", "--set", "--threads", "--overwrite"};
  } else {
    mode = "SCENE...";
    takes = {"scenes", "--steps", "--repeat", "--threads", "--set", "--csv", "--brute-force"};
  }
  for (const CLI::Option* opt : cmd.get_options()) {
    const std::string name = opt->get_name();
    if (opt->count() == 0 || name == "--help" || std::find(takes.begin(), takes.end(), name) != takes.end()) continue;
    std::string value;
    for (const std::string& r : opt->results()) value += (value.empty() ? "" : ",") + r;
    std::string list;
    for (const std::string& t : takes)
      list += (list.empty() ? "" : ", ") + (t == "scenes" ? std::string("SCENE") : t == "--output" ? "-o" : t);
    const std::string shown = name == "scenes" ? "SCENE" : name == "--output" ? "-o" : name;
    std::string why = "bench " + mode + " does not read it (it takes " + list + ")";
    if (name == "--steps" && mode == "--sweep")
      why += "; each run goes to the scene's duration: shorten it with --duration S";
    if (name == "scenes" && mode == "--collect")
      why = "bench --collect merges the bench.csv files of directories and runs no scene";
    throw view::FlagError(shown, value, why);
  }
}

}  // namespace

Command add_bench(CLI::App& app) {
  auto bench = std::make_shared<BenchOptions>();
  CLI::App* benchcmd = app.add_subcommand("bench", "Time scenes; print a table and write CSV");
  benchcmd->add_option("scenes", bench->scenes, "Scene files (one in sweep mode; none with --collect)");
  benchcmd->add_option("--steps", bench->steps, "Steps per run (0: the whole duration)")
      ->check(number_check(true, 0, false));
  benchcmd->add_option("--repeat", bench->repeat, "Runs per scene; the median is reported")
      ->check(number_check(true, 1, false));
  benchcmd->add_option("--threads", bench->threads, "OpenMP threads")->check(threads_check());
  benchcmd->add_option("--set", bench->set, "Override a scene value (applies to every scene)")->take_all();
  benchcmd->add_option("--csv", bench->csv, "CSV output file");
  benchcmd->add_flag("--brute-force", bench->brute_force, "O(n^2) neighbour search instead of the grid");
  benchcmd->add_option("--sweep", bench->sweep,
                       "Sweep a scene value: KEY=V1,V2,... (repeatable; every combination runs)");
  benchcmd->add_option("--duration", bench->duration, "Sweep: simulated seconds per run (overrides time.duration)")
      ->check(positive_check());
  benchcmd->add_option("-o,--output", bench->output_dir,
                       "Sweep: directory for bench.csv, bench.md, bench.png (default renders/bench/<scene>)");
  benchcmd->add_option("--jobs", bench->jobs, "Sweep: write one command line per run to this file instead of running");
  benchcmd->add_flag("--end-to-end", bench->end_to_end,
                     "Time `render` of one scene (default scenes/dam_break_130k.json, 5 s, 60 fps, 1920x1080) as a "
                     "whole, split into simulation, drawing, PNG and video");
  benchcmd->add_option("--fps", bench->fps, "End-to-end: frames per second (default 60)")->check(positive_check());
  benchcmd->add_option("--resolution", bench->resolution, "End-to-end: WxH (default 1920x1080)");
  benchcmd->add_option("--collect", bench->collect, "Merge the bench.csv of these directories into -o DIR")->take_all();
  benchcmd->add_flag("--overwrite", bench->overwrite,
                     "Sweep, --collect, --end-to-end: replace an earlier run's files in the output directory");
  return {benchcmd, [bench, benchcmd] {
            check_mode_flags(*benchcmd, *bench);
            return run_bench(*bench);
          }};
}

}  // namespace sluice::app
