#include "solver/simulation.h"

#include <algorithm>

#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

using namespace solver_detail;

// WCSPH (section 2.3.1): p_i = max(k (rho_i / rho0 - 1), 0), then Eq. 24.
void Simulation::solve_pressure_wcsph(double dt, StepStats& st) {
  const Index n = fluid_.size();
  const double rho0 = settings_.rest_density, k = settings_.stiffness;
  prepare_boundary_terms();
  scratch_->p_over_rho2.resize(n);
  parallel_for(n, [&](Index i) {
    const double rho = fluid_.rho[i];
    const double p = std::max(k * (rho / rho0 - 1.0), 0.0);
    fluid_.p[i] = p;
    scratch_->p_over_rho2[i] = p / (rho * rho);
  });
  update_boundary_pressure();
  compute_pressure_acceleration();
  if (has_moving_boundaries()) add_boundary_pressure_work(dt);
  st.iterations = 0;
  st.avg_error_percent = st.density_error_percent;
  st.max_error_percent = parallel_max(n, 0.0, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); });
}

}  // namespace sluice
