#include "solver/simulation.h"

// The start's relaxation (TimeSettings::relax_start): the fluid that the sampling left
// compressed against a boundary off its lattice is moved, before t = 0, to rest density.
#include <algorithm>

#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure/pressure_solver.h"  // pressure_method_ is remade for the run

namespace sluice {

using namespace solver_detail;

// A boundary off the fluid's lattice (a plate 0.2 or 0.8 spacings from a fluid column, a
// slanted wall) keeps lattice points that the 0.9 h rule does not remove, up to 14 %
// compressed, and the first steps' pressure rings through the tank for seconds
// (docs/validation.md, "Still water next to a plate anywhere"). Each round is one IISPH
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
  const std::vector<Vec2> scene_bv = boundary_.v, scene_ba = boundary_.a;
  settings_.type = SolverType::IISPH;
  settings_.pressure_solver = PressureSolver::Jacobi;
  settings_.gravity = Vec2::Zero();
  std::fill(boundary_.v.begin(), boundary_.v.end(), Vec2::Zero());  // every boundary held at its t = 0 pose
  std::fill(boundary_.a.begin(), boundary_.a.end(), Vec2::Zero());
  const double dt = choose_time_step();  // any step: the move dt^2 a_p does not depend on it
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
  boundary_.v = scene_bv;
  boundary_.a = scene_ba;
  // The run starts at rest from zero pressure, as a start on the lattice does.
  std::fill(fluid_.v.begin(), fluid_.v.end(), Vec2::Zero());
  std::fill(fluid_.p.begin(), fluid_.p.end(), 0.0);
  std::fill(boundary_.p.begin(), boundary_.p.end(), 0.0);
  pressure_method_.reset();
  return r;
}

}  // namespace sluice
