// `sluice suite`: the hard-case suite (scenes/hard/suite.json), every case with IISPH
// and WCSPH, judged by its criteria; prints a table, writes CSV, exits 1 when a run fails
// (known limits included; an expected stop is not a failure).
#include <cstdio>
#include <filesystem>

#include "analysis/hard_cases.h"
#include "app/commands.h"
#include "app/run.h"
#include "io/output.h"

namespace sluice::app {

int run_suite(const SuiteOptions& o) {
  set_threads(o.threads);
  const auto cases = analysis::load_suite(o.file);
  const std::string dir = std::filesystem::path(o.file).parent_path().string();
  std::vector<analysis::CaseResult> results;
  std::printf("%-18s %-6s %7s %6s %6s %8s %10s %6s %7s  %-13s  %s\n", "case", "solver", "sim_s", "steps", "iters",
              "err_%", "max_dens_%", "bound", "leaks", "result", "outcome");
  for (const auto& c : cases) {
    if (!o.only.empty() && c.name != o.only) continue;
    for (SolverType s : c.solvers) {
      if ((s == SolverType::IISPH && o.solver == "wcsph") || (s == SolverType::WCSPH && o.solver == "iisph")) continue;
      const analysis::CaseResult r = analysis::run_case(c, dir, s, o.quick);
      std::printf("%-18s %-6s %7.3f %6ld %6.2f %8.4f %10.4f %6.2f %7ld  %-13s  %s\n", r.name.c_str(), r.solver.c_str(),
                  r.simulated, r.steps, r.avg_iterations, r.avg_error, r.max_density_error, r.bound, r.leaks,
                  analysis::outcome_name(r.result), r.outcome.c_str());
      if (c.resting)
        std::printf("%-18s %-6s   kinetic energy peak %.4g J/m, end %.4g J/m; centre of mass moved %.2e m\n", "", "",
                    r.ke_peak, r.ke_end, r.drift);
      std::fflush(stdout);
      results.push_back(r);
    }
  }
  long held = 0, stopped = 0, failed = 0, known = 0;
  std::string text =
      "case,solver,result,known_limit,outcome,simulated_s,steps,avg_iterations,avg_error_percent,tolerance_percent,"
      "max_density_error_percent,bound_percent,leaks,ke_peak,ke_end,drift_m,wall_s\n";
  for (const auto& r : results) {
    held += r.result == analysis::Outcome::Held;
    stopped += r.result == analysis::Outcome::ExpectedStop;
    failed += r.result == analysis::Outcome::Failed;
    known += r.result == analysis::Outcome::Failed && r.known_limit;
    std::string outcome = r.outcome;
    for (char& ch : outcome)
      if (ch == ',' || ch == '"' || ch == '\n') ch = ';';
    char line[1024];
    std::snprintf(line, sizeof line, "%s,%s,%s,%d,%s,%.6g,%ld,%.4f,%.6f,%.4g,%.6f,%.4g,%ld,%.6g,%.6g,%.4g,%.3f\n",
                  r.name.c_str(), r.solver.c_str(), analysis::outcome_name(r.result), r.known_limit ? 1 : 0,
                  outcome.c_str(), r.simulated, r.steps, r.avg_iterations, r.avg_error, r.tolerance,
                  r.max_density_error, r.bound, r.leaks, r.ke_peak, r.ke_end, r.drift, r.wall_seconds);
    text += line;
  }
  const std::filesystem::path csv(o.csv);
  if (csv.has_parent_path()) make_directory(csv.parent_path());
  write_file_atomic(o.csv, text);
  std::printf("%zu runs: %ld held, %ld expected stops, %ld failed (%ld of them known limits); wrote %s\n",
              results.size(), held, stopped, failed, known, o.csv.c_str());
  return failed ? 1 : 0;
}

}  // namespace sluice::app
