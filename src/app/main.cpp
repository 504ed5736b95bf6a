// sluice: 2D IISPH / WCSPH fluid simulator. Command-line entry point (CLI11).
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>

#include "app/commands.h"
#include "io/output.h"
#include "scene/scene.h"
#include "sim/simulation.h"

int main(int argc, char** argv) {
  using namespace sluice::app;
  CLI::App app{"sluice: 2D implicit incompressible SPH (IISPH) and WCSPH fluid simulator"};
  app.set_version_flag("--version", SLUICE_VERSION);
  app.require_subcommand(1);

  SimulateOptions sim;
  CLI::App* simulate = app.add_subcommand("simulate", "Simulate a scene; write stats.csv, summary.json and exports");
  simulate->add_option("scene", sim.scene, "Scene file (JSON)")->required();
  simulate->add_option("-o,--output", sim.output_dir, "Output directory (default: the scene's output.directory)");
  simulate->add_option("--duration", sim.duration, "Simulated seconds (overrides time.duration)")
      ->check(CLI::PositiveNumber);
  simulate->add_option("--threads", sim.threads, "OpenMP threads (default: all cores)")->check(CLI::PositiveNumber);
  simulate->add_option("--set", sim.set, "Override a scene value: path=value, e.g. solver.tolerance=0.05")
      ->take_all();
  simulate->add_option("--export", sim.exports, "Particle exports at every frame: csv, vtk")
      ->delimiter(',')
      ->check(CLI::IsMember({"csv", "vtk"}));
  simulate->add_flag("-q,--quiet", sim.quiet, "No progress output");

  BenchOptions bench;
  CLI::App* benchcmd = app.add_subcommand("bench", "Time scenes; print a table and write CSV");
  benchcmd->add_option("scenes", bench.scenes, "Scene files")->required();
  benchcmd->add_option("--steps", bench.steps, "Steps per run (0: the whole duration)")->check(CLI::NonNegativeNumber);
  benchcmd->add_option("--repeat", bench.repeat, "Runs per scene; the median is reported")
      ->check(CLI::PositiveNumber);
  benchcmd->add_option("--threads", bench.threads, "OpenMP threads")->check(CLI::PositiveNumber);
  benchcmd->add_option("--set", bench.set, "Override a scene value (applies to every scene)")->take_all();
  benchcmd->add_option("--csv", bench.csv, "CSV output file");

  CLI11_PARSE(app, argc, argv);
  try {
    if (*simulate) return run_simulate(sim);
    if (*benchcmd) return run_bench(bench);
  } catch (const sluice::SceneError& e) {
    std::fprintf(stderr, "sluice: scene error: %s\n", e.what());
    return 2;
  } catch (const sluice::OutputError& e) {
    std::fprintf(stderr, "sluice: output error: %s\n", e.what());
    return 3;
  } catch (const sluice::SimulationUnstable& e) {
    std::fprintf(stderr, "sluice: %s\n", e.what());
    return 4;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sluice: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
