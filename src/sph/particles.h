#pragma once
// Particle storage as structure-of-arrays. All per-particle arrays of a set are
// reordered together after a spatial sort (see Simulation::reorder).
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace sluice {

template <class T>
void apply_permutation(std::vector<T>& a, const std::vector<Index>& order, std::vector<T>& scratch) {
  if (a.empty()) return;
  scratch.resize(a.size());
  for (size_t k = 0; k < order.size(); ++k) scratch[k] = a[static_cast<size_t>(order[k])];
  a.swap(scratch);
}

struct FluidParticles {
  std::vector<Vec2> x, v;   // position [m], velocity [m/s]
  std::vector<double> rho;  // density of the current step (Eq. 13) [kg/m^2]
  std::vector<double> p;    // pressure [Pa m]; kept between steps for warm starts
  std::vector<Index> id;    // index in the scene's initial order (stable under reorders)

  Index size() const { return static_cast<Index>(x.size()); }
  void resize(Index n) {
    x.resize(n);
    v.resize(n);
    rho.resize(n);
    p.resize(n);
    id.resize(n);
  }
};

struct BoundaryParticles {
  std::vector<Vec2> x, v;            // position [m], velocity [m/s] (zero for walls at rest)
  std::vector<Vec2> a;               // acceleration [m/s^2] (Eq. 25 uses g - a_b)
  std::vector<Vec2> x0;              // position at rest (the scene's sample; identity pose)
  std::vector<std::uint8_t> moving;  // 1: on an object with a scripted motion
  std::vector<double> volume;        // V_b = gamma1 / sum_b W (section 4.1) [m^2]
  std::vector<double> p;             // extrapolated pressure (Eq. 25) [Pa m]
  std::vector<Index> object;         // index of the scene's boundary object
  std::vector<double> wall_nu;       // the object's wall_viscosity if it is no-slip, else 0 [m^2/s]

  Index size() const { return static_cast<Index>(x.size()); }
};

}  // namespace sluice
