#include "solver/simulation.h"

// The step (Algorithm 2) and its time control (Eq. 14).
#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"

namespace sluice {

using namespace solver_detail;

namespace {
constexpr long kReorderEvery = 16;  // steps between spatial sorts of the fluid arrays
}  // namespace

// ---------------------------------------------------------------------------------
// The step (Algorithm 2: neighbours and density, non-pressure accelerations, pressure
// solve, integration), each phase timed.
StepStats Simulation::step() {
  const Stopwatch total;
  StepStats st;
  st.step = step_ + 1;
  st.fluid_particles = fluid_.size();

  // Time step of Eq. 14 (or fixed), shortened so that steps land on the next frame time.
  const double target = std::min(static_cast<double>(frame_ + 1) / setup_.time.fps, setup_.time.duration);
  const double remaining = target - time_;
  const double dt_nominal = choose_time_step();
  const double n_steps = std::max(1.0, std::ceil(remaining / dt_nominal - 1e-9));
  const double dt = remaining / n_steps;
  SLUICE_ASSERT(dt > 0 && std::isfinite(dt), "a step moves time forward");
  st.dt = dt;
  advance(dt, st, /*settling=*/false);

  ++step_;
  if (n_steps == 1.0) {
    time_ = target;
    ++frame_;
    st.frame = frame_;
  } else {
    time_ += dt;
  }
  st.time = time_;
  st.ms_total = total.ms();
  check_stability(st);
  return st;
}

// Before t = 0: steps under gravity with the velocities relaxed towards zero (time
// constant settle / 10) and boundaries held at their t = 0 pose, so that the fluid
// finds its equilibrium, with its pressure field, before the run starts. The run then
// starts at rest; the pressures stay as the next solve's warm start. No statistics.
void Simulation::settle(double duration) {
  const double tau = 0.1 * duration;
  settle_seconds_ = duration;
  std::fill(boundary_.v.begin(), boundary_.v.end(), Vec2::Zero());
  std::fill(boundary_.a.begin(), boundary_.a.end(), Vec2::Zero());
  double t = 0;
  while (t < duration) {
    const double step = choose_time_step();
    // What a fixed step leaves of the settle time by rounding (4000 x 2.5e-4 s falls
    // 1e-13 s short of 1 s) is no step: the pressure solve divides by its dt^2 and blew
    // the fluid up. The run's steps (step()) round the same way to frame times.
    if (duration - t <= 1e-9 * step) break;
    const double dt = std::min(step, duration - t);
    StepStats st;
    st.step = -settle_steps_;
    st.time = t;
    st.dt = dt;
    advance(dt, st, /*settling=*/true);
    const double keep = std::exp(-dt / tau);
    parallel_for(fluid_.size(), [&](Index i) { fluid_.v[i] *= keep; });
    ++settle_steps_;
    t += dt;
    check_stability(st);
  }
  std::fill(fluid_.v.begin(), fluid_.v.end(), Vec2::Zero());
  recompute_density();
}

// The moving walls' work on each fluid particle, summed by the phases of one step (and by
// the start relaxation's solve); energy.cpp reads it. Sized here, before any of them adds.
void Simulation::reset_boundary_work() {
  if (has_moving_boundaries()) scratch_->work.assign(static_cast<size_t>(fluid_.size()), 0.0);
}

void Simulation::advance(double dt, StepStats& st, bool settling) {
  reset_boundary_work();
  for (const Phase phase : kPhases) {
    if (phase == Phase::Boundary && (settling || !has_moving_boundaries())) continue;  // its time stays 0
    const Stopwatch t;
    run_phase(phase, dt, st);
    st.ms(phase) = t.ms();
  }
}

void Simulation::run_phase(Phase phase, double dt, StepStats& st) {
  switch (phase) {
    case Phase::Boundary:  // chapter 4: scripted poses, then the volumes of 4.1 where they can change
      move_boundaries(dt);
      update_boundary_volumes();
      break;
    case Phase::Neighbors:  // Algorithm 2's first loop: neighbours and density (with the periodic spatial sort)
      if (step_stamp() % kReorderEvery == 0) reorder_fluid();
      find_neighbors_phase();
      compute_density();
      break;
    case Phase::NonPressure: {  // Eq. 15 at the step's start, then Eq. 12 and gravity
      const Index n = fluid_.size();
      const double rho0 = settings_.rest_density;
      const auto [sum, largest] =
          parallel_sum_max(n, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); });
      st.density_error_percent = n ? sum / n : 0.0;
      scratch_->start_compression_max = largest;
      scratch_->start_compression_stamp = step_stamp();
      apply_nonpressure(dt);
      break;
    }
    case Phase::Pressure:
      if (settings_.type == SolverType::IISPH)
        solve_pressure_iisph(dt, st);
      else
        solve_pressure_wcsph(dt, st);
      break;
    case Phase::Integrate: {  // semi-implicit Euler, then Eq. 14's CFL number and the energies
      integrate(dt);
      const Index n = fluid_.size();
      const double vmax = std::sqrt(parallel_max(n, 0.0, [&](Index i) { return fluid_.v[i].squaredNorm(); }));
      st.max_cfl = vmax * dt / setup_.spacing;
      measure_energy(st);
      break;
    }
  }
}

// Fixed dt, or the CFL condition Eq. 14: dt = lambda h / v_max, at most dt_max and at most
// the ambient-pressure limit kHydrostaticCfl h / sqrt(|g| H).
double Simulation::choose_time_step() const {
  const TimeSettings& ts = setup_.time;
  if (ts.dt > 0) return ts.dt;
  const Index n = fluid_.size();
  // Moving boundary samples must not outrun the fluid's CFL bound either.
  const double vmax = std::max(std::sqrt(parallel_max(n, 0.0, [&](Index i) { return fluid_.v[i].squaredNorm(); })),
                               max_boundary_speed());
  double dt = ts.dt_max;
  if (vmax > 0) dt = std::min(dt, ts.cfl * setup_.spacing / vmax);
  // The ambient-pressure limit, which Eq. 14 leaves out (the thesis is silent on it).
  const double c_h = hydrostatic_speed();
  if (c_h > 0) dt = std::min(dt, kHydrostaticCfl * setup_.spacing / c_h);
  // WCSPH also resolves its sound waves (Monaghan 1992): dt <= 0.4 h / (c + v_max).
  if (settings_.type == SolverType::WCSPH) dt = std::min(dt, kAcousticCfl * setup_.spacing / (wcsph_speed_ + vmax));
  if (dt < ts.dt_min) {
    std::ostringstream os;
    os << "unstable at step " << step_ + 1 << ", t = " << time_ << " s: the CFL time step " << dt
       << " s fell below time.dt_min = " << ts.dt_min << " s (max speed " << vmax << " m/s, sqrt(g H) " << c_h
       << " m/s)";
    throw SimulationUnstable(os.str());
  }
  return dt;
}

// sqrt(|g| H), H the fluid's extent along g: the speed that the hydrostatic pressure
// rho0 |g| H at the bottom of the fluid gives it (Bernoulli). Displacements that keep the
// density (particles sliding past each other under Eq. 24's sum form) meet a restoring
// force that grows with the ambient pressure and that the implicit solve does not see; the
// step integrates it explicitly, and a deep column boils from the bottom up past about
// h / sqrt(g H) (docs/performance.md, "The stable step of a deep fluid"). Not the solve's
// largest pressure: a solve that falls short of its tolerance raises it as 1 / dt^2, a
// shorter step raises it further, and a 2 m column's step fell to 0.1 ms in four steps.
double Simulation::hydrostatic_speed() const {
  const Index n = fluid_.size();
  const double g = settings_.gravity.norm();
  if (g <= 0.0 || n == 0) return 0.0;
  const Vec2 down = settings_.gravity / g;
  constexpr double kLow = -std::numeric_limits<double>::infinity();
  const double deepest = parallel_max(n, kLow, [&](Index i) { return fluid_.x[i].dot(down); });
  const double highest = -parallel_max(n, kLow, [&](Index i) { return -fluid_.x[i].dot(down); });
  return std::sqrt(g * (deepest - highest));
}

// Semi-implicit Euler (Algorithm 1/2): v(t+dt) = v* + dt a_p, x(t+dt) = x + dt v(t+dt).
void Simulation::integrate(double dt) {
  SLUICE_ASSERT(scratch_->a_p.size() == static_cast<size_t>(fluid_.size()),
                "the pressure solve left one a_p per particle");
  parallel_for(fluid_.size(), [&](Index i) {
    fluid_.v[i] += dt * scratch_->a_p[i];
    fluid_.x[i] += dt * fluid_.v[i];
  });
}

void Simulation::reorder_fluid() {
  const std::vector<Index> order = spatial_order(fluid_.x, kernel_.support());
  std::vector<Vec2> sv;
  std::vector<double> sd;
  std::vector<Index> si;
  apply_permutation(fluid_.x, order, sv);
  apply_permutation(fluid_.v, order, sv);
  apply_permutation(fluid_.rho, order, sd);
  apply_permutation(fluid_.p, order, sd);
  apply_permutation(fluid_.id, order, si);
}

void Simulation::recompute_density() {
  find_neighbors_phase();
  compute_density();
}

}  // namespace sluice
