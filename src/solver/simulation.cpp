#include "solver/simulation.h"

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

// IISPH has no sound speed; its artificial viscosity takes Monaghan's (1994) choice for a
// weakly compressible fluid, c = 10 v_max, with v_max = sqrt(2 g H) of the fluid's
// initial height H (or its fastest initial particle, if faster).
double incompressible_sound_speed(const SimulationSetup& setup) {
  const Vec2 g = setup.solver.gravity;
  double vmax = 0, lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Vec2& v : setup.fluid_v) vmax = std::max(vmax, v.norm());
  if (g.norm() > 0) {
    const Vec2 up = -g.normalized();
    for (const Vec2& x : setup.fluid_x) {
      lo = std::min(lo, x.dot(up));
      hi = std::max(hi, x.dot(up));
    }
    if (hi >= lo) vmax = std::max(vmax, std::sqrt(2.0 * g.norm() * (hi - lo + setup.spacing)));
  }
  return 10.0 * vmax;
}

}  // namespace

// sum_j W(x_ij) over a square lattice of spacing h (self included): 1.000862 / h^2 for
// the cubic spline. The fluid mass is rho0 / this sum, so that a filled lattice is at
// rest density exactly; with m = rho0 h^2 every particle of the initial block would be
// 0.086% compressed and IISPH would push the whole block apart in its first step.
double lattice_kernel_sum(const CubicSpline2D& kernel) {
  double sum = 0.0;
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j) sum += kernel.W(kernel.h() * std::sqrt(double(i * i + j * j)));
  return sum;
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

Simulation::Simulation(const SimulationSetup& setup)
    : setup_(setup),
      settings_(setup.solver),
      kernel_(setup.spacing),
      mass_(setup.solver.rest_density / lattice_kernel_sum(kernel_)),
      scratch_(std::make_unique<SolverScratch>()) {
  SLUICE_ASSERT(setup.spacing > 0, "the setup's spacing is positive (the scene checks it)");
  SLUICE_ASSERT(setup.boundary_object.empty() || setup.boundary_object.size() == setup.boundary_x.size(),
                "one object index per boundary sample");
  for (const BoundaryObject& obj : setup.objects)
    SLUICE_ASSERT(
        obj.first >= 0 && obj.count >= 0 && obj.first + obj.count <= static_cast<Index>(setup.boundary_x.size()),
        "an object's samples lie within boundary_x");
  const Index n = static_cast<Index>(setup.fluid_x.size());
  fluid_.resize(n);
  for (Index i = 0; i < n; ++i) {
    fluid_.x[i] = setup.fluid_x[i];
    fluid_.v[i] = i < static_cast<Index>(setup.fluid_v.size()) ? setup.fluid_v[i] : Vec2::Zero();
    fluid_.rho[i] = settings_.rest_density;
    fluid_.p[i] = 0.0;
    fluid_.id[i] = i;
  }

  // Boundary particles in spatial order, once. Moving ones keep their rest position x0
  // and get their pose from the script every step.
  const std::vector<Index> order = spatial_order(setup.boundary_x, kernel_.support());
  const Index nb = static_cast<Index>(order.size());
  boundary_.x.resize(nb);
  boundary_.object.resize(nb);
  boundary_.moving.assign(nb, 0);
  for (Index k = 0; k < nb; ++k) {
    boundary_.x[k] = setup.boundary_x[order[k]];
    boundary_.object[k] = setup.boundary_object.empty() ? 0 : setup.boundary_object[order[k]];
    if (boundary_.object[k] < static_cast<Index>(setup.objects.size()) && setup.objects[boundary_.object[k]].moving) {
      boundary_.moving[k] = 1;
      moving_.push_back(k);
    }
  }
  boundary_.x0 = boundary_.x;
  boundary_.v.assign(nb, Vec2::Zero());
  boundary_.a.assign(nb, Vec2::Zero());
  boundary_.p.assign(nb, 0.0);
  boundary_.volume.assign(nb, 0.0);
  near_moving_.assign(nb, 0);
  if (has_moving_boundaries()) {
    move_boundaries(0.0);  // the pose at t = 0 (a script may start displaced), grid, volumes
    volume_update_.resize(static_cast<size_t>(nb));
    for (Index b = 0; b < nb; ++b) volume_update_[b] = b;
    compute_volumes(boundary_grid_, volume_update_, boundary_.volume);
  } else {
    // Walls at rest: a grid with many cells per point (built once) and volumes once.
    boundary_grid_.build(boundary_.x, kernel_.support(), /*cells_per_point=*/1024.0);
    std::vector<Index> all(static_cast<size_t>(nb));
    for (Index b = 0; b < nb; ++b) all[b] = b;
    compute_volumes(boundary_grid_, all, boundary_.volume);
  }

  const Vec2 size = (setup.bounds_max - setup.bounds_min).cwiseMax(Vec2::Constant(setup.spacing));
  const double margin = setup.limits.bounds_margin * size.maxCoeff();
  lost_min_ = setup.bounds_min - Vec2::Constant(margin);
  lost_max_ = setup.bounds_max + Vec2::Constant(margin);

  last_frame_ = static_cast<Index>(std::ceil(setup.time.duration * setup.time.fps - 1e-9));
  wcsph_speed_ = std::sqrt(settings_.stiffness / settings_.rest_density);
  sound_speed_ = settings_.sound_speed;
  if (sound_speed_ <= 0)
    sound_speed_ = settings_.type == SolverType::WCSPH ? wcsph_speed_ : incompressible_sound_speed(setup);
  reorder_fluid();
  recompute_density();
  if (setup.time.settle > 0) settle();
}

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
void Simulation::settle() {
  const double duration = setup_.time.settle, tau = 0.1 * duration;
  std::fill(boundary_.v.begin(), boundary_.v.end(), Vec2::Zero());
  std::fill(boundary_.a.begin(), boundary_.a.end(), Vec2::Zero());
  double t = 0;
  while (t < duration) {
    const double dt = std::min(choose_time_step(), duration - t);
    StepStats st;
    st.step = -settle_steps_;
    st.time = t;
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

void Simulation::advance(double dt, StepStats& st, bool settling) {
  if (has_moving_boundaries()) scratch_->work.assign(static_cast<size_t>(fluid_.size()), 0.0);
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
      if ((step_ + settle_steps_) % kReorderEvery == 0) reorder_fluid();
      find_neighbors_phase();
      compute_density();
      break;
    case Phase::NonPressure: {  // Eq. 15 at the step's start, then Eq. 12 and gravity
      const Index n = fluid_.size();
      const double rho0 = settings_.rest_density;
      st.density_error_percent =
          n ? parallel_sum(n, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); }) / n : 0.0;
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

// Fixed dt, or the CFL condition Eq. 14: dt = lambda h / v_max, at most dt_max.
double Simulation::choose_time_step() const {
  const TimeSettings& ts = setup_.time;
  if (ts.dt > 0) return ts.dt;
  const Index n = fluid_.size();
  // Moving boundary samples must not outrun the fluid's CFL bound either.
  const double vmax = std::max(std::sqrt(parallel_max(n, 0.0, [&](Index i) { return fluid_.v[i].squaredNorm(); })),
                               max_boundary_speed());
  double dt = ts.dt_max;
  if (vmax > 0) dt = std::min(dt, ts.cfl * setup_.spacing / vmax);
  // WCSPH also resolves its sound waves (Monaghan 1992): dt <= 0.4 h / (c + v_max).
  if (settings_.type == SolverType::WCSPH) dt = std::min(dt, kAcousticCfl * setup_.spacing / (wcsph_speed_ + vmax));
  if (dt < ts.dt_min) {
    std::ostringstream os;
    os << "unstable at step " << step_ + 1 << ", t = " << time_ << " s: the CFL time step " << dt
       << " s fell below time.dt_min = " << ts.dt_min << " s (max speed " << vmax << " m/s)";
    throw SimulationUnstable(os.str());
  }
  return dt;
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

double Simulation::mechanical_energy() const {
  StepStats st;
  measure_energy(st);
  return st.mechanical_energy;
}

void Simulation::measure_energy(StepStats& st) const {
  const Index n = fluid_.size();
  const Vec2 g = settings_.gravity;
  st.kinetic_energy = 0.5 * mass_ * parallel_sum(n, [&](Index i) { return fluid_.v[i].squaredNorm(); });
  st.potential_energy = -mass_ * parallel_sum(n, [&](Index i) { return g.dot(fluid_.x[i]); });
  st.mechanical_energy = st.kinetic_energy + st.potential_energy;
  st.boundary_work = scratch_->work.size() == static_cast<size_t>(n) && has_moving_boundaries()
                         ? parallel_sum(n, [&](Index i) { return scratch_->work[i]; })
                         : 0.0;
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
