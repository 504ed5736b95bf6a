#pragma once
// Parameter sweeps for `sluice bench --sweep`: the combinations of the swept scene values,
// one clean run per combination, and the Pareto front of time against error.
#include <functional>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "solver/stats.h"

namespace sluice::analysis {

// One swept scene value: `KEY=V1,V2,...` (KEY as for --set; the values are split at the
// commas outside [], {} and quotes, so a value may be a JSON array or object).
struct SweepAxis {
  std::string key;
  std::vector<std::string> values;
};

// Parses "KEY=V1,V2,..."; throws SceneError naming the flag text and what is allowed.
SweepAxis parse_sweep(const std::string& text);

// Every combination as --set overrides, the first axis varying slowest; one empty
// combination when there are no axes.
std::vector<std::vector<std::string>> sweep_combinations(const std::vector<SweepAxis>& axes);

struct SweepRun {
  std::string scene;             // scene name
  std::vector<std::string> set;  // the combination's overrides
  std::string solver;
  long particles = 0;
  int threads = 0;
  bool stable = true;
  std::string message;  // the detector's message when not stable
  long steps = 0;
  double simulated = 0;  // simulated seconds reached
  double wall_seconds = 0;
  double avg_iterations = 0;
  double avg_density_error = 0;             // mean over steps of Eq. 15's average density error [%]
  double max_density_error = 0;             // its largest per-step value [%]
  double ms_phase[6] = {0, 0, 0, 0, 0, 0};  // per step: neighbours, non-pressure, pressure, integration, total, moving
  bool pareto = false;
  double avg_dt = 0, min_dt = 0;  // step sizes [s]
  // The average step as a share of time.dt_max (or of a fixed time.dt) [%]: near 100,
  // dt_max bound the step rather than the CFL or acoustic limit (steps evened out to
  // land on frame times keep it a little below 100).
  double dt_of_max_percent = 0;

  // The combination's values, for the figure's point labels: "iisph, 0.002".
  std::string label() const;

  // Wall seconds per simulated second: the cost a user pays for one second of animation.
  double seconds_per_simulated_second() const { return simulated > 0 ? wall_seconds / simulated : 0; }
};

// Runs a scene from its initial state to its duration (a fresh Simulation: runs do not
// depend on each other or on their order). An unstable run is recorded, not thrown.
// `on_step` (when given) sees every step's statistics (stats.csv rows, distributions);
// `brute_force` uses the O(n^2) neighbour search (the thesis' Figure 14 comparison).
SweepRun run_sweep_point(const Scene& scene, const std::vector<std::string>& set,
                         const std::function<void(const StepStats&)>& on_step = {}, bool brute_force = false);

// Marks the Pareto front of (seconds per simulated second, average density error) among
// the stable runs: a run is on it when no other stable run is at least as good in both
// and better in one.
void mark_pareto_front(std::vector<SweepRun>& runs);

// The gnuplot script of bench.png: seconds per simulated second against the average
// density error, log-log, one series per solver that ran (no empty legend entries),
// each point labelled with its values, the Pareto front when there is one. The data is
// inline; stable runs with both values positive (a log axis) are drawn.
std::string sweep_plot_script(const std::vector<SweepRun>& runs, const std::string& title);

// CSV with a header row; read_sweep_csv reads what write_sweep_csv writes (for --collect).
std::string sweep_csv(const std::vector<SweepRun>& runs);
std::vector<SweepRun> read_sweep_csv(const std::string& path);

// The Markdown table of the runs (Pareto runs marked).
std::string sweep_markdown(const std::vector<SweepRun>& runs);

}  // namespace sluice::analysis
