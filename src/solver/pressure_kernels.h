#pragma once
// Private to the solver: Eq. 24, Eq. 20 and Eq. 20/21/23 for one particle, inlined into the
// Jacobi sweep's loops (jacobi_sweep.cpp) and the pressure solvers (iisph.cpp).
#include <algorithm>

#include "core/lanes.h"
#include "solver/internal.h"
#include "solver/simulation.h"

namespace sluice {

// The pressure stabilisation (solver.pressure_stabilisation = kappa; issue 37 item 2). Eq. 24's
// sum form gives a particle no force from its own pressure (sum_j grad W_ij = 0 inside the
// fluid), so on a lattice rows k - 1 and k + 1 alone push row k: a pressure alternating row
// by row, through the wall samples too, exerts no force, and Eq. 20 has it in its null
// space (docs/performance.md, "Pressure at the floor"). A row of the PPE gets
//   kappa a_ii rho_i^2 (q_i - q_bar_i),  q = p / rho^2,
// q_bar_i the mean of q over i's neighbours corrected by grad q ~ -a_i / rho_i (Eq. 24's own
// acceleration) so that a linear field, the hydrostatic one among them, is left alone: the
// compact Laplacian of Rhie & Chow's collocated grids (Brezzi & Pitkaranta's pressure
// stabilisation), which sees the alternating pattern with eigenvalue about 1.5 kappa.
// Only the wall band's rows (fluid with a boundary neighbour and their fluid neighbours)
// and the samples': the mode is closed where the walls close it, and the fluid inside keeps
// Eq. 20 (on the whole fluid, kappa = 3 let the shipped tank move at the default
// tolerance; docs/performance.md). Samples get twice kappa: their mean is one-sided.
inline constexpr double kSampleStabilisation = 2.0;
// Share of kappa a_ii added to the diagonal that the relaxed update divides by: all of it
// would slow the smooth modes (1 + kappa)-fold; 0.5 keeps the update stable on the
// lattice's spectrum (omega (lambda_max + 1.5 kappa) / (1 + 0.5 kappa) < 2 for kappa <= 10
// at omega = 0.5) and slows them by 1 + 0.5 kappa.
inline constexpr double kStabilisationDiagonal = 0.5;

// Eq. 24 for particle i; in a stabilised row also the mean of the stabilisation
// (stab_mean), from q of the neighbours summed in Eq. 24's own loops.
[[gnu::always_inline]] inline Vec2 Simulation::pressure_acceleration_of(Index i, const PressureTerms& t) const {
  double q_sum = 0.0;
  if (!stabilised_row(i, t)) return eq24_of<false>(i, t, q_sum);
  const Vec2 a = eq24_of<true>(i, t, q_sum);
  scratch_->stab_mean[i] = stabilisation_mean_of(i, a, q_sum, t);
  return a;
}

// Eq. 24 for particle i; with kSumQ also adds to q_sum the q = p / rho^2 of its neighbours
// that the stabilisation's mean reads (fluid, then samples where they carry a pressure of
// their own), in the order of the pairs: one pass over them instead of two.
template <bool kSumQ>
[[gnu::always_inline]] inline Vec2 Simulation::eq24_of(Index i, const PressureTerms& t, double& q_sum) const {
  const std::vector<double>& pr = scratch_->p_over_rho2;
  const double pri = pr[i];
  Vec2 a = Vec2::Zero();
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
    const double q = pr[ff_.j[k]];
    a += (pri + q) * ff_.grad[k].cast<double>();
    if constexpr (kSumQ) q_sum += q;
  }
  a *= -t.mass;
  a -= (t.c_gamma3 * pri) * scratch_->grad_b[i];
  if (t.boundary_field) {
    Vec2 ab = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const double q = scratch_->pb_over_rho2[b];
      ab += (boundary_.volume[b] * q) * fb_.grad[k].cast<double>();
      if constexpr (kSumQ) q_sum += q;
    }
    a -= t.gamma3_rho0 * ab;
  }
  return a;
}

// q_bar_i of the stabilisation from q_sum, the sum of q over i's neighbours (eq24_of), and
// i's acceleration a_i.
inline double Simulation::stabilisation_mean_of(Index i, const Vec2& a_i, double q_sum, const PressureTerms& t) const {
  const Index count = ff_.count(i) + (t.boundary_field ? fb_.count(i) : 0);
  if (count == 0) return scratch_->p_over_rho2[i];
  return q_sum / static_cast<double>(count) + a_i.dot(scratch_->stab_offset[i]) / fluid_.rho[i];
}

// Whether fluid row i carries the stabilisation's term: kappa > 0 and i in the wall band.
// Callers test it once per row: stabilisation_of and stab_mean serve these rows only.
inline bool Simulation::stabilised_row(Index i, const PressureTerms& t) const {
  return t.stabilisation > 0.0 && scratch_->stab_on[i];
}

// The stabilisation's term of a stabilised row i (stabilised_row): kappa a_ii rho_i^2
// (q_i - q_bar_i).
inline double Simulation::stabilisation_of(Index i, const PressureTerms& t) const {
  const double rho = fluid_.rho[i];
  return t.stabilisation * scratch_->a_ii[i] * rho * rho * (scratch_->p_over_rho2[i] - scratch_->stab_mean[i]);
}

// One relaxed Jacobi update of particle i (Algorithm 2's second solver loop): (Ap)_i of
// Eq. 20 from the accelerations a_p of i and its fluid neighbours, the update of Eq. 21
// with negative pressures clamped, and the predicted compression of Eq. 23 (stored in
// err). Reads neighbours' a_p, writes only particle i.
[[gnu::always_inline]] inline double Simulation::pressure_operator_of(Index i, const PressureTerms& t) const {
  const Vec2 ai = scratch_->a_p[i];
  // (a_i - a_j) . grad W_ij with both components in one register: the scalar dot's
  // operations and order, x product plus y product (the same bits), in fewer instructions.
  const Double2 ai2 = lanes(ai.x(), ai.y());
  double ap = 0.0;
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k)
    ap += dot_lanes(ai2 - load_lanes(scratch_->a_p[ff_.j[k]].data()), widen_lanes(ff_.grad[k].data()));
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
  double ap = pressure_operator_of(i, t);
  const double si = scratch_->s[i];
  double aii = scratch_->a_ii[i];
  if (stabilised_row(i, t)) {
    ap += stabilisation_of(i, t);
    aii *= 1.0 + kStabilisationDiagonal * t.stabilisation;
  }
  double p = aii != 0.0 ? std::max(fluid_.p[i] + t.omega / aii * (si - ap), 0.0) : 0.0;
  if (t.chebyshev > 0.0) p = chebyshev_extrapolate(p, fluid_.p[i], scratch_->p_prev[i], t.chebyshev);
  fluid_.p[i] = p;
  scratch_->p_over_rho2[i] = p / (fluid_.rho[i] * fluid_.rho[i]);
  scratch_->err[i] = std::max(t.err_scale * (ap - si), 0.0);
}

}  // namespace sluice
