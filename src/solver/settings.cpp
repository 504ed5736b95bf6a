#include "solver/settings.h"

#include <cstdio>

namespace sluice {

std::string pressure_solver_advice(const SolverSettings& s, double avg_iterations) {
  const bool slow_solver = s.pressure_solver == PressureSolver::Jacobi || s.pressure_solver == PressureSolver::Chebyshev;
  const bool supported = s.boundary_pressure != BoundaryPressure::Extrapolation && s.multilevel_cell >= s.support;
  if (s.type != SolverType::IISPH || !slow_solver || !supported || !(avg_iterations > kMultilevelAdviceIterations))
    return {};
  char line[320];
  std::snprintf(line, sizeof line,
                "the pressure solve took %.1f iterations a step on average, as a deep fluid does with %s; "
                "--set solver.pressure_solver=multilevel takes about 4 at any depth (the 130k dam break's first "
                "0.5 s ran 2.5-2.9x faster, a 2 m column 3x; docs/performance.md)",
                avg_iterations, to_string(s.pressure_solver));
  return line;
}

const char* to_string(SolverType t) { return t == SolverType::IISPH ? "iisph" : "wcsph"; }

const char* to_string(BoundaryPressure b) {
  switch (b) {
    case BoundaryPressure::Solved:
      return "solved";
    case BoundaryPressure::Extrapolation:
      return "extrapolation";
    case BoundaryPressure::Mirroring:
      return "mirroring";
    case BoundaryPressure::Zero:
      return "zero";
  }
  return "?";
}

const char* to_string(PressureInit p) { return p == PressureInit::Thesis ? "thesis" : "warm"; }

const char* to_string(PressureSolver p) {
  switch (p) {
    case PressureSolver::Jacobi:
      return "jacobi";
    case PressureSolver::Chebyshev:
      return "chebyshev";
    case PressureSolver::Multilevel:
      return "multilevel";
  }
  return "?";
}

}  // namespace sluice
