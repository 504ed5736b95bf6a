// `sluice experiment NAME`: the experiments of the thesis' chapter 5, one command each
// (the experiments themselves: app/experiments/, one file each).
// Every experiment writes its numbers as CSV, its figures through `sluice figures`
// (analysis/figures.h) and a summary.md that says what to compare with which thesis
// figure or table. Runs are fresh in-process simulations (analysis::run_sweep_point), so
// a result does not depend on the order of the runs.
//
// Units: the thesis' experiments use their own scale (time steps of 0.05 s); sluice's
// scenes are in metres with h = 0.01 m, so the swept values are the equivalents here
// (the stable range of dt, the column of 5000 particles), not the thesis' numbers.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "app/commands.h"
#include "app/experiments/common.h"
#include "app/run.h"
#include "io/csv.h"
#include "io/output.h"

namespace sluice::app {

namespace {

namespace fs = std::filesystem;
using experiments::Context;

struct Experiment {
  const char* name;
  const char* thesis;
  const char* what;
  std::function<void(Context&)> run;
};

const std::vector<Experiment>& experiment_list() {
  static const std::vector<Experiment> list = {
      {"snapshots", "Figure 2", "breaking dam snapshots at eight times (montage)", experiments::snapshots},
      {"dam-break-iterations", "Figure 3", "solver iterations and compression error over time, breaking dam",
       experiments::dam_break_iterations},
      {"iisph-dt", "Figure 6a, Table 2", "IISPH iterations and pressure/neighbour/overall time against dt, column",
       experiments::iisph_dt},
      {"column-height", "Figure 6b", "IISPH iterations against column height at fixed dt",
       experiments::column_height_experiment},
      {"fixed-iterations", "Figure 7", "compression error against a fixed number of Jacobi iterations",
       experiments::fixed_iterations},
      {"boundary-pressure", "Figure 8", "pressure field of the three boundary methods side by side (montage)",
       experiments::boundary_pressure},
      {"boundary-gamma", "Figure 9", "gamma1-3 search for each boundary method, best values",
       experiments::boundary_gamma},
      {"boundary-iterations", "Figure 10", "iteration distributions per boundary method",
       experiments::boundary_iterations},
      {"wcsph", "Table 3, Figure 12", "WCSPH error against stiffness, time against dt", experiments::wcsph},
      {"speed-error", "Section 5.5", "IISPH against WCSPH: time against error, Pareto front and crossover",
       experiments::speed_error},
      {"parallel", "Figure 11", "1 against 2 threads: column sizes and the 130k breaking dam's efficiency",
       experiments::parallel},
      {"scaling", "(O(n) target)", "time per particle-step from 10k to 1M particles", experiments::scaling},
      {"neighbour-search", "Figure 14", "naive against spatial-hashing neighbour search",
       experiments::neighbour_search},
  };
  return list;
}

}  // namespace

std::vector<std::string> experiment_names() {
  std::vector<std::string> names;
  for (const auto& e : experiment_list()) names.push_back(e.name);
  return names;
}

int run_experiment(const ExperimentOptions& o) {
  if (o.names.empty() || (o.names.size() == 1 && o.names[0] == "list")) {
    std::printf("%-22s %-20s %s\n", "experiment", "thesis", "what");
    for (const auto& e : experiment_list()) std::printf("%-22s %-20s %s\n", e.name, e.thesis, e.what);
    return 0;
  }
  std::vector<const Experiment*> chosen;
  for (const auto& n : o.names) {
    if (n == "all") {
      for (const auto& e : experiment_list()) chosen.push_back(&e);
      continue;
    }
    const auto it = std::find_if(experiment_list().begin(), experiment_list().end(),
                                 [&](const Experiment& e) { return n == e.name; });
    if (it == experiment_list().end())
      throw view::FlagError("name", n, "one of: " + io::join(experiment_names(), ", ") + ", all, list");
    chosen.push_back(&*it);
  }
  if (!o.scene.empty() && chosen.size() > 1)
    throw view::FlagError("--scene", o.scene, "one experiment at a time (each has its own base scene)");
  set_threads(o.threads);
  const fs::path root(o.output_dir);
  std::string index =
      "# sluice: the experiments of the thesis' chapter 5\n\nWritten by `sluice experiment` "
      "(scripts/experiments.sh runs them all). Each section's figures and CSV files are in its folder.\n\n";
  for (const Experiment* e : chosen) {
    Context c;
    c.root = root;
    c.dir = root / e->name;
    c.quick = o.quick;
    c.scenes = o.scenes;
    c.scene = o.scene;
    c.set = o.set;
    make_directory(c.dir);
    std::printf("%s (%s): %s\n", e->name, e->thesis, e->what);
    c.md = "## " + std::string(e->name) + " (thesis " + e->thesis + ")\n\n" + e->what +
           ". Command: `sluice experiment " + e->name + (o.quick ? " --quick" : "") + "`.\n\n";
    e->run(c);
    write_file_atomic((c.dir / "summary.md").string(), c.md);
    std::printf("  wrote %s\n", (c.dir / "summary.md").string().c_str());
  }
  // The index holds every experiment whose summary is in DIR, in the list's order, so that
  // rerunning one experiment keeps the others' sections.
  for (const auto& e : experiment_list()) {
    const fs::path summary = root / e.name / "summary.md";
    if (!fs::exists(summary)) continue;
    std::ifstream in(summary);
    std::string linked((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    // The index links the figures from the root folder.
    for (std::size_t p = 0; (p = linked.find("](", p)) != std::string::npos; p += 2)
      linked.insert(p + 2, std::string(e.name) + "/");
    index += linked;
  }
  write_file_atomic((root / "README.md").string(), index);
  std::printf("wrote %s\n", (root / "README.md").string().c_str());
  return 0;
}

}  // namespace sluice::app
