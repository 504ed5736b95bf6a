#include "app/experiments/common.h"

#include <omp.h>

#include <algorithm>
#include <cstdio>

#include "io/output.h"

namespace sluice::app::experiments {

// --- Section 5.5: IISPH or WCSPH, speed against error --------------------------------------------

namespace {

// Names where the combined Pareto front changes solver: below which error each one is the
// faster choice.
std::string crossover_text(std::vector<SweepRun> runs) {
  analysis::mark_pareto_front(runs);
  std::vector<const SweepRun*> front;
  for (const auto& r : runs)
    if (r.pareto) front.push_back(&r);
  std::sort(front.begin(), front.end(), [](const SweepRun* a, const SweepRun* b) {
    return a->seconds_per_simulated_second() < b->seconds_per_simulated_second();
  });
  if (front.empty()) return "No stable run: no front.";
  std::string s = "Pareto front from fastest to most accurate: ";
  for (std::size_t i = 0; i < front.size(); ++i)
    s += (i ? ", " : "") + front[i]->solver + " (" + fmt(front[i]->seconds_per_simulated_second(), 3) + " s, " +
         fmt(front[i]->avg_density_error, 3) + " %)";
  // Runs of the same solver along the front: each is the faster choice over its errors.
  std::vector<std::pair<std::size_t, std::size_t>> segments;
  for (std::size_t i = 0; i < front.size(); ++i)
    if (i == 0 || front[i]->solver != front[i - 1]->solver)
      segments.push_back({i, i});
    else
      segments.back().second = i;
  if (segments.size() == 1) return s + ". No crossover: " + front[0]->solver + " is faster at every error reached.";
  s += ". The faster solver by the error asked for: ";
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const SweepRun* a = front[segments[k].first];
    const SweepRun* b = front[segments[k].second];
    s += (k ? "; " : "") + a->solver + " " +
         (a == b ? "at " + fmt(a->avg_density_error, 3) + " %"
                 : "from " + fmt(a->avg_density_error, 3) + " % down to " + fmt(b->avg_density_error, 3) + " %");
  }
  return s + ". Crossovers lie between neighbouring segments.";
}

}  // namespace

void speed_error(Context& c) {
  struct Case {
    std::string label, base;
    std::vector<std::string> own;
  };
  const double duration = c.quick ? 0.05 : 0.5;
  std::vector<Case> cases = {{"dam_break_20k", "dam_break.json", {}},
                             {"column_1m", "column.json", {}},
                             {"column_2m", "column.json", column_height(0.5, 2.0)}};
  if (c.quick) cases = {{"dam_break", "dam_break.json", {}}};
  const std::vector<std::vector<std::string>> iisph =
      c.quick ? std::vector<std::vector<std::string>>{{"time.dt=1e-3", "solver.tolerance=0.1"}}
              : analysis::sweep_combinations({analysis::parse_sweep("time.dt=5e-4,1e-3,2e-3"),
                                              analysis::parse_sweep("solver.tolerance=0.01,0.1,1")});
  const std::vector<std::vector<std::string>> wc =
      c.quick ? std::vector<std::vector<std::string>>{{"solver.stiffness=1e6", "time.dt=1e-4"}}
              : analysis::sweep_combinations({analysis::parse_sweep("solver.stiffness=1e5,1e6,1e7"),
                                              analysis::parse_sweep("time.dt=5e-5,1e-4,2e-4")});
  c.md +=
      "Each scene runs " + fmt(duration, 3) +
      " simulated seconds per combination: IISPH over dt x tolerance, WCSPH over stiffness x dt. Time is wall seconds "
      "per simulated second (" +
      std::to_string(omp_get_max_threads()) +
      " threads), error is the average of Eq. 15's "
      "density error over the steps. Load average at the start " +
      fmt(load_average(), 3) + ".\n\n";
  for (const Case& k : cases) {
    std::vector<SweepRun> runs;
    for (const auto* grid : {&iisph, &wc})
      for (const auto& combo : *grid) {
        auto own = k.own;
        own.push_back(number_override("time.duration", duration));
        own.push_back(std::string("solver.type=") + (grid == &iisph ? "iisph" : "wcsph"));
        own.insert(own.end(), combo.begin(), combo.end());
        runs.push_back(analysis::run_sweep_point(c.load(k.base, own), combo));
        runs.back().scene = k.label;
        print_run(k.label + " " + io::join(combo, " "), runs.back());
      }
    analysis::mark_pareto_front(runs);
    const fs::path csv = c.dir / (k.label + ".csv");
    write_file_atomic(csv.string(), analysis::sweep_csv(runs));
    c.md += "### " + k.label + " (" + std::to_string(runs.front().particles) + " particles)\n\n" +
            analysis::sweep_markdown(runs) + "\n" + crossover_text(runs) + "\n\n";
    FigureSpec a = spec(FigureKind::Scatter, csv, "s_per_simulated_s", {"avg_density_error_percent"}, k.label + ".png");
    a.group = "solver";
    a.where = {"stable=1"};
    a.pareto = true;
    a.logx = a.logy = true;
    c.figure(a, k.label + ": time per simulated second against average density error, Pareto front dashed");
  }
}

}  // namespace sluice::app::experiments
