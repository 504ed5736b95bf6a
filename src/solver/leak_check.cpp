#include "solver/leak_check.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace sluice {

FluidInSolids find_fluid_in_solids(const SimulationSetup& setup, const std::vector<Vec2>& fluid_x, double t) {
  const double h = setup.spacing;
  FluidInSolids r;
  for (const BoundaryObject& obj : setup.objects) {
    // Into the object's rest frame: x0 = R(-angle) (x - shift).
    const Pose pose = obj.moving ? obj.motion.at(t) : Pose{};
    const PoseMap back(Pose{-pose.angle, 0, 0, Vec2::Zero(), Vec2::Zero(), Vec2::Zero()});
    std::vector<std::pair<Vec2, Vec2>> curve;  // built on the first particle on the solid side
    for (std::size_t i = 0; i < fluid_x.size(); ++i) {
      const Vec2 p = back.rotated(fluid_x[i] - pose.shift);
      if (!obj.geometry.on_solid_side(p, 0.5 * h)) continue;
      // Deeper than half a spacing behind the surface: past the first sample layer (a
      // particle in a sharp tip thinner than the fluid's spacing is not through a wall).
      if (curve.empty()) curve = obj.geometry.curve(h);
      double d = std::numeric_limits<double>::infinity();
      Vec2 nearest = p;
      for (const auto& [a, b] : curve) {
        const Vec2 ab = b - a;
        const double len2 = ab.squaredNorm();
        const double u = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
        const Vec2 q = a + u * ab;
        if ((p - q).norm() < d) {
          d = (p - q).norm();
          nearest = q;
        }
      }
      if (!curve.empty() && d <= 0.5 * h) continue;
      if (r.count++ == 0) {
        r.first = static_cast<Index>(i);
        r.object = obj.name;
        r.at = fluid_x[i];
        r.surface = PoseMap(pose).position(nearest);
      }
    }
  }
  return r;
}

Index count_fluid_in_solids(const SimulationSetup& setup, const std::vector<Vec2>& fluid_x, double t) {
  return find_fluid_in_solids(setup, fluid_x, t).count;
}

}  // namespace sluice
