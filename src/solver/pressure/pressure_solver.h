#pragma once
// The iteration schemes for IISPH's pressure Poisson equation (Eq. 17/20), one file each:
// jacobi.cpp (Algorithm 2's relaxed Jacobi), chebyshev.cpp (the same sweeps with
// Chebyshev's semi-iteration), multilevel.cpp (the sweeps with a Galerkin coarse
// correction, coarse_level.cpp). Each iterates through a PressureSystem (system.h) that
// Simulation::iterate_pressure builds for the step; the solver's set-up (Eq. 19, 22/26)
// and its hot kernels (pressure_kernels.h, jacobi_sweep.cpp) stay in the Simulation.
// Private to the solver (src/solver/simulation.h is the public interface).
#include <memory>

#include "solver/settings.h"

namespace sluice {

class PressureSystem;

// Warm start p^(0) = 0.5 p(t - dt), the choice of [Ihm+14a] (Jacobi, multilevel). A factor
// of 1 keeps the part of the previous pressure that the operator A barely sees
// (lattice-scale, checkerboard-like noise) forever; it then drives particles apart and a
// column at rest never settles (kinetic energy grows). Halving it every step lets it decay.
constexpr double kJacobiWarmStartFactor = 0.5;

// When iterate stops: the average predicted compression (Eq. 23) within tolerance_percent
// after at least min_iterations, or after max_iterations in any case.
struct PressureSolveLimits {
  double tolerance_percent;
  int min_iterations, max_iterations;
};

struct PressureSolveResult {
  int iterations = 0;
  double avg_error_percent = 0;  // at exit (StepStats::avg_error_percent)
};

// One iteration scheme for the PPE of Eq. 17/20.
class PressureSolverMethod {
 public:
  virtual ~PressureSolverMethod() = default;
  virtual const char* name() const = 0;
  virtual double warm_start_factor() const = 0;  // p^(0) = factor * p(t - dt) (Eq. 21's start)
  // Iterates on the set-up system until converged (or max_iterations); leaves in the
  // fluid's and samples' pressures the iterate whose accelerations are integrated.
  virtual PressureSolveResult iterate(PressureSystem& system, const PressureSolveLimits& limits) = 0;
};

std::unique_ptr<PressureSolverMethod> make_pressure_solver(PressureSolver kind);

// Algorithm 2's loop: relaxed Jacobi sweeps until the limits' stopping test (jacobi.cpp);
// the Jacobi scheme, and the multilevel scheme's steps that start with an impact.
PressureSolveResult iterate_jacobi(PressureSystem& system, const PressureSolveLimits& limits);

// Each scheme's own factory (jacobi.cpp, chebyshev.cpp, multilevel.cpp), for make_pressure_solver.
std::unique_ptr<PressureSolverMethod> make_jacobi_solver();
std::unique_ptr<PressureSolverMethod> make_chebyshev_solver();
std::unique_ptr<PressureSolverMethod> make_multilevel_solver();

}  // namespace sluice
