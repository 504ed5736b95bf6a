#pragma once
// Subcommands of the `sluice` program; each is a thin layer over the library.
#include <string>
#include <vector>

namespace sluice::app {

struct SimulateOptions {
  std::string scene;
  std::string output_dir;  // empty: the scene's output.directory
  double duration = 0;     // > 0 overrides time.duration
  int threads = 0;         // 0: OpenMP default
  std::vector<std::string> set;
  std::vector<std::string> exports;  // csv, vtk
  bool quiet = false;
};
int run_simulate(const SimulateOptions& o);

struct BenchOptions {
  std::vector<std::string> scenes;
  long steps = 200;        // steps per run (0: the scene's whole duration)
  int repeat = 3;          // runs per scene; the median is reported
  int threads = 0;
  std::vector<std::string> set;
  std::string csv = "renders/bench/bench.csv";
};
int run_bench(const BenchOptions& o);

void set_threads(int threads);

}  // namespace sluice::app
