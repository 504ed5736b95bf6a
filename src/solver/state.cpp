#include "solver/simulation.h"

#include <cmath>
#include <sstream>
#include <string>

namespace sluice {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

std::string count_mismatch(const char* what, size_t state, Index here) {
  std::ostringstream os;
  os << what << ": the state has " << state << ", this simulation " << here;
  return os.str();
}

}  // namespace

SimulationState Simulation::state() const {
  SimulationState s;
  s.time = time_;
  s.step = step_;
  s.frame = frame_;
  s.fluid = fluid_;
  s.boundary_x = boundary_.x;
  s.boundary_v = boundary_.v;
  s.boundary_a = boundary_.a;
  s.boundary_volume = boundary_.volume;
  s.boundary_p = boundary_.p;
  s.near_moving = near_moving_;
  return s;
}

// Everything is checked before anything is assigned, so a refused state leaves the
// simulation as it was.
void Simulation::restore(const SimulationState& s) {
  const Index n = fluid_.size(), nb = boundary_.size();
  const FluidParticles& f = s.fluid;
  for (size_t size : {f.x.size(), f.v.size(), f.rho.size(), f.p.size(), f.id.size()})
    require(size == static_cast<size_t>(n), count_mismatch("fluid particles", size, n));
  for (size_t size : {s.boundary_x.size(), s.boundary_v.size(), s.boundary_a.size(), s.boundary_volume.size(),
                      s.boundary_p.size(), s.near_moving.size()})
    require(size == static_cast<size_t>(nb), count_mismatch("boundary samples", size, nb));
  // Exports index arrays by id: they must be a permutation of 0..n-1.
  std::vector<std::uint8_t> seen(static_cast<size_t>(n), 0);
  for (Index id : f.id) {
    require(id >= 0 && id < n && !seen[id], "fluid ids are not a permutation of 0.." + std::to_string(n - 1));
    seen[id] = 1;
  }
  // Walls at rest never move and the static boundary grid was built from the scene's
  // positions: a state whose walls stand elsewhere belongs to another scene.
  for (Index b = 0; b < nb; ++b)
    require(boundary_.moving[b] || s.boundary_x[b] == boundary_.x[b],
            "boundary sample " + std::to_string(b) + " at rest lies elsewhere than in this scene");
  require(std::isfinite(s.time) && s.time >= 0 && s.time <= setup_.time.duration,
          "time " + std::to_string(s.time) + " s is outside this scene's 0.." + std::to_string(setup_.time.duration) +
              " s");
  require(s.step >= 0 && s.frame >= 0 && s.frame <= last_frame_,
          "step " + std::to_string(s.step) + " / frame " + std::to_string(s.frame) + " out of range (last frame " +
              std::to_string(last_frame_) + ")");

  time_ = s.time;
  step_ = s.step;
  frame_ = s.frame;
  fluid_ = f;
  boundary_.x = s.boundary_x;
  boundary_.v = s.boundary_v;
  boundary_.a = s.boundary_a;
  boundary_.volume = s.boundary_volume;
  boundary_.p = s.boundary_p;
  near_moving_ = s.near_moving;
  // The grid holds copies of the positions; moving ones have just changed. (Every step
  // rebuilds it before use; this keeps recompute_density() right in between.)
  if (has_moving_boundaries()) boundary_grid_.build(boundary_.x, kernel_.support());
}

}  // namespace sluice
