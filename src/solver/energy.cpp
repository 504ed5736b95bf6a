#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/simulation.h"

// The fluid's mechanical energy and the boundaries' work of the step, in J/m (2D: per
// metre of depth), for stats.csv and summary.json.
namespace sluice {

using namespace solver_detail;

double Simulation::mechanical_energy() const {
  StepStats st;
  measure_energy(st);
  return st.mechanical_energy;
}

void Simulation::measure_energy(StepStats& st) const {
  const Index n = fluid_.size();
  const Vec2 g = settings_.gravity;
  st.kinetic_energy = 0.5 * mass_ * parallel_sum(n, [&](Index i) { return fluid_.v[i].squaredNorm(); });
  st.potential_energy = -mass_ * parallel_sum(n, [&](Index i) { return g.dot(fluid_.x[i]); });
  st.mechanical_energy = st.kinetic_energy + st.potential_energy;
  st.boundary_work = scratch_->work.size() == static_cast<size_t>(n) && has_moving_boundaries()
                         ? parallel_sum(n, [&](Index i) { return scratch_->work[i]; })
                         : 0.0;
}

}  // namespace sluice
