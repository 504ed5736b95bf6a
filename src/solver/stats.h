#pragma once
// What one simulation step reports; one row of stats.csv.
#include <array>
#include <cstddef>

#include "core/types.h"

namespace sluice {

// The phases of a step in the order of Algorithm 2 (Boundary: the scripted poses of
// moving boundaries, their grid and the volume updates of 4.1; it runs only when a
// scene has moving boundaries).
enum class Phase { Boundary, Neighbors, NonPressure, Pressure, Integrate };
inline constexpr std::size_t kPhaseCount = 5;
inline constexpr std::array<Phase, kPhaseCount> kPhases = {Phase::Boundary, Phase::Neighbors, Phase::NonPressure,
                                                           Phase::Pressure, Phase::Integrate};

struct StepStats {
  long step = 0;                     // 1-based step number
  double time = 0;                   // simulated time at the end of the step [s]
  double dt = 0;                     // step size [s]
  int iterations = 0;                // pressure solver iterations (0 for WCSPH)
  double avg_error_percent = 0;      // IISPH: predicted average compression error (Eq. 23) at exit;
                                     // WCSPH: average density error (Eq. 15)
  double max_error_percent = 0;      // the largest per-particle value of the same quantity
  double density_error_percent = 0;  // average density error of Eq. 15 at the step's start
  double max_cfl = 0;                // max |v| dt / h after the step (Eq. 14 with lambda = CFL)
  // Energy of the fluid after the step [J/m, per metre of depth]: kinetic 1/2 m |v|^2,
  // potential -m g . x (zero at the origin), their sum, and the work the boundaries did
  // on the fluid during the step (their forces on fluid particles times the boundary
  // velocities; zero for walls at rest).
  double kinetic_energy = 0, potential_energy = 0, mechanical_energy = 0, boundary_work = 0;
  Index fluid_particles = 0;
  Index frame = -1;                            // frame index when the step landed on a frame time, else -1
  std::array<double, kPhaseCount> phase_ms{};  // wall-clock milliseconds per phase
  double ms_total = 0;                         // the whole step

  double& ms(Phase p) { return phase_ms[static_cast<std::size_t>(p)]; }
  double ms(Phase p) const { return phase_ms[static_cast<std::size_t>(p)]; }
};

}  // namespace sluice
