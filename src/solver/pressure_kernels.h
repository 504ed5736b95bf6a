#pragma once
// Private to the solver: Eq. 24, Eq. 20 and Eq. 20/21/23 for one particle, inlined into the
// Jacobi sweep's loops (jacobi_sweep.cpp) and the pressure solvers (iisph.cpp).
#include <algorithm>

#include "solver/internal.h"
#include "solver/simulation.h"

namespace sluice {

[[gnu::always_inline]] inline Vec2 Simulation::pressure_acceleration_of(Index i, const PressureTerms& t) const {
  const std::vector<double>& pr = scratch_->p_over_rho2;
  const double pri = pr[i];
  Vec2 a = Vec2::Zero();
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) a += (pri + pr[ff_.j[k]]) * ff_.grad[k].cast<double>();
  a *= -t.mass;
  a -= (t.c_gamma3 * pri) * scratch_->grad_b[i];
  if (t.boundary_field) {
    Vec2 ab = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      ab += (boundary_.volume[b] * scratch_->pb_over_rho2[b]) * fb_.grad[k].cast<double>();
    }
    a -= t.gamma3_rho0 * ab;
  }
  return a;
}

// One relaxed Jacobi update of particle i (Algorithm 2's second solver loop): (Ap)_i of
// Eq. 20 from the accelerations a_p of i and its fluid neighbours, the update of Eq. 21
// with negative pressures clamped, and the predicted compression of Eq. 23 (stored in
// err). Reads neighbours' a_p, writes only particle i.
[[gnu::always_inline]] inline double Simulation::pressure_operator_of(Index i, const PressureTerms& t) const {
  const Vec2 ai = scratch_->a_p[i];
  double ap = 0.0;
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k)
    ap += (ai - scratch_->a_p[ff_.j[k]]).dot(ff_.grad[k].cast<double>());
  return t.dt * (t.mass * ap + t.gamma2 * ai.dot(scratch_->grad_b[i]));
}

// Chebyshev's semi-iteration (Golub & Varga 1961; projected as in Wang 2015): the
// Jacobi iterate p_hat of p_k is extrapolated to p_{k+1} = w (p_hat - p_{k-1}) + p_{k-1},
// clamped at zero like Eq. 21 (clamping p_hat first changes nothing: w >= 1). Shifts
// prev from p_{k-1} to p_k.
[[gnu::always_inline]] inline double chebyshev_extrapolate(double p_hat, double p_k, double& prev, double w) {
  const double p = std::max(w * (p_hat - prev) + prev, 0.0);
  prev = p_k;
  return p;
}

[[gnu::always_inline]] inline void Simulation::jacobi_update_of(Index i, const PressureTerms& t) {
  const double ap = pressure_operator_of(i, t);
  const double si = scratch_->s[i], aii = scratch_->a_ii[i];
  double p = aii != 0.0 ? std::max(fluid_.p[i] + t.omega / aii * (si - ap), 0.0) : 0.0;
  if (t.chebyshev > 0.0) p = chebyshev_extrapolate(p, fluid_.p[i], scratch_->p_prev[i], t.chebyshev);
  fluid_.p[i] = p;
  scratch_->p_over_rho2[i] = p / (fluid_.rho[i] * fluid_.rho[i]);
  scratch_->err[i] = std::max(t.err_scale * (ap - si), 0.0);
}

}  // namespace sluice
