#include "solver/simulation.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

using namespace solver_detail;

void Simulation::find_neighbors_phase() {
  const PairCache none{};
  if (brute_force_) {
    find_neighbors_brute_force(fluid_.x, fluid_.x, kernel_.support(), true, ff_);
    find_neighbors_brute_force(fluid_.x, boundary_.x, kernel_.support(), false, fb_);
  } else {
    fluid_grid_.build(fluid_.x, kernel_.support());
    find_neighbors(fluid_.x, fluid_grid_, kernel_, /*exclude_self=*/true, none, ff_);
    find_neighbors(fluid_.x, boundary_grid_, kernel_, /*exclude_self=*/false, none, fb_);
  }
  SLUICE_ASSERT(ff_.offset.size() == static_cast<size_t>(fluid_.size()) + 1 && ff_.offset.size() == fb_.offset.size(),
                "one neighbour list per fluid particle");
}

// One pass over all pairs: caches grad W (in single precision, see NeighborLists) for fluid and boundary pairs (and W
// for boundary pairs, which Eq. 25 gathers again) and sums the density of Eq. 13 with the boundary term of section 4.1:
//   rho_i = sum_f m_f W_if + gamma2 sum_b m_b W_ib,  m_b = rho0 V_b.
void Simulation::compute_density() {
  const double w0 = kernel_.W(0.0);
  const double rho0 = settings_.rest_density, g2 = settings_.gamma2;
  resize_pairs(ff_.grad, static_cast<size_t>(ff_.pairs()));
  resize_pairs(fb_.grad, static_cast<size_t>(fb_.pairs()));
  resize_pairs(fb_.w, static_cast<size_t>(fb_.pairs()));
  const bool correct = settings_.gradient_correction;
  if (correct) scratch_->grad_scale.resize(fluid_.size());
  parallel_for(fluid_.size(), [&](Index i) {
    const Vec2 xi = fluid_.x[i];
    double w, dw;
    double sf = w0, mf = 0.0, mb = 0.0;
    // Two pairs at a time (Kernel2D::eval2), summed in list order: the bits of one at a time.
    Index k = ff_.offset[i];
    for (const Index end = ff_.offset[i + 1]; k + 1 < end; k += 2) {
      const Vec2 r0 = xi - fluid_.x[ff_.j[k]], r1 = xi - fluid_.x[ff_.j[k + 1]];
      const Double2 rx = lanes(r0.x(), r1.x()), ry = lanes(r0.y(), r1.y());
      const Double2 r2 = rx * rx + ry * ry;
      Double2 w2, dw2;
      kernel_.eval2(sqrt_lanes(r2), w2, dw2);
      sf += w2[0];
      mf += dw2[0] * r2[0];
      sf += w2[1];
      mf += dw2[1] * r2[1];
      const Double2 gx = dw2 * rx, gy = dw2 * ry;
      ff_.grad[k] = Vec2f(static_cast<float>(gx[0]), static_cast<float>(gy[0]));
      ff_.grad[k + 1] = Vec2f(static_cast<float>(gx[1]), static_cast<float>(gy[1]));
    }
    if (k < ff_.offset[i + 1]) {
      const Vec2 r = xi - fluid_.x[ff_.j[k]];
      const double r2 = r.squaredNorm();
      kernel_.eval(std::sqrt(r2), w, dw);
      sf += w;
      mf += dw * r2;
      ff_.grad[k] = (dw * r).cast<float>();
    }
    double sb = 0.0;
    k = fb_.offset[i];
    for (const Index end = fb_.offset[i + 1]; k + 1 < end; k += 2) {
      const Index b0 = fb_.j[k], b1 = fb_.j[k + 1];
      const Vec2 r0 = xi - boundary_.x[b0], r1 = xi - boundary_.x[b1];
      const Double2 rx = lanes(r0.x(), r1.x()), ry = lanes(r0.y(), r1.y());
      const Double2 r2 = rx * rx + ry * ry;
      Double2 w2, dw2;
      kernel_.eval2(sqrt_lanes(r2), w2, dw2);
      const Double2 vol = lanes(boundary_.volume[b0], boundary_.volume[b1]);
      const Double2 vw = vol * w2, vdr = vol * dw2 * r2;
      sb += vw[0];
      mb += vdr[0];
      sb += vw[1];
      mb += vdr[1];
      fb_.w[k] = w2[0];
      fb_.w[k + 1] = w2[1];
      const Double2 gx = dw2 * rx, gy = dw2 * ry;
      fb_.grad[k] = Vec2f(static_cast<float>(gx[0]), static_cast<float>(gy[0]));
      fb_.grad[k + 1] = Vec2f(static_cast<float>(gx[1]), static_cast<float>(gy[1]));
    }
    if (k < fb_.offset[i + 1]) {
      const Index b = fb_.j[k];
      const Vec2 r = xi - boundary_.x[b];
      const double r2 = r.squaredNorm();
      kernel_.eval(std::sqrt(r2), w, dw);
      sb += boundary_.volume[b] * w;
      mb += boundary_.volume[b] * dw * r2;
      fb_.w[k] = w;
      fb_.grad[k] = (dw * r).cast<float>();
    }
    fluid_.rho[i] = mass_ * sf + g2 * rho0 * sb;
    if (correct) {
      // tr(sum_j V_j x_ji (x) grad W_ij) = -sum_j V_j r_ij^2 (dW/dr)/r: 2 for an exact gradient.
      const double trace = -(mass_ / rho0 * mf + mb);
      scratch_->grad_scale[i] = trace > kMinGradientTrace ? 2.0 / trace : 1.0;
    }
  });
  if (correct) correct_gradients();
  // Eq. 25 gathers over the fluid neighbours of each boundary particle.
  // Eq. 25 and pressure boundaries gather over the fluid neighbours of each sample.
  if (settings_.boundary_pressure == BoundaryPressure::Extrapolation ||
      settings_.boundary_pressure == BoundaryPressure::Solved)
    transpose_neighbors(fb_, boundary_.size(), bf_);
}

// The scalar gradient correction (solver.gradient_correction; the thesis uses grad W_ij as
// is in Eq. 11-24, which is 1.3 % weak on a settled arrangement): fluid pairs scale by
// (c_i + c_j) / 2, which keeps them antisymmetric (momentum is conserved), boundary pairs
// by c_i. A free-surface particle (trace below kMinGradientTrace) is left as it is.
void Simulation::correct_gradients() {
  const std::vector<double>& c = scratch_->grad_scale;
  parallel_for(fluid_.size(), [&](Index i) {
    const double ci = c[i];
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k)
      ff_.grad[k] *= static_cast<float>(0.5 * (ci + c[ff_.j[k]]));
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) fb_.grad[k] *= static_cast<float>(ci);
  });
}

}  // namespace sluice
