#include "solver/setup.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice {

double fluid_height(const SimulationSetup& setup) {
  const Vec2 g = setup.solver.gravity;
  if (!(g.norm() > 0) || setup.fluid_x.empty()) return 0.0;
  const Vec2 up = -g.normalized();
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec2& x : setup.fluid_x) {
    lo = std::min(lo, x.dot(up));
    hi = std::max(hi, x.dot(up));
  }
  return hi - lo + setup.spacing;
}

double fastest_initial_speed(const SimulationSetup& setup) {
  double vmax = 0;
  for (const Vec2& v : setup.fluid_v) vmax = std::max(vmax, v.norm());
  return vmax;
}

double wcsph_default_stiffness(const SimulationSetup& setup) {
  const double v0 = fastest_initial_speed(setup), H = fluid_height(setup);
  const double c0 = 20.0 * std::max(v0, std::sqrt(setup.solver.gravity.norm() * H));
  return setup.solver.rest_density * c0 * c0;
}

double wcsph_acoustic_limit(const SimulationSetup& setup) {
  if (!(setup.solver.stiffness > 0)) return 0.0;
  return kAcousticCfl * setup.spacing / std::sqrt(setup.solver.stiffness / setup.solver.rest_density);
}

}  // namespace sluice
