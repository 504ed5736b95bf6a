#include "solver/pressure/pressure_solver.h"

namespace sluice {

std::unique_ptr<PressureSolverMethod> make_pressure_solver(PressureSolver kind) {
  switch (kind) {  // no default: a new PressureSolver without a scheme here is a warning (-Wswitch)
    case PressureSolver::Jacobi:
      return make_jacobi_solver();
    case PressureSolver::Chebyshev:
      return make_chebyshev_solver();
    case PressureSolver::Multilevel:
      return make_multilevel_solver();
  }
  return make_jacobi_solver();
}

}  // namespace sluice
