#include "solver/simulation.h"

#include "core/lanes.h"
#include "core/parallel.h"
#include "core/select.h"
#include "solver/internal.h"

namespace sluice {

// a_v of every fluid particle (the pair sums of apply_nonpressure); kViscous: with Eq. 12.
template <bool kViscous>
void Simulation::viscous_accelerations(double dt, double avc, std::vector<Vec2>& a_v) {
  const double nu = settings_.viscosity, rho0 = settings_.rest_density;
  const Index n = fluid_.size();
  const double eps = 0.01 * setup_.spacing * setup_.spacing;
  const bool work = has_moving_boundaries();
  // m_j / rho_j once per particle, not once per pair (the same bits).
  std::vector<double>& vol = scratch_->volume;
  if (kViscous) {
    vol.resize(n);
    parallel_for(n, [&](Index i) { vol[i] = mass_ / fluid_.rho[i]; });
  }
  parallel_for(n, [&](Index i) {
    const Vec2 xi = fluid_.x[i], vi = fluid_.v[i];
    const double rhoi = fluid_.rho[i];
    Vec2 lap = Vec2::Zero(), art = Vec2::Zero();
    auto pair = [&](Index k) {
      const Index j = ff_.j[k];
      const Vec2 xij = xi - fluid_.x[j], vij = vi - fluid_.v[j], gw = ff_.grad[k].cast<double>();
      const double r2 = xij.squaredNorm() + eps, vx = vij.dot(xij);
      if (kViscous) lap += vol[j] * (xij.dot(gw) / r2) * vij;
      // A select, not a branch: approaching and receding pairs alternate at random, and
      // adding 0 * grad W leaves the sum's bits as the branch left them. It picks v_ij . x_ij
      // before the division, through masks: a select after it let GCC branch around the
      // division, mispredicted in about every second pair.
      const double approach = mask_select(vx < 0.0, vx, 0.0);
      art += (mass_ * approach / (r2 * 0.5 * (rhoi + fluid_.rho[j]))) * gw;
    };
    // Two pairs at a time, as pair() does each (one division instruction for both), summed
    // in list order: the same bits.
    Index kf = ff_.offset[i];
    for (const Index end = ff_.offset[i + 1]; kf + 1 < end; kf += 2) {
      const Index j0 = ff_.j[kf], j1 = ff_.j[kf + 1];
      const Vec2 x0 = xi - fluid_.x[j0], x1 = xi - fluid_.x[j1];
      const Vec2 v0 = vi - fluid_.v[j0], v1 = vi - fluid_.v[j1];
      const Vec2 g0 = ff_.grad[kf].cast<double>(), g1 = ff_.grad[kf + 1].cast<double>();
      const Double2 xx = lanes(x0.x(), x1.x()), xy = lanes(x0.y(), x1.y());
      const Double2 r2 = (xx * xx + xy * xy) + eps;
      const Double2 vx = lanes(v0.x(), v1.x()) * xx + lanes(v0.y(), v1.y()) * xy;
      if (kViscous) {
        const Double2 dg = xx * lanes(g0.x(), g1.x()) + xy * lanes(g0.y(), g1.y());
        const Double2 s2 = lanes(vol[j0], vol[j1]) * (dg / r2);
        lap += s2[0] * v0;
        lap += s2[1] * v1;
      }
      const Double2 approach = select_lanes(vx < 0.0, vx, splat(0.0));
      const Double2 c2 = mass_ * approach / (r2 * 0.5 * (rhoi + lanes(fluid_.rho[j0], fluid_.rho[j1])));
      art += c2[0] * g0;
      art += c2[1] * g1;
    }
    if (kf < ff_.offset[i + 1]) pair(kf);
    Vec2 acc = kViscous ? Vec2(2.0 * nu * lap + avc * art) : Vec2(avc * art);
    // Walls (free slip unless the scene says no_slip): the artificial viscosity sees only the
    // velocity along the wall's normal n_i and pushes only along it, so that sliding along a
    // wall costs nothing; a no-slip wall adds Eq. 12 with its own viscosity. n_i is the
    // direction of sum_b V_b grad W_ib (the wall as particle i sees it; its sign cancels).
    // The thesis is silent; Monaghan's viscosity against walls acts as a friction whose
    // coefficient alpha c h is set by the column's height (docs/validation.md).
    Vec2 n_i = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k)
      n_i += boundary_.volume[fb_.j[k]] * fb_.grad[k].cast<double>();
    const double len = n_i.norm();
    if (len > 0.0) n_i /= len;  // else: no wall neighbour, or walls cancelling on both sides
    double w = 0.0;
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const Vec2 xib = xi - boundary_.x[b], vib = vi - boundary_.v[b], gw = fb_.grad[k].cast<double>();
      const double r2 = xib.squaredNorm() + eps, vb = boundary_.volume[b];
      const double nu_b = boundary_.wall_nu[b];
      Vec2 a = Vec2::Zero();
      if (nu_b > 0.0) a = (2.0 * nu_b * vb * (xib.dot(gw) / r2)) * vib;
      const double vx = vib.dot(n_i) * n_i.dot(xib);
      if (vx < 0.0) a += ((avc * rho0 * vb * vx / (r2 * 0.5 * (rhoi + rho0))) * gw.dot(n_i)) * n_i;
      acc += a;
      if (work) w += a.dot(boundary_.v[b]);
    }
    a_v[i] = acc;
    if (work) scratch_->work[i] += dt * mass_ * w;
  });
}

// v* = v + dt (a_v + g): the viscosity of Eq. 12 and Monaghan's artificial viscosity
// (1992, Eq. 4.1; the thesis has none), against fluid neighbours and, on the velocity along
// the wall's normal only, boundary neighbours (with their own velocity, m_b = rho0 V_b,
// rho_b = rho0); a no-slip object adds Eq. 12 with its wall_viscosity:
//   a_i += -sum_j m_j Pi_ij grad W_ij,  Pi_ij = -alpha c h mu_ij / rho_ij for v_ij . x_ij < 0,
//   mu_ij = v_ij . x_ij / (|x_ij|^2 + 0.01 h^2),  rho_ij = (rho_i + rho_j) / 2.
// With both off and no no-slip wall the pass is skipped. The boundary pairs' share of a_v, times
// the boundary velocity, is the boundaries' work on the fluid (scratch_->work).
void Simulation::apply_nonpressure(double dt) {
  const Vec2 g = settings_.gravity;
  const double nu = settings_.viscosity;
  const double avc = settings_.artificial_viscosity * sound_speed_ * setup_.spacing;
  const Index n = fluid_.size();
  if (nu <= 0.0 && avc <= 0.0 && !has_no_slip_) {
    parallel_for(n, [&](Index i) { fluid_.v[i] += dt * g; });
    return;
  }
  std::vector<Vec2>& a_v = scratch_->a_p;  // reused as scratch: a_p is recomputed later
  a_v.resize(n);
  // Without physical viscosity (the default) the pass skips Eq. 12's terms, a division and
  // a gather per pair: the same bits, as those terms are exactly zero then.
  if (nu > 0.0)
    viscous_accelerations<true>(dt, avc, a_v);
  else
    viscous_accelerations<false>(dt, avc, a_v);
  parallel_for(n, [&](Index i) { fluid_.v[i] += dt * (a_v[i] + g); });
}

}  // namespace sluice
