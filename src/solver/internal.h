#pragma once
// Private to the solver's files: constants and helpers that several phases share.
// Not part of the public interface (src/solver/simulation.h).
#include <algorithm>
#include <chrono>

#include "core/types.h"

namespace sluice::solver_detail {

// Warm start p^(0) = 0.5 p(t - dt), the choice of [Ihm+14a]. A factor of 1 keeps the
// part of the previous pressure that the operator A barely sees (lattice-scale,
// checkerboard-like noise) forever; it then drives particles apart and a column at
// rest never settles (kinetic energy grows). Halving it every step lets it decay.
constexpr double kWarmStartFactor = 0.5;

class Stopwatch {
 public:
  Stopwatch() : t0_(std::chrono::steady_clock::now()) {}
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

// The gradient correction leaves particles whose support is less than this full (the
// trace is 2 in a full support) uncorrected: at the free surface 2 / trace grows without
// bound.
constexpr double kMinGradientTrace = 1.6;

// Relative compression of Eq. 15 in percent.
inline double compression_percent(double rho, double rho0) {
  return std::max(100.0 * (rho - rho0) / rho0, 0.0);
}

}  // namespace sluice::solver_detail
