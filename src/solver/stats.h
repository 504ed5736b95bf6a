#pragma once
// What one simulation step reports; one row of stats.csv.
#include "core/types.h"

namespace sluice {

struct StepStats {
  long step = 0;               // 1-based step number
  double time = 0;             // simulated time at the end of the step [s]
  double dt = 0;               // step size [s]
  int iterations = 0;          // pressure solver iterations (0 for WCSPH)
  double avg_error_percent = 0;  // IISPH: predicted average compression error (Eq. 23) at exit;
                                 // WCSPH: average density error (Eq. 15)
  double max_error_percent = 0;  // the largest per-particle value of the same quantity
  double density_error_percent = 0;  // average density error of Eq. 15 at the step's start
  double max_cfl = 0;          // max |v| dt / h after the step (Eq. 14 with lambda = CFL)
  // Energy of the fluid after the step [J/m, per metre of depth]: kinetic 1/2 m |v|^2,
  // potential -m g . x (zero at the origin), their sum, and the work the boundaries did
  // on the fluid during the step (their forces on fluid particles times the boundary
  // velocities; zero for walls at rest).
  double kinetic_energy = 0, potential_energy = 0, mechanical_energy = 0, boundary_work = 0;
  Index fluid_particles = 0;
  Index frame = -1;            // frame index when the step landed on a frame time, else -1
  // wall-clock milliseconds per phase
  // (ms_boundary: moving boundaries: poses, their grid and the volume updates of 4.1)
  double ms_neighbors = 0, ms_nonpressure = 0, ms_pressure = 0, ms_integrate = 0, ms_total = 0, ms_boundary = 0;
};

}  // namespace sluice
