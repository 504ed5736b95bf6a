#include "solver/simulation.h"

#include <cmath>
#include <sstream>
#include <string>

#include "solver/leak_check.h"

namespace sluice {

void Simulation::check_stability(const StepStats& st) const {
  auto fail = [&](const std::string& cause) {
    std::ostringstream os;
    if (st.step <= 0)  // settle() numbers its steps 0, -1, -2, ...
      os << "unstable while settling (time.settle = " << setup_.time.settle << " s) at its step " << 1 - st.step << ", "
         << st.time << " s into it: " << cause;
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
  if (st.density_error_percent > setup_.limits.max_error_percent) {
    std::ostringstream os;
    os << "average compression error " << st.density_error_percent
       << "% exceeds stability.max_error_percent = " << setup_.limits.max_error_percent << "%";
    fail(os.str());
  }
}

}  // namespace sluice
