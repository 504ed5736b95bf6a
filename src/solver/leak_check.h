#pragma once
// The leak check of the stability detector: fluid particles that passed through a wall.
#include <string>
#include <vector>

#include "core/types.h"
#include "solver/setup.h"

namespace sluice {

// Fluid particles on the solid side of any boundary at time t (each object at its
// scripted pose) and more than half a spacing behind its surface, i.e. past the first
// sample layer, with the first such particle (in the order of fluid_x): its index, the
// object it is in, where it is and the nearest point of that object's surface (where it
// crossed, to within the step's motion), all at time t. Open polylines count a band of
// half a spacing behind their last layer. count is 0 for a healthy run.
struct FluidInSolids {
  Index count = 0;
  Index first = -1;
  std::string object;
  Vec2 at = Vec2::Zero();
  Vec2 surface = Vec2::Zero();
};
FluidInSolids find_fluid_in_solids(const SimulationSetup& setup, const std::vector<Vec2>& fluid_x, double t);
Index count_fluid_in_solids(const SimulationSetup& setup, const std::vector<Vec2>& fluid_x, double t);

}  // namespace sluice
