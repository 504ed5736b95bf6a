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

const char* to_string(PressureSolver p) { return p == PressureSolver::Chebyshev ? "chebyshev" : "jacobi"; }

}  // namespace sluice
