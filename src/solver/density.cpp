#include "solver/simulation.h"

#include <algorithm>
#include <cmath>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

using namespace solver_detail;

// Algorithm 2's first loop, fused: the neighbour lists, and for each pair grad W (single
// precision, see NeighborLists; W too for boundary pairs, which Eq. 25 gathers again),
// evaluated as soon as a particle's neighbours are found, with the kernel sums that
// compute_density makes Eq. 13 of.
void Simulation::find_neighbors_phase() {
  scratch_->fluid_sums.volume = nullptr;
  scratch_->boundary_sums.volume = &boundary_.volume;
  const PairCache fluid_pairs{.grad = true}, boundary_pairs{.grad = true, .w = true};
  if (brute_force_) {
    find_neighbors_brute_force(fluid_.x, fluid_.x, kernel_.support(), true, ff_);
    find_neighbors_brute_force(fluid_.x, boundary_.x, kernel_.support(), false, fb_);
    compute_kernel_sums(fluid_.x, fluid_.x, kernel_, true, fluid_pairs, ff_, scratch_->fluid_sums);
    compute_kernel_sums(fluid_.x, boundary_.x, kernel_, false, boundary_pairs, fb_, scratch_->boundary_sums);
  } else {
    fluid_grid_.build(fluid_.x, kernel_.support());
    find_neighbors(fluid_.x, fluid_grid_, kernel_, /*exclude_self=*/true, fluid_pairs, ff_, &scratch_->fluid_sums);
    find_neighbors(fluid_.x, boundary_grid_, kernel_, /*exclude_self=*/false, boundary_pairs, fb_,
                   &scratch_->boundary_sums);
  }
  SLUICE_ASSERT(ff_.offset.size() == static_cast<size_t>(fluid_.size()) + 1 && ff_.offset.size() == fb_.offset.size(),
                "one neighbour list per fluid particle");
}

// The density of Eq. 13 with the boundary term of section 4.1, from the kernel sums of
// find_neighbors_phase:
//   rho_i = sum_f m_f W_if + gamma2 sum_b m_b W_ib,  m_b = rho0 V_b,
// then the gradient correction's scale of each particle.
void Simulation::compute_density() {
  const double rho0 = settings_.rest_density, g2 = settings_.gamma2;
  const bool correct = settings_.gradient_correction;
  const KernelSums& sf = scratch_->fluid_sums;
  const KernelSums& sb = scratch_->boundary_sums;
  if (correct) scratch_->grad_scale.resize(fluid_.size());
  parallel_for(fluid_.size(), [&](Index i) {
    fluid_.rho[i] = mass_ * sf.w[i] + g2 * rho0 * sb.w[i];
    if (correct) {
      // tr(sum_j V_j x_ji (x) grad W_ij) = -sum_j V_j r_ij^2 (dW/dr)/r: 2 for an exact gradient.
      const double trace = -(mass_ / rho0 * sf.dw_r2[i] + sb.dw_r2[i]);
      scratch_->grad_scale[i] = trace > kMinGradientTrace ? 2.0 / trace : 1.0;
    }
  });
  if (correct) correct_gradients();
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
