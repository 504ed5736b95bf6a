// Chebyshev's semi-iteration on Algorithm 2's relaxed Jacobi (Golub & Varga 1961;
// projected as in Wang 2015): the same sweeps, each update after the delay extrapolated
// (chebyshev_extrapolate, pressure_kernels.h).
#include <memory>

#include "solver/pressure/pressure_solver.h"
#include "solver/pressure/system.h"

namespace sluice {

namespace {

// Chebyshev's residual polynomial is steep at the Jacobi eigenvalue 1, so the modes the
// operator barely sees grow faster within a solve and the old pressure must be forgotten
// faster than Jacobi's 0.5 (pressure_solver.h): at 0.5 a closed tank at rest gained 0.99 J/m in
// 10 s, at 0.1 0.025 J/m (docs/performance.md, "Pressure solvers").
constexpr double kChebyshevWarmStartFactor = 0.1;

// Chebyshev's extrapolation starts after this many plain Jacobi iterations (the delay of
// Wang 2015): a step that converges within them, a fluid at rest, is Jacobi's bit for bit.
constexpr int kChebyshevDelay = 3;

// The weight w_{l+1} of Chebyshev's semi-iteration in iteration l (0-based) for a Jacobi
// iteration of spectral radius rho: 1, 2 / (2 - rho^2), then 4 / (4 - rho^2 w_l). Its
// residual polynomial is T_l(mu / rho) / T_l(1 / rho) on each eigenvalue mu of the
// Jacobi iteration, below 1 for every |mu| < 1: any rho converges where Jacobi does, the
// modes with |mu| <= rho fastest. Modes at mu near 1 (the lattice-scale near-null modes of
// Eq. 24's sum form) it leaves alone, as Jacobi does.
double chebyshev_weight(int l, double previous, double rho) {
  if (l == 0) return 1.0;
  if (l == 1) return 2.0 / (2.0 - rho * rho);
  return 4.0 / (4.0 - rho * rho * previous);
}

class ChebyshevSolver final : public PressureSolverMethod {
 public:
  const char* name() const override { return "chebyshev"; }
  double warm_start_factor() const override { return kChebyshevWarmStartFactor; }

  PressureSolveResult iterate(PressureSystem& system, const PressureSolveLimits& limits) override {
    const double rho = system.settings().chebyshev_rho;
    system.save_previous_iterate();
    int l = 0;
    double avg = 0.0, w = 0.0;  // w = 0: no extrapolation yet
    do {
      if (l >= kChebyshevDelay) {
        w = chebyshev_weight(l - kChebyshevDelay, w, rho);
        system.set_extrapolation_weight(w);
      }
      avg = system.sweep();
      ++l;
    } while ((avg > limits.tolerance_percent || l < limits.min_iterations) && l < limits.max_iterations);
    // The last extrapolation is unchecked (Eq. 23 was measured at p_k, before it) and can
    // overshoot where the clamp is active; keep the iterate that was measured.
    if (w > 0.0) system.restore_saved_iterate();
    return {l, avg};
  }
};

}  // namespace

std::unique_ptr<PressureSolverMethod> make_chebyshev_solver() { return std::make_unique<ChebyshevSolver>(); }

}  // namespace sluice
