#include "solver/simulation.h"

#include <algorithm>

#include "core/lanes.h"
#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure/pressure_solver.h"
#include "solver/pressure/system.h"
#include "solver/pressure_kernels.h"

namespace sluice {

using namespace solver_detail;

// ---------------------------------------------------------------------------------
// IISPH pressure solver (chapter 3, Algorithm 2): the PPE's set-up and the step's solve;
// the iteration schemes (relaxed Jacobi, Chebyshev, multilevel) are in solver/pressure/.
//
// With the pressure accelerations of Eq. 24, the PPE of Eq. 17 for fluid particle i is
//   (Ap)_i = dt [ sum_f m_f (a_i - a_f) . grad W_if + gamma2 sum_b m_b (a_i - a_b) . grad W_ib ]
//          = s_i = (rho0 - rho*_i) / dt                                      (Eq. 19, 20)
// where rho*_i = rho_i + dt [ sum_f m_f v*_if . grad W_if + gamma2 sum_b m_b v*_ib . grad W_ib ]
// (Eq. 16; the boundary particle enters with its own velocity, a_b = 0 for a wall).
// The predicted density after the pressure update is rho*_i + dt (Ap)_i, so the
// relative compression of Eq. 23 is 100 dt ((Ap)_i - s_i) / rho0 (the thesis writes
// Eq. 23 without the factor dt because its A and s carry 1/dt).
//
// Diagonal (Eq. 22/26), derived for the chosen boundary method: writing
//   a_i = p_i D_i + (terms without p_i),
//   D_i = -(1/rho_i^2) (sum_f m_f grad W_if + c gamma3 grad_b_i) - E_i,
// with c = 2 for mirroring (p_b/rho_b^2 = p_i/rho_i^2) and 1 otherwise, and for
// extrapolation E_i = (gamma3 / rho0^2) sum_b m_b (W_bi / sum_f W_bf) grad W_ib, the
// share of p_i in each p_b of Eq. 25. Each fluid neighbour f holds p_i through
// a_f = ... - m_i (p_i/rho_i^2) grad W_fi (and, with extrapolation, through the p_b of
// its walls: extrapolation_coupling), so
//   a_ii = dt [ D_i . (sum_f m_f grad W_if + gamma2 grad_b_i) - (m_i^2/rho_i^2) sum_f |grad W_if|^2 ]
//          (+ the extrapolation coupling).
// tests/test_pressure_system.cpp checks a_ii against the operator by finite differences.
// Eq. 26 as printed is c = 1 and E = 0 (boundary_diagonal = false). With pressure
// boundaries p_b is an unknown of its own (prepare_solved_boundary): c = 1, E = 0, and the
// iteration stops when the samples' average predicted compression is within the
// tolerance too (st.avg_error_percent is the larger of the two averages).
void Simulation::solve_pressure_iisph(double dt, StepStats& st) {
  const Index active_samples = prepare_pressure_system(dt);
  iterate_pressure(dt, active_samples, st);
}

// The share of p_i that reaches (Ap)_i through its fluid neighbours' extrapolated walls:
// a_f holds -(gamma3 / rho0^2) m_b p_b grad W_fb and p_b (Eq. 25) holds p_i with weight
// W_bi / sum_f W_bf, so d(Ap)_i / dp_i gains
//   dt m (gamma3 / rho0^2) sum_b m_b (W_bi / sum_f W_bf) sum_f grad W_fb . grad W_if
// (this returns the double sum). Zero away from walls; the samples b are i's own.
double Simulation::extrapolation_coupling(Index i) const {
  const double rho0 = settings_.rest_density;
  double sum = 0.0;
  for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
    const Index b = fb_.j[k];
    if (scratch_->ext_wsum[b] <= 0.0) continue;
    const double weight = rho0 * boundary_.volume[b] * fb_.w[k] / scratch_->ext_wsum[b];
    double dots = 0.0;
    for (Index kf = ff_.offset[i]; kf < ff_.offset[i + 1]; ++kf) {
      const Index f = ff_.j[kf];
      for (Index kb = fb_.offset[f]; kb < fb_.offset[f + 1]; ++kb)
        if (fb_.j[kb] == b) {
          dots += fb_.grad[kb].cast<double>().dot(ff_.grad[kf].cast<double>());
          break;
        }
    }
    sum += weight * dots;
  }
  return sum;
}

// The set-up of the PPE: boundary terms, s_i (Eq. 19), a_ii (Eq. 26), p^(0) (Eq. 21),
// and the samples' rows for pressure boundaries. Returns the samples with a row.
Index Simulation::prepare_pressure_system(double dt) {
  const Index n = fluid_.size();
  const SolverSettings& s = settings_;
  const double rho0 = s.rest_density, g2 = s.gamma2, g3 = s.gamma3, omega = omega_;
  prepare_boundary_terms();
  scratch_->s.resize(n);
  scratch_->a_ii.resize(n);
  scratch_->p_over_rho2.resize(n);
  const bool mirror = s.boundary_pressure == BoundaryPressure::Mirroring;
  const bool extrapolate = s.boundary_pressure == BoundaryPressure::Extrapolation;
  const bool solved_boundary = s.boundary_pressure == BoundaryPressure::Solved;
  // Boundary samples with a fluid neighbour (their rows of the PPE).
  const Index active_samples = solved_boundary ? prepare_solved_boundary(dt) : 0;
  const double c = (mirror && s.boundary_diagonal) ? 2.0 : 1.0;
  const bool coupling = extrapolate && s.boundary_diagonal;
  const bool thesis_init = s.pressure_init == PressureInit::Thesis;
  const double warm = pressure_method().warm_start_factor();  // p^(0) = warm p(t - dt)
  const double vb_scale = boundary_velocity_in_source_ ? 1.0 : 0.0;

  // Source term s_i (Eq. 19), diagonal a_ii (Eq. 26), initial pressure p^(0) (Eq. 21).
  parallel_for(n, [&](Index i) {
    const Vec2 vi = fluid_.v[i];
    const double rhoi = fluid_.rho[i];
    double div = 0.0, grad2 = 0.0;
    // x and y in one register each pair, the dots' lanes added x then y: the bits of
    // (v_i - v_j) . grad W, sum grad W and |grad W|^2 computed one component at a time.
    const Double2 vi2 = lanes(vi.x(), vi.y());
    Double2 sum_grad2 = splat(0.0);
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      const Double2 gw = widen_lanes(ff_.grad[k].data());
      div += dot_lanes(vi2 - load_lanes(fluid_.v[ff_.j[k]].data()), gw);
      sum_grad2 += gw;
      grad2 += dot_lanes(gw, gw);
    }
    div *= mass_;
    const Vec2 sum_grad = mass_ * Vec2(sum_grad2[0], sum_grad2[1]);
    double div_b = 0.0;
    Vec2 e = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const double mb = rho0 * boundary_.volume[b];
      div_b += mb * (vi - vb_scale * boundary_.v[b]).dot(fb_.grad[k].cast<double>());
      if (coupling && scratch_->ext_wsum[b] > 0.0)
        e += (mb * fb_.w[k] / scratch_->ext_wsum[b]) * fb_.grad[k].cast<double>();
    }
    scratch_->s[i] = (rho0 - rhoi) / dt - (div + g2 * div_b);
    const double inv_rho2 = 1.0 / (rhoi * rhoi);
    const Vec2 d = -inv_rho2 * (sum_grad + (c * g3) * scratch_->grad_b[i]) - (g3 / (rho0 * rho0)) * e;
    double aii = dt * (d.dot(sum_grad + g2 * scratch_->grad_b[i]) - mass_ * mass_ * inv_rho2 * grad2);
    if (coupling) aii += dt * mass_ * (g3 / (rho0 * rho0)) * extrapolation_coupling(i);
    scratch_->a_ii[i] = aii;
    double p0 = warm * fluid_.p[i];
    if (thesis_init) p0 = aii != 0.0 ? std::max(omega * scratch_->s[i] / aii, 0.0) : 0.0;
    fluid_.p[i] = p0;
    scratch_->p_over_rho2[i] = p0 * inv_rho2;
  });
  if (stabilisation_kappa(s) > 0.0) prepare_stabilisation();

  return active_samples;
}

// The rows the stabilisation acts on, the wall band (mark_wall_band; the multilevel wall
// sweeps' plan_wall_band reuses it), and the mean offset x_j - x_i of their neighbours that
// its mean reads (pressure_kernels.h): the fluid neighbours, and the samples where they
// carry a pressure of their own.
void Simulation::prepare_stabilisation() {
  const Index n = fluid_.size();
  const bool samples = pressure_terms(0.0).boundary_field;
  mark_wall_band(scratch_->stab_on, scratch_->wall_flag_a);
  scratch_->stab_offset.resize(n);
  scratch_->stab_mean.resize(n);
  parallel_for(n, [&](Index i) {
    if (!scratch_->stab_on[i]) return;
    const Vec2 xi = fluid_.x[i];
    Vec2 sum = Vec2::Zero();
    Index count = ff_.count(i);
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) sum += fluid_.x[ff_.j[k]] - xi;
    if (samples) {
      for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) sum += boundary_.x[fb_.j[k]] - xi;
      count += fb_.count(i);
    }
    scratch_->stab_offset[i] = count > 0 ? Vec2(sum / static_cast<double>(count)) : Vec2::Zero();
  });
}

// The scheme that solves this step's PPE (solver/pressure/): made again when
// settings_.pressure_solver has changed since the last step.
PressureSolverMethod& Simulation::pressure_method() {
  if (!pressure_method_ || pressure_method_kind_ != settings_.pressure_solver) {
    pressure_method_ = make_pressure_solver(settings_.pressure_solver);
    pressure_method_kind_ = settings_.pressure_solver;
  }
  return *pressure_method_;
}

// Algorithm 2's solver loop, run by the chosen scheme (solver/pressure/jacobi.cpp,
// chebyshev.cpp, multilevel.cpp) through the step's PressureSystem, then the accelerations of the final
// pressures.
void Simulation::iterate_pressure(double dt, Index active_samples, StepStats& st) {
  const Index n = fluid_.size();
  const SolverSettings& s = settings_;
  const Index block = plan_jacobi_sweep();  // how the sweeps are scheduled (jacobi_sweep.cpp)
  scratch_->err.resize(n);
  scratch_->a_p.resize(n);
  PressureSystem system(*this, pressure_terms(dt), block, active_samples);
  const PressureSolveResult r =
      pressure_method().iterate(system, {s.tolerance_percent, s.min_iterations, s.max_iterations});
  // Integrate the accelerations of the final pressures ([Ihm+14a], Algorithm 1); the
  // loop's a_p belong to the iterate before the last update.
  update_boundary_pressure();
  compute_pressure_acceleration();
  if (has_moving_boundaries()) add_boundary_pressure_work(dt);
  st.iterations = r.iterations;
  st.avg_error_percent = r.avg_error_percent;
  st.max_error_percent = system.largest_error();
}

// Pressure boundaries (Band et al. 2018, "Pressure boundaries for implicit incompressible
// SPH", ACM TOG 37(2)): the density constraint of each boundary sample with fluid
// neighbours joins the PPE, so p_b is its Lagrange multiplier and the boundary term of
// Eq. 24 becomes a constraint force, which does no work while the constraints hold.
// The sample's counterparts of Eq. 19 and 22, with a_b = 0 (its motion is scripted):
//   s_b = (rho0 - rho_b) / dt - sum_f m_f (v_b - v*_f) . grad W_bf,
//   (Ap)_b = -dt sum_f m_f a_f . grad W_bf,
//   a_bb = d(Ap)_b / dp_b = -dt gamma3 (V_b m / rho0) sum_f |grad W_bf|^2.
Index Simulation::prepare_solved_boundary(double dt) {
  const SolverSettings& s = settings_;
  const double rho0 = s.rest_density, inv_rho0_2 = 1.0 / (rho0 * rho0);
  const bool thesis_init = s.pressure_init == PressureInit::Thesis;
  const double warm = pressure_method().warm_start_factor();
  const Index nb = boundary_.size();
  const double vb_scale = boundary_velocity_in_source_ ? 1.0 : 0.0;
  scratch_->bnd_s.resize(nb);
  scratch_->bnd_aii.resize(nb);
  parallel_for(nb, [&](Index b) {
    double wsum = 0.0, div = 0.0, grad2 = 0.0, lumped = 0.0;
    for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
      const Index f = bf_.j[k];
      const Vec2 gw = bf_.grad[k].cast<double>();
      wsum += bf_.w[k];
      div += (vb_scale * boundary_.v[b] - fluid_.v[f]).dot(gw);
      grad2 += gw.squaredNorm();
      lumped += gw.dot(scratch_->grad_b[f]);
    }
    // rho_b as in boundary_density, summed in the same pass over the sample's pairs.
    const double sb = (rho0 - (mass_ * wsum + sample_wall_share_[b] * rho0)) / dt - mass_ * div;
    // The row's diagonal, or its lumped sum over all samples that share a fluid neighbour
    // (dt gamma3 m / rho0^2 sum_f grad W_bf . grad_b_f) when larger: samples denser than
    // the fluid, or a thin plate sampled on both sides, are near-duplicate constraints,
    // and Jacobi with the plain diagonal overshoots on them by their number and diverges.
    const double abb = std::min(-dt * s.gamma3 * boundary_.volume[b] / rho0 * mass_ * grad2,
                                dt * s.gamma3 * mass_ / (rho0 * rho0) * lumped);
    scratch_->bnd_s[b] = sb;
    scratch_->bnd_aii[b] = abb;
    double p0 = abb != 0.0 ? warm * boundary_.p[b] : 0.0;
    if (thesis_init) p0 = abb != 0.0 ? std::max(omega_ * sb / abb, 0.0) : 0.0;
    boundary_.p[b] = p0;
    scratch_->pb_over_rho2[b] = p0 * inv_rho0_2;
  });
  return static_cast<Index>(parallel_sum(nb, [&](Index b) { return scratch_->bnd_aii[b] != 0.0 ? 1.0 : 0.0; }));
}

// (Ap)_b of a pressure-boundary sample (prepare_solved_boundary) from the fluid's a_p.
double Simulation::sample_operator_of(Index b, const PressureTerms& t) const {
  double ap = 0.0;
  for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k)
    ap -= scratch_->a_p[bf_.j[k]].dot(bf_.grad[k].cast<double>());
  return ap * (t.dt * t.mass);
}

// The stabilisation's term of a sample's row (pressure_kernels.h), with kSampleStabilisation
// kappa: its fluid neighbours' q carried to the sample along grad q ~ -a_f / rho_f, so that
// a linear field is left alone at a one-sided sample.
double Simulation::sample_stabilisation_of(Index b, const PressureTerms& t) const {
  const Index count = bf_.count(b);
  if (count == 0) return 0.0;
  const Vec2 xb = boundary_.x[b];
  double sum = 0.0;
  for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
    const Index f = bf_.j[k];
    sum += scratch_->p_over_rho2[f] - scratch_->a_p[f].dot(xb - fluid_.x[f]) / fluid_.rho[f];
  }
  const double rho0 = settings_.rest_density;
  return kSampleStabilisation * t.stabilisation * scratch_->bnd_aii[b] * rho0 * rho0 *
         (scratch_->pb_over_rho2[b] - sum / static_cast<double>(count));
}

// Eq. 21 for every boundary sample, from the accelerations a_p of the iteration (all
// computed before: the sweep has finished), clamped at zero like the fluid's. Returns
// the sum of the samples' predicted compression (Eq. 23) at these accelerations.
double Simulation::jacobi_update_boundary(const PressureTerms& t) {
  const double inv_rho0_2 = 1.0 / (settings_.rest_density * settings_.rest_density);
  return parallel_sum(boundary_.size(), [&](Index b) {
    double abb = scratch_->bnd_aii[b];
    if (abb == 0.0) return 0.0;  // no fluid neighbour: p_b stays 0
    double ap = sample_operator_of(b, t);
    if (t.stabilisation > 0.0) {
      ap += sample_stabilisation_of(b, t);
      abb *= 1.0 + kStabilisationDiagonal * kSampleStabilisation * t.stabilisation;
    }
    double p = std::max(boundary_.p[b] + t.omega / abb * (scratch_->bnd_s[b] - ap), 0.0);
    if (t.chebyshev > 0.0) p = chebyshev_extrapolate(p, boundary_.p[b], scratch_->pb_prev[b], t.chebyshev);
    boundary_.p[b] = p;
    scratch_->pb_over_rho2[b] = p * inv_rho0_2;
    return std::max(t.err_scale * (ap - scratch_->bnd_s[b]), 0.0);
  });
}

// Eq. 24: a_i = - sum_f m_f (p_i/rho_i^2 + p_f/rho_f^2) grad W_if
//               - gamma3 sum_b m_b (p_i/rho_i^2 + p_b/rho_b^2) grad W_ib.
// Mirroring (4.2.2) sets p_b/rho_b^2 = p_i/rho_i^2, zero pressure (4.2.3) p_b = 0, so
// their boundary sum is c gamma3 (p_i/rho_i^2) grad_b_i with c = 2 or 1.
Simulation::PressureTerms Simulation::pressure_terms(double dt) const {
  const SolverSettings& s = settings_;
  PressureTerms t;
  t.mass = mass_;
  t.c_gamma3 = (s.boundary_pressure == BoundaryPressure::Mirroring ? 2.0 : 1.0) * s.gamma3;
  t.gamma3_rho0 = s.gamma3 * s.rest_density;
  t.boundary_field =
      s.boundary_pressure == BoundaryPressure::Extrapolation || s.boundary_pressure == BoundaryPressure::Solved;
  t.gamma2 = s.gamma2;
  t.omega = omega_;
  t.stabilisation = stabilisation_kappa(s);
  t.dt = dt;
  t.err_scale = 100.0 * dt / s.rest_density;
  return t;
}

void Simulation::compute_pressure_acceleration() {
  PressureTerms t = pressure_terms(0.0);
  t.stabilisation = 0.0;  // the accelerations alone
  compute_pressure_acceleration(t);
}

// Eq. 24 for every fluid particle with the sweep's terms t: with the stabilisation on, also
// the means of its rows (stab_mean) that the updates of Eq. 20 then read.
void Simulation::compute_pressure_acceleration(const PressureTerms& t) {
  scratch_->a_p.resize(fluid_.size());
  parallel_for(fluid_.size(), [&](Index i) { scratch_->a_p[i] = pressure_acceleration_of(i, t); });
}

}  // namespace sluice
