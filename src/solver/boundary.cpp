#include "solver/simulation.h"

#include <algorithm>
#include <atomic>
#include <cmath>

#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

namespace {

// Density of boundary sample b from its fluid neighbours plus its wall's own share:
//   rho_b = sum_f m_f W_bf + rho0 sum_b' V_b' W_bb' ~ sum_f m_f W_bf + gamma1 rho0,
// the second by the definition of V_b (section 4.1; exact for a uniformly sampled wall),
// on the thesis' support; on another, the wall's share is Simulation::wall_share_ (the
// lattice's share of the sample's own row and those below), and for a sample that starts
// with fluid on both sides less (Simulation::compute_sample_wall_shares). A sample
// continuing the fluid's lattice is then at rest density.
inline double boundary_density(const NeighborLists& bf, Index b, double mass, double wall_share_rho0) {
  double rf = 0.0;
  for (Index k = bf.offset[b]; k < bf.offset[b + 1]; ++k) rf += bf.w[k];
  return mass * rf + wall_share_rho0;
}

}  // namespace

double Simulation::sample_density_of(Index b) const {
  return boundary_density(bf_, b, mass_, sample_wall_share_[b] * settings_.rest_density);
}

// Section 4.1: V_b = gamma1 / sum_b' W(x_bb'), summed over all boundary particles of
// every object (self included), so touching and overlapping objects share their volume.
// W is the thesis' kernel (volume_kernel_), whatever the fluid's support, and V_b is scaled
// to the fluid's m / rho0 (volume_scale_), so gamma1 keeps its calibration.
// Each sum runs in ascending index order, whatever the grid's layout (which follows the
// moving samples), so a volume kept from an earlier step has the same bits as one
// computed from scratch now.
void Simulation::compute_volumes(const SpatialHashGrid& grid, const std::vector<Index>& which,
                                 std::vector<double>& volume) const {
  const double r = volume_kernel_.support(), w0 = volume_kernel_.W(0.0);
  const std::vector<Vec2>& x = grid.points();
  const Index n = static_cast<Index>(which.size());
#pragma omp parallel if (n >= kParallelMin / 8)
  {
    std::vector<Index> near;
#pragma omp for schedule(dynamic, kForChunk)
    for (Index k = 0; k < n; ++k) {
      const Index b = which[k];
      const Vec2 xb = x[b];
      const size_t count = grid.gather_within(xb, r, b, near, 0);
      std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));
      double sum = w0;
      for (size_t m = 0; m < count; ++m) sum += volume_kernel_.W((xb - x[near[m]]).norm());
      volume[b] = sample_gamma_[b] / sum;
    }
  }
}

std::vector<double> Simulation::boundary_volumes_from_scratch() const {
  std::vector<Index> all(static_cast<size_t>(boundary_.size()));
  for (Index b = 0; b < boundary_.size(); ++b) all[b] = b;
  SpatialHashGrid grid;
  grid.build(boundary_.x, kernel_.support());
  std::vector<double> volume(all.size(), 0.0);
  compute_volumes(grid, all, volume);
  return volume;
}

// Scripted motion (chapter 4, dynamic boundaries): every moving sample gets its position
// and acceleration from its object's pose at the step's time t, and the velocity at
// t + dt/2, the mean velocity over the step to second order, which the source term
// (Eq. 16/19) and viscosity use to predict where the boundary is at t + dt. Positions
// come from the script at t, never from accumulated increments.
void Simulation::move_boundaries(double dt) {
  std::vector<PoseMap> now, mid;
  for (const BoundaryObject& obj : setup_.objects) {
    now.emplace_back(obj.moving ? obj.motion.at(time_) : Pose{});
    mid.emplace_back(obj.moving ? obj.motion.at(time_ + 0.5 * dt) : Pose{});
  }
  parallel_for(static_cast<Index>(moving_.size()), [&](Index k) {
    const Index b = moving_[k];
    const Index o = boundary_.object[b];
    const Vec2 x0 = boundary_.x0[b];
    boundary_.x[b] = now[o].position(x0);
    boundary_.v[b] = mid[o].velocity(x0);
    boundary_.a[b] = now[o].acceleration(x0);
  });
  // The grid is rebuilt with every step's positions (few cells per point, as the
  // fluid's); the static walls ride along.
  boundary_grid_.build(boundary_.x, kernel_.support());
}

// Section 4.1 for the samples whose boundary neighbourhood may have changed since the
// last step: every moving sample, and every static one with a moving sample in its
// support now or at the last update. Static walls far from any moving part keep their
// volumes.
void Simulation::update_boundary_volumes() {
  const double r = volume_kernel_.support(), w0 = volume_kernel_.W(0.0);
  const Index nm = static_cast<Index>(moving_.size());
  std::vector<std::uint8_t> near_now(near_moving_.size(), 0);
  // Moving samples: volume and, in the same gather, the static samples they reach.
  // (Volume loops do far more work per item than a particle loop: a lower threshold.)
#pragma omp parallel if (nm >= kParallelMin / 8)
  {
    std::vector<Index> near;
#pragma omp for schedule(dynamic, kForChunk)
    for (Index k = 0; k < nm; ++k) {
      const Index b = moving_[k];
      const Vec2 xb = boundary_.x[b];
      const size_t count = boundary_grid_.gather_within(xb, r, b, near, 0);
      std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));  // index order, as compute_volumes
      double sum = w0;
      for (size_t m = 0; m < count; ++m) {
        const Index j = near[m];
        sum += volume_kernel_.W((xb - boundary_.x[j]).norm());
        if (!boundary_.moving[j])  // every writer stores 1: the result is order-free
          std::atomic_ref<std::uint8_t>(near_now[j]).store(1, std::memory_order_relaxed);
      }
      boundary_.volume[b] = sample_gamma_[b] / sum;
    }
  }
  volume_update_.clear();
  for (Index b = 0; b < boundary_.size(); ++b)
    if (near_now[b] || near_moving_[b]) volume_update_.push_back(b);
  near_moving_.swap(near_now);
  compute_volumes(boundary_grid_, volume_update_, boundary_.volume);
}

double Simulation::max_boundary_speed() const { return boundary_speed_at(time_); }

double Simulation::boundary_speed_at(double t) const {
  double vmax = 0.0;
  for (size_t o = 0; o < setup_.objects.size(); ++o) {
    const BoundaryObject& obj = setup_.objects[o];
    if (!obj.moving) continue;
    const PoseMap pose(obj.motion.at(t));
    for (Index k = 0; k < obj.count; ++k)
      vmax = std::max(vmax, pose.velocity(setup_.boundary_x[obj.first + k]).squaredNorm());
  }
  return std::sqrt(vmax);
}

// Per-step boundary quantities of the pressure solvers:
//   grad_b_i = sum_b m_b grad W_ib (Eq. 24 and Eq. 26 boundary sums),
//   for Eq. 25: sum_f W_bf and (g - a_b) . sum_f rho_f x_bf W_bf, the hydrostatic term
//   in the frame of a boundary sample that accelerates with a_b.
void Simulation::prepare_boundary_terms() {
  const Index n = fluid_.size(), nb = boundary_.size();
  const double rho0 = settings_.rest_density;
  scratch_->grad_b.resize(n);
  parallel_for(n, [&](Index i) {
    Vec2 g = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k)
      g += (rho0 * boundary_.volume[fb_.j[k]]) * fb_.grad[k].cast<double>();
    scratch_->grad_b[i] = g;
  });
  scratch_->pb_over_rho2.assign(nb, 0.0);
  if (settings_.boundary_pressure != BoundaryPressure::Extrapolation) return;
  scratch_->ext_wsum.resize(nb);
  scratch_->ext_gravity.resize(nb);
  const Vec2 gravity = settings_.gravity;
  parallel_for(nb, [&](Index b) {
    double ws = 0.0;
    Vec2 xr = Vec2::Zero();
    for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
      const Index f = bf_.j[k];
      ws += bf_.w[k];
      xr += (fluid_.rho[f] * bf_.w[k]) * (boundary_.x[b] - fluid_.x[f]);
    }
    scratch_->ext_wsum[b] = ws;
    scratch_->ext_gravity[b] = (gravity - boundary_.a[b]).dot(xr);  // an accelerating wall: g - a_b
  });
}

// Boundary pressure seen by fluid neighbours, as p_b / rho_b^2 (rho_b = rho0):
// WCSPH with pressure boundaries: the state equation of section 2.3.1 at rho_b (the
// sample's share of the energy, so its force is conservative as well);
// extrapolation, Eq. 25: p_b = (sum_f p_f W_bf + (g - a_b) . sum_f rho_f x_bf W_bf) / sum_f W_bf,
// clamped at zero like fluid pressures. Mirroring and zero pressure need no pass.
void Simulation::update_boundary_pressure() {
  const double rho0 = settings_.rest_density, inv_rho0_2 = 1.0 / (rho0 * rho0);
  if (settings_.boundary_pressure == BoundaryPressure::Solved && settings_.type == SolverType::WCSPH) {
    const double k = settings_.stiffness;
    parallel_for(boundary_.size(), [&](Index b) {
      const double p =
          bf_.offset[b] == bf_.offset[b + 1] ? 0.0 : std::max(k * (sample_density_of(b) / rho0 - 1.0), 0.0);
      boundary_.p[b] = p;
      scratch_->pb_over_rho2[b] = p * inv_rho0_2;
    });
    return;
  }
  if (settings_.boundary_pressure != BoundaryPressure::Extrapolation) return;
  parallel_for(boundary_.size(), [&](Index b) {
    const double ws = scratch_->ext_wsum[b];
    double p = 0.0;
    if (ws > 0.0) {
      double sp = 0.0;
      for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) sp += fluid_.p[bf_.j[k]] * bf_.w[k];
      p = std::max((sp + scratch_->ext_gravity[b]) / ws, 0.0);
    }
    boundary_.p[b] = p;
    scratch_->pb_over_rho2[b] = p * inv_rho0_2;
  });
}

// The pressure force's share of the boundaries' work on the fluid: the boundary pairs'
// term of Eq. 24 (with the pressures the step integrates) times the boundary velocity.
void Simulation::add_boundary_pressure_work(double dt) {
  const PressureTerms t = pressure_terms(dt);
  const std::vector<double>& pr = scratch_->p_over_rho2;
  parallel_for(fluid_.size(), [&](Index i) {
    double w = 0.0;
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      if (!boundary_.moving[b]) continue;
      const double pb = t.boundary_field ? scratch_->pb_over_rho2[b] : 0.0;
      const double c = t.c_gamma3 / settings_.gamma3;  // 2 for mirroring: p_b / rho_b^2 = p_i / rho_i^2
      const Vec2 a = -(t.gamma3_rho0 * boundary_.volume[b] * (c * pr[i] + pb)) * fb_.grad[k].cast<double>();
      w += a.dot(boundary_.v[b]);
    }
    scratch_->work[i] += dt * mass_ * w;
  });
}

}  // namespace sluice
