#include "solver/probe.h"

#include <stdexcept>

#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure/coarse_level.h"
#include "solver/pressure_kernels.h"

namespace sluice {

void SolverProbe::prepare_pressure_system(double dt) {
  if (sim_.settings_.type != SolverType::IISPH) throw std::logic_error("SolverProbe: the pressure system is IISPH's");
  StepStats st;
  sim_.run_phase(Phase::Neighbors, dt, st);
  sim_.run_phase(Phase::NonPressure, dt, st);
  dt_ = dt;
  active_samples_ = sim_.prepare_pressure_system(dt);
}

int SolverProbe::iterate_pressure(StepStats* stats) {
  StepStats st;
  sim_.iterate_pressure(dt_, active_samples_, st);
  if (stats) *stats = st;
  return st.iterations;
}

const CoarseLevel& SolverProbe::coarse_level() {
  sim_.build_coarse_level(sim_.pressure_terms(dt_));
  return *sim_.scratch_->coarse;
}

const std::vector<double>& SolverProbe::source() const { return sim_.scratch_->s; }
const std::vector<double>& SolverProbe::diagonal() const { return sim_.scratch_->a_ii; }
const std::vector<double>& SolverProbe::sample_source() const { return sim_.scratch_->bnd_s; }
const std::vector<double>& SolverProbe::sample_diagonal() const { return sim_.scratch_->bnd_aii; }

std::vector<double> SolverProbe::sample_density() const {
  std::vector<double> rho(static_cast<size_t>(sim_.boundary_.size()), 0.0);
  for (Index b = 0; b < sim_.boundary_.size(); ++b)
    if (sim_.bf_.count(b) > 0) rho[b] = sim_.sample_density_of(b);
  return rho;
}

Vec2 SolverProbe::boundary_pressure_force() const {
  const Simulation& s = sim_;
  const Simulation::PressureTerms t = s.pressure_terms(0.0);
  const double inv_rho0_2 = 1.0 / (s.settings_.rest_density * s.settings_.rest_density);
  Vec2 f = Vec2::Zero();
  for (Index i = 0; i < s.fluid_.size(); ++i) {  // fixed order: the same bits for any thread count
    const double pri = s.fluid_.p[i] / (s.fluid_.rho[i] * s.fluid_.rho[i]);
    Vec2 a = -(t.c_gamma3 * pri) * s.scratch_->grad_b[i];
    if (t.boundary_field)
      for (Index k = s.fb_.offset[i]; k < s.fb_.offset[i + 1]; ++k) {
        const Index b = s.fb_.j[k];
        a -= (t.gamma3_rho0 * s.boundary_.volume[b] * s.boundary_.p[b] * inv_rho0_2) * s.fb_.grad[k].cast<double>();
      }
    f += s.mass_ * a;
  }
  return f;
}

void SolverProbe::apply(const std::vector<double>& p, const std::vector<double>& pb, std::vector<double>& ap,
                        std::vector<double>& apb) {
  Simulation& s = sim_;
  const Index n = s.fluid_.size(), nb = s.boundary_.size();
  const bool solved = s.settings_.boundary_pressure == BoundaryPressure::Solved;
  const double inv_rho0_2 = 1.0 / (s.settings_.rest_density * s.settings_.rest_density);
  s.scratch_->p_over_rho2.resize(n);
  for (Index i = 0; i < n; ++i) {
    s.fluid_.p[i] = p[i];
    s.scratch_->p_over_rho2[i] = p[i] / (s.fluid_.rho[i] * s.fluid_.rho[i]);
  }
  if (solved)
    for (Index b = 0; b < nb; ++b) {
      s.boundary_.p[b] = pb[b];
      s.scratch_->pb_over_rho2[b] = pb[b] * inv_rho0_2;
    }
  s.update_boundary_pressure();
  const Simulation::PressureTerms t = s.pressure_terms(dt_);
  s.compute_pressure_acceleration(t);  // and the stabilisation's means
  const bool stabilised = t.stabilisation > 0.0;
  ap.assign(static_cast<size_t>(n), 0.0);
  for (Index i = 0; i < n; ++i)
    ap[i] = s.pressure_operator_of(i, t) + (s.stabilised_row(i, t) ? s.stabilisation_of(i, t) : 0.0);
  apb.assign(static_cast<size_t>(nb), 0.0);
  if (solved)
    for (Index b = 0; b < nb; ++b)
      apb[b] = s.sample_operator_of(b, t) + (stabilised ? s.sample_stabilisation_of(b, t) : 0.0);
}

const std::vector<Vec2>& SolverProbe::pressure_acceleration() const { return sim_.scratch_->a_p; }

}  // namespace sluice
