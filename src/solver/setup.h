#pragma once
// What a simulation is built from: its settings, the initial fluid particles, the
// boundary samples and the objects they belong to, with each object's motion and the
// geometry its leak check needs. Plain data: no JSON, no render or output settings.
// The scene (src/scene) builds it from a scene file; tests may build one by hand.
#include <string>
#include <vector>

#include "core/shapes.h"
#include "core/types.h"
#include "solver/motion.h"
#include "solver/settings.h"

namespace sluice {

// One boundary object (a wall, a container, an obstacle). Its samples are
// boundary_x[first, first + count).
struct BoundaryObject {
  std::string name;     // "name" key, or "<shape><index>"
  std::string shape;    // box | polyline | polygon | circle | ellipse
  bool moving = false;  // has a scripted motion; false: a wall at rest (volumes computed once)
  // The fluid's tangential motion along the object: free slip (the default; the artificial
  // viscosity acts only on the velocity normal to the wall), or no slip through a physical
  // viscosity of wall_viscosity [m^2/s] (Eq. 12 against the wall's samples).
  bool no_slip = false;
  double wall_viscosity = 1.0e-6;  // water at 20 degrees C
  Motion motion;                   // pose over time; boundary_x holds the samples at rest (identity pose)
  shapes::BoundaryShape geometry;  // the shape at rest (solid-side tests, e.g. leak checks)
  Index first = 0;
  Index count = 0;
};

struct SimulationSetup {
  double spacing = 0;  // fluid particle spacing h [m]; kernel support is 2h
  SolverSettings solver;
  TimeSettings time;
  StabilityLimits limits;

  std::vector<Vec2> fluid_x, fluid_v;  // initial fluid particles
  std::vector<Vec2> boundary_x;        // all boundary samples, at rest (identity pose)
  std::vector<Index> boundary_object;  // object index of each boundary sample
  std::vector<BoundaryObject> objects;

  Vec2 bounds_min{0, 0}, bounds_max{0, 0};  // box around all particles at t = 0
};

// The fluid's initial extent along gravity, plus one spacing (the rows' own height); 0
// without gravity.
double fluid_height(const SimulationSetup& setup);
// The fastest initial fluid particle's speed [m/s].
double fastest_initial_speed(const SimulationSetup& setup);

// WCSPH's stiffness when the scene gives none: k = rho0 c0^2 with c0 = 20 v_ref, v_ref the
// larger of sqrt(g H) (H: the fluid's initial height along gravity) and its fastest
// initial particle. DualSPHysics' default (speed of sound = coefsound sqrt(g H), coefsound
// 20): the column's hydrostatic compression is g H / c0^2 = 0.25 % at the floor. 0 when
// the setup has neither gravity nor initial motion to scale it by.
double wcsph_default_stiffness(const SimulationSetup& setup);

// The largest fixed step WCSPH takes at the setup's stiffness (Monaghan 1992):
// dt <= 0.4 h / c with c = sqrt(stiffness / rest_density) [s]; 0 without a stiffness.
double wcsph_acoustic_limit(const SimulationSetup& setup);

}  // namespace sluice
