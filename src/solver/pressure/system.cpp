#include "solver/pressure/system.h"

#include <algorithm>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

Index PressureSystem::fluid_count() const { return sim_.fluid_.size(); }

const SolverSettings& PressureSystem::settings() const { return sim_.settings_; }

double PressureSystem::largest_error() const {
  return parallel_max(sim_.fluid_.size(), 0.0, [&](Index i) { return sim_.scratch_->err[i]; });
}

// Measured in the step's non-pressure phase, beside the average (StepStats::density_error_percent).
double PressureSystem::largest_start_compression() const {
  SLUICE_ASSERT(sim_.scratch_->start_compression_stamp == sim_.step_stamp(),
                "the non-pressure phase measured this step's start compression");
  return sim_.scratch_->start_compression_max;
}

double PressureSystem::sweep() {
  const Index n = sim_.fluid_.size();
  sim_.update_boundary_pressure();
  const double sum = sim_.jacobi_sweep(block_, terms_);
  double avg = n ? sum / n : 0.0;
  // Pressure boundaries: the samples' constraints converge too (their own average), or
  // their pressures lag the fluid's and stop being constraint forces.
  if (sim_.settings_.boundary_pressure == BoundaryPressure::Solved && active_samples_ > 0)
    avg = std::max(avg, sim_.jacobi_update_boundary(terms_) / active_samples_);
  return avg;
}

void PressureSystem::build_coarse_level() { sim_.build_coarse_level(terms_); }

bool PressureSystem::coarse_correction(double scale) { return sim_.coarse_correction(terms_, scale); }

void PressureSystem::smooth_near_walls(int iterations) {
  if (iterations <= 0) return;
  if (!band_planned_) sim_.plan_wall_band();
  band_planned_ = true;
  for (int k = 0; k < iterations; ++k) sim_.smooth_wall_band(terms_);
}

void PressureSystem::save_previous_iterate() {
  Simulation& s = sim_;
  s.scratch_->p_prev.resize(s.fluid_.p.size());
  s.scratch_->pb_prev.resize(s.boundary_.p.size());
  parallel_for(s.fluid_.size(), [&](Index i) { s.scratch_->p_prev[i] = s.fluid_.p[i]; });
  parallel_for(s.boundary_.size(), [&](Index b) { s.scratch_->pb_prev[b] = s.boundary_.p[b]; });
}

void PressureSystem::restore_saved_iterate() {
  Simulation& s = sim_;
  s.fluid_.p = s.scratch_->p_prev;
  s.boundary_.p = s.scratch_->pb_prev;
  const double inv_rho0_2 = 1.0 / (s.settings_.rest_density * s.settings_.rest_density);
  parallel_for(s.fluid_.size(),
               [&](Index i) { s.scratch_->p_over_rho2[i] = s.fluid_.p[i] / (s.fluid_.rho[i] * s.fluid_.rho[i]); });
  parallel_for(s.boundary_.size(), [&](Index b) { s.scratch_->pb_over_rho2[b] = s.boundary_.p[b] * inv_rho0_2; });
}

}  // namespace sluice
