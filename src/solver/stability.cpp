#include "solver/simulation.h"

#include <cmath>
#include <sstream>
#include <string>

#include "solver/leak_check.h"

namespace sluice {

// The bound of check_stability's energy test [J/m]: a fraction of the energy available
// to the fluid (the initial kinetic energy and fall, at least every particle falling one
// spacing under standard gravity, so that a fluid at rest without gravity has a bound
// above its noise), plus, with moving walls, what they can have given it without a
// record of their work (a resume has none): a lift through the whole scene and the
// fluid at twice their peak speed.
double Simulation::energy_gain_bound() const {
  const double m = mass_ * static_cast<double>(fluid_.size());
  const double g = settings_.gravity.norm();
  double e = setup_.limits.max_energy_gain * (initial_available_energy_ + m * std::max(g, 9.81) * setup_.spacing);
  if (has_moving_boundaries()) {
    const double vb = peak_boundary_speed_;
    e += m * (g * (setup_.bounds_max - setup_.bounds_min).norm() + 2.0 * vb * vb);
  }
  return e;
}

// The bound of check_stability's speed test [m/s]: max_speed_ratio times the speed of a fall
// through the whole scene (under at least standard gravity) plus the fastest initial
// speed, plus twice the moving walls' peak speed. A dam break's front runs at 2 sqrt(g H),
// under a fall through its tank.
double Simulation::speed_bound() const {
  const double g = std::max(settings_.gravity.norm(), 9.81);
  const double fall = std::sqrt(2.0 * g * (setup_.bounds_max - setup_.bounds_min).norm());
  return setup_.limits.max_speed_ratio * (fall + initial_max_speed_) + 2.0 * peak_boundary_speed_;
}

void Simulation::check_stability(const StepStats& st) const {
  auto fail = [&](const std::string& cause) {
    std::ostringstream os;
    if (st.step <= 0)  // settle() numbers its steps 0, -1, -2, ...
      os << "unstable while settling (" << settle_origin(setup_.time) << settle_seconds_ << " s) at its step "
         << 1 - st.step << ", " << st.time << " s into it: " << cause;
    else
      os << "unstable at step " << st.step << ", t = " << st.time << " s: " << cause;
    throw SimulationUnstable(os.str());
  };
  for (Index i = 0; i < fluid_.size(); ++i) {
    const Vec2& x = fluid_.x[i];
    const Vec2& v = fluid_.v[i];
    if (!x.allFinite() || !v.allFinite() || !std::isfinite(fluid_.p[i])) {
      std::ostringstream os;
      os << "fluid particle " << fluid_.id[i] << " has a non-finite position, velocity or pressure";
      fail(os.str());
    }
    if ((x.array() < lost_min_.array()).any() || (x.array() > lost_max_.array()).any()) {
      std::ostringstream os;
      os << "fluid particle " << fluid_.id[i] << " at (" << x.x() << ", " << x.y()
         << ") left the scene's bounds by more than stability.bounds_margin = " << setup_.limits.bounds_margin
         << " scene sizes";
      fail(os.str());
    }
  }
  // Walls that no longer hold the fluid (checked at frame times: a pass over every
  // particle and object).
  if (st.frame >= 0) {
    const FluidInSolids leak = find_fluid_in_solids(setup_, fluid_.x, time_);
    if (leak.count > 0 && 100.0 * leak.count > setup_.limits.max_leaked_percent * fluid_.size()) {
      std::ostringstream os;
      os << leak.count << " of " << fluid_.size() << " fluid particles are past a wall's first sample layer (more than "
         << "stability.max_leaked_percent = " << setup_.limits.max_leaked_percent << "%); the first, particle "
         << fluid_.id[leak.first] << ", is inside boundary \"" << leak.object << "\" at (" << leak.at.x() << ", "
         << leak.at.y() << "), behind its surface at (" << leak.surface.x() << ", " << leak.surface.y() << ")";
      fail(os.str());
    }
  }
  // Energy conservation: with static walls (which do no work) and gravity the only
  // force that gives energy, the mechanical energy cannot rise beyond the solver's small
  // drift (the closed tank: 0.05 % of its potential energy in 10 s). A larger rise is
  // a blow-up, even one that stays inside the bounds and away from the walls.
  const double gain = st.mechanical_energy - initial_energy_, bound = energy_gain_bound();
  if (gain > bound) {
    std::ostringstream os;
    os << "the fluid's mechanical energy rose by " << gain << " J/m since the start, more than the " << bound
       << " J/m that stability.max_energy_gain = " << setup_.limits.max_energy_gain
       << " allows (that fraction of the energy available to the fluid"
       << (has_moving_boundaries() ? ", plus what the moving walls can have given it" : "") << ")";
    fail(os.str());
  }
  // max_cfl = v_max dt / h (Eq. 14), after the step.
  const double vmax = st.dt > 0 ? st.max_cfl * setup_.spacing / st.dt : 0.0, vbound = speed_bound();
  if (vmax > vbound) {
    std::ostringstream os;
    os << "the fastest fluid particle moves at " << vmax << " m/s, more than the " << vbound
       << " m/s that stability.max_speed_ratio = " << setup_.limits.max_speed_ratio
       << " allows (that many times a fall through the whole scene plus the initial speeds"
       << (has_moving_boundaries() ? ", plus twice the moving walls' peak speed" : "") << ")";
    fail(os.str());
  }
  if (st.density_error_percent > setup_.limits.max_error_percent) {
    std::ostringstream os;
    os << "average compression error " << st.density_error_percent
       << "% exceeds stability.max_error_percent = " << setup_.limits.max_error_percent << "%";
    fail(os.str());
  }
}

}  // namespace sluice
