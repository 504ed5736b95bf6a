#include "solver/simulation.h"

// The start's relaxation (TimeSettings::relax_start): the fluid that the sampling left
// compressed against a boundary off its lattice is moved, before t = 0, to rest density.
#include <algorithm>
#include <cmath>

#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure/pressure_solver.h"  // pressure_method_ is remade for the run

namespace sluice {

using namespace solver_detail;

// A boundary off the fluid's lattice (a plate 0.2 or 0.8 spacings from a fluid column, a
// slanted wall) keeps lattice points that the 0.9 h rule does not remove, up to 14 %
// compressed, and the first steps' pressure rings through the tank for seconds
// (docs/validation.md, "The start relaxed"). Each round is one IISPH
// projection without gravity from rest (Eq. 16-24 with v* = 0): the PPE's source is the
// density error alone, the particles move by dt^2 a_p, and their velocities are
// discarded. Jacobi's sweeps (Algorithm 2) to the scene's tolerance spread a column's
// excess over its neighbours round by round; a converged solve overshoots (the moves are
// not small against h) and takes more rounds. Moving particles one at a time along their
// own density's gradient does not converge at all (docs/validation.md): only a shift of the
// whole neighbourhood absorbs the excess. Colagrossi et al. (2012) pack a start the same
// way, with a background pressure; the thesis starts from the lattice.
RelaxStats Simulation::relax_start() {
  const Index n = fluid_.size();
  const double rho0 = settings_.rest_density;
  auto largest_compression = [&] {
    return parallel_max(n, 0.0, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); });
  };
  RelaxStats r;
  r.largest_before_percent = r.largest_after_percent = largest_compression();
  if (r.largest_before_percent <= kRelaxStartPercent) return r;

  const SolverSettings scene_settings = settings_;
  const std::vector<Vec2> scene_v = fluid_.v, scene_bv = boundary_.v, scene_ba = boundary_.a;
  settings_.type = SolverType::IISPH;
  settings_.pressure_solver = PressureSolver::Jacobi;
  settings_.gravity = Vec2::Zero();
  std::fill(boundary_.v.begin(), boundary_.v.end(), Vec2::Zero());  // every boundary held at its t = 0 pose
  std::fill(boundary_.a.begin(), boundary_.a.end(), Vec2::Zero());
  const double dt = choose_time_step();  // any step: the move dt^2 a_p does not depend on it
  // The solve books the moving walls' work per particle (Eq. 24's boundary term times v_b,
  // here 0), as in a step; without it the rotor on Wendland's C2, or any moving object next
  // to a compressed start, wrote past the array's end.
  reset_boundary_work();
  while (r.rounds < kRelaxStartRounds && r.largest_after_percent > kRelaxStartPercent) {
    std::fill(fluid_.v.begin(), fluid_.v.end(), Vec2::Zero());
    StepStats st;
    solve_pressure_iisph(dt, st);
    integrate(dt);
    ++r.rounds;
    recompute_density();
    r.largest_after_percent = largest_compression();
  }
  settings_ = scene_settings;
  // The run starts with the scene's velocities (no reorder since: the same indices) and
  // from zero pressure, as a start on the lattice does.
  fluid_.v = scene_v;
  boundary_.v = scene_bv;
  boundary_.a = scene_ba;
  std::fill(fluid_.p.begin(), fluid_.p.end(), 0.0);
  std::fill(boundary_.p.begin(), boundary_.p.end(), 0.0);
  pressure_method_.reset();
  return r;
}

// time.settle "auto" settles a start (kAutoSettleSeconds) only where the fluid is at rest:
// nothing moves, gravity pulls, and at least kAtRestSurfaceShare of the free surface faces up (its
// outward normal -sum_j grad W_ij within 45 degrees of -g). The free surface is the particles
// below 90 % of rho0 with no boundary neighbour (a hole next to a boundary is not surface).
// A dam break's column, whose side faces sideways, does not settle: it must fall at t = 0.
bool Simulation::starts_at_rest() const {
  const Vec2 g = settings_.gravity;
  const Index n = fluid_.size();
  if (g.squaredNorm() == 0.0) return false;
  for (const Vec2& v : fluid_.v)
    if (v != Vec2::Zero()) return false;
  const Vec2 up = -g.normalized();
  const double rho0 = settings_.rest_density, cos45 = std::sqrt(0.5);
  long surface = 0, facing_up = 0;
  for (Index i = 0; i < n; ++i) {
    if (fluid_.rho[i] >= 0.9 * rho0 || fb_.count(i) > 0) continue;
    Vec2 outward = Vec2::Zero();
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) outward -= ff_.grad[k].cast<double>();
    ++surface;
    facing_up += outward.dot(up) >= cos45 * outward.norm();
  }
  return surface == 0 || static_cast<double>(facing_up) >= kAtRestSurfaceShare * static_cast<double>(surface);
}

}  // namespace sluice
