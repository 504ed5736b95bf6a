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

const char* to_string(KernelKind k) { return k == KernelKind::CubicSpline ? "cubic_spline" : "wendland_c2"; }

// The cubic spline: the thesis' 2 spacings. Wendland C2: 2.0.
double default_support(KernelKind k) { return k == KernelKind::CubicSpline ? 2.0 : 2.0; }

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
