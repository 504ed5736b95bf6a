#pragma once
// The hard-case suite (scenes/hard/suite.json): scenes that stress the solver, each run
// with IISPH and WCSPH and judged by stated criteria: no NaN/Inf, no fluid particle
// through a wall, IISPH's average compression error at its tolerance, the largest
// per-step density error within a bound, and a resting column's kinetic energy decaying.
// WCSPH runs with the instability detector set to that bound. A run the detector stops
// fails, unless the case declares the stop expected for that solver (expect_stop); a run
// expected to stop that holds fails too (the suite is stale).
#include <string>
#include <vector>

#include "solver/settings.h"

namespace sluice::analysis {

struct HardCase {
  std::string name;
  std::string scene;                   // path, relative to the suite file
  std::vector<std::string> set;        // overrides for both solvers
  std::vector<std::string> short_set;  // extra overrides of the short version (CI)
  std::vector<std::string> iisph_set, wcsph_set;
  std::vector<SolverType> solvers{SolverType::IISPH, SolverType::WCSPH};
  double max_density_error_iisph = 1.0;  // bound on the largest per-step average density error (Eq. 15) [%]
  double max_density_error_wcsph = 3.0;
  bool resting = false;                 // the fluid starts at rest and must settle
  std::vector<SolverType> expect_stop;  // solvers whose run the detector is expected to stop
  bool known_limit = false;             // a label: documented as failing; it still counts as a failure
  std::string what;                     // one line for the table
  std::string why;                      // why the expected stops are expected

  bool expects_stop(SolverType s) const;
};

// Reads a suite file; throws SceneError naming the file, the JSON path and the problem.
std::vector<HardCase> load_suite(const std::string& path);

enum class Outcome {
  Held,          // ran to the end within the criteria
  Failed,        // missed a criterion, was stopped unexpectedly, or held where a stop was expected
  ExpectedStop,  // the detector stopped it, as the case declares for this solver
};

// "held", "failed", "expected_stop" (the table's and the CSV's result column).
const char* outcome_name(Outcome o);

struct CaseResult {
  std::string name, solver;
  Outcome result = Outcome::Failed;
  bool known_limit = false;  // copied from the case (a label)
  std::string outcome;  // the table's text: "held", "expected stop: ...", "FAILED: ...", "FAILED (known limit): ..."
  long steps = 0;
  double simulated = 0, wall_seconds = 0;
  double avg_iterations = 0;
  double avg_error = 0;                     // mean of the per-step average error (IISPH: Eq. 23 at exit; WCSPH: Eq. 15)
  double tolerance = 0;                     // IISPH tolerance [%]
  double max_density_error = 0, bound = 0;  // largest per-step average density error (Eq. 15) and its bound [%]
  long leaks = 0;                           // fluid particles found on a solid side (summed over checks)
  double ke_peak = 0, ke_end = 0;           // kinetic energy per metre of depth [J/m] (resting cases)
  double drift = 0;                         // resting cases: |centre of mass(end) - centre of mass(0)| [m]
};

// Runs one case with one solver (quick: the short version).
CaseResult run_case(const HardCase& c, const std::string& suite_dir, SolverType solver, bool quick);

}  // namespace sluice::analysis
