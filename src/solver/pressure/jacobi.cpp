// Algorithm 2's solver loop: relaxed Jacobi sweeps (Eq. 24, then 20, 21, 23) until the
// average predicted compression is within the tolerance.
#include <memory>

#include "solver/pressure/pressure_solver.h"
#include "solver/pressure/system.h"

namespace sluice {

PressureSolveResult iterate_jacobi(PressureSystem& system, const PressureSolveLimits& limits) {
  int l = 0;
  double avg = 0.0;
  do {
    avg = system.sweep();
    ++l;
  } while ((avg > limits.tolerance_percent || l < limits.min_iterations) && l < limits.max_iterations);
  return {l, avg};
}

namespace {

class JacobiSolver final : public PressureSolverMethod {
 public:
  const char* name() const override { return "jacobi"; }
  double warm_start_factor() const override { return kJacobiWarmStartFactor; }
  PressureSolveResult iterate(PressureSystem& system, const PressureSolveLimits& limits) override {
    return iterate_jacobi(system, limits);
  }
};

}  // namespace

std::unique_ptr<PressureSolverMethod> make_jacobi_solver() { return std::make_unique<JacobiSolver>(); }

}  // namespace sluice
