#include "solver/settings.h"

namespace sluice {

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
