#include "solver/simulation.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/parallel.h"
#include "solver/leak_check.h"

namespace sluice {

namespace {

constexpr long kReorderEvery = 16;  // steps between spatial sorts of the fluid arrays
// Particles per block of the fused Jacobi sweep (see jacobi_sweep): a block's pairs
// (about 2 MB at 16384) stay in cache until its updates read them again.
constexpr Index kSweepBlock = 16384;
// An update waits for at most this many blocks after its own; particles with a
// neighbour further ahead are deferred.
constexpr int kMaxSweepLag = 2;
// The fused sweep is used when the iteration's arrays exceed this many bytes, three
// quarters of the 32 MB L3 of the machine it was measured on (see jacobi_block_size).
// Elsewhere the crossover moves with the cache; either way the bits are the same.
constexpr double kFuseAboveBytes = 24.0 * 1024 * 1024;

// Warm start p^(0) = 0.5 p(t - dt), the choice of [Ihm+14a]. A factor of 1 keeps the
// part of the previous pressure that the operator A barely sees (lattice-scale,
// checkerboard-like noise) forever; it then drives particles apart and a column at
// rest never settles (kinetic energy grows). Halving it every step lets it decay.
constexpr double kWarmStartFactor = 0.5;

class Stopwatch {
 public:
  Stopwatch() : t0_(std::chrono::steady_clock::now()) {}
  double ms() const {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0_).count();
  }

 private:
  std::chrono::steady_clock::time_point t0_;
};

// The gradient correction leaves particles whose support is less than this full (the
// trace is 2 in a full support) uncorrected: at the free surface 2 / trace grows without
// bound.
constexpr double kMinGradientTrace = 1.6;

// Relative compression of Eq. 15 in percent.
inline double compression_percent(double rho, double rho0) {
  return std::max(100.0 * (rho - rho0) / rho0, 0.0);
}

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

Simulation::Simulation(const SimulationSetup& setup)
    : setup_(setup),
      settings_(setup.solver),
      kernel_(setup.spacing),
      mass_(setup.solver.rest_density / lattice_kernel_sum(kernel_)) {
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
  if (sound_speed_ <= 0) sound_speed_ = settings_.type == SolverType::WCSPH ? wcsph_speed_ : incompressible_sound_speed(setup);
  reorder_fluid();
  recompute_density();
  if (setup.time.settle > 0) settle();
}

// Section 4.1: V_b = gamma1 / sum_b' W(x_bb'), summed over all boundary particles of
// every object (self included), so touching and overlapping objects share their volume.
// Each sum runs in ascending index order, whatever the grid's layout (which follows the
// moving samples), so a volume kept from an earlier step has the same bits as one
// computed from scratch now.
void Simulation::compute_volumes(const SpatialHashGrid& grid, const std::vector<Index>& which,
                                 std::vector<double>& volume) const {
  const double r = kernel_.support(), w0 = kernel_.W(0.0), gamma1 = settings_.gamma1;
  const std::vector<Vec2>& x = grid.points();
  const Index n = static_cast<Index>(which.size());
#pragma omp parallel if (n >= kParallelMin / 8)
  {
    std::vector<Index> near;
#pragma omp for schedule(dynamic, kForChunk)
    for (Index k = 0; k < n; ++k) {
      const Index b = which[k];
      const Vec2 xb = x[b];
      const size_t count = grid.gather_within(xb, r, b, near, 0);
      std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));
      double sum = w0;
      for (size_t m = 0; m < count; ++m) sum += kernel_.W((xb - x[near[m]]).norm());
      volume[b] = gamma1 / sum;
    }
  }
}

std::vector<double> Simulation::boundary_volumes_from_scratch() const {
  std::vector<Index> all(static_cast<size_t>(boundary_.size()));
  for (Index b = 0; b < boundary_.size(); ++b) all[b] = b;
  SpatialHashGrid grid;
  grid.build(boundary_.x, kernel_.support());
  std::vector<double> volume(all.size(), 0.0);
  compute_volumes(grid, all, volume);
  return volume;
}

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
          "time " + std::to_string(s.time) + " s is outside this scene's 0.." + std::to_string(setup_.time.duration) + " s");
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

// Scripted motion (chapter 4, dynamic boundaries): every moving sample gets its position
// and acceleration from its object's pose at the step's time t, and the velocity at
// t + dt/2, the mean velocity over the step to second order, which the source term
// (Eq. 16/19) and viscosity use to predict where the boundary is at t + dt. Positions
// come from the script at t, never from accumulated increments.
void Simulation::move_boundaries(double dt) {
  std::vector<PoseMap> now, mid;
  for (const BoundaryObject& obj : setup_.objects) {
    now.emplace_back(obj.moving ? obj.motion.at(time_) : Pose{});
    mid.emplace_back(obj.moving ? obj.motion.at(time_ + 0.5 * dt) : Pose{});
  }
  parallel_for(static_cast<Index>(moving_.size()), [&](Index k) {
    const Index b = moving_[k];
    const Index o = boundary_.object[b];
    const Vec2 x0 = boundary_.x0[b];
    boundary_.x[b] = now[o].position(x0);
    boundary_.v[b] = mid[o].velocity(x0);
    boundary_.a[b] = now[o].acceleration(x0);
  });
  // The grid is rebuilt with every step's positions (few cells per point, as the
  // fluid's); the static walls ride along.
  boundary_grid_.build(boundary_.x, kernel_.support());
}

// Section 4.1 for the samples whose boundary neighbourhood may have changed since the
// last step: every moving sample, and every static one with a moving sample in its
// support now or at the last update. Static walls far from any moving part keep their
// volumes.
void Simulation::update_boundary_volumes() {
  const double r = kernel_.support(), w0 = kernel_.W(0.0), gamma1 = settings_.gamma1;
  const Index nm = static_cast<Index>(moving_.size());
  std::vector<std::uint8_t> near_now(near_moving_.size(), 0);
  // Moving samples: volume and, in the same gather, the static samples they reach.
  // (Volume loops do far more work per item than a particle loop: a lower threshold.)
#pragma omp parallel if (nm >= kParallelMin / 8)
  {
    std::vector<Index> near;
#pragma omp for schedule(dynamic, kForChunk)
    for (Index k = 0; k < nm; ++k) {
      const Index b = moving_[k];
      const Vec2 xb = boundary_.x[b];
      const size_t count = boundary_grid_.gather_within(xb, r, b, near, 0);
      std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));  // index order, as compute_volumes
      double sum = w0;
      for (size_t m = 0; m < count; ++m) {
        const Index j = near[m];
        sum += kernel_.W((xb - boundary_.x[j]).norm());
        if (!boundary_.moving[j])  // every writer stores 1: the result is order-free
          std::atomic_ref<std::uint8_t>(near_now[j]).store(1, std::memory_order_relaxed);
      }
      boundary_.volume[b] = gamma1 / sum;
    }
  }
  volume_update_.clear();
  for (Index b = 0; b < boundary_.size(); ++b)
    if (near_now[b] || near_moving_[b]) volume_update_.push_back(b);
  near_moving_.swap(near_now);
  compute_volumes(boundary_grid_, volume_update_, boundary_.volume);
}

double Simulation::max_boundary_speed() const {
  double vmax = 0.0;
  for (size_t o = 0; o < setup_.objects.size(); ++o) {
    const BoundaryObject& obj = setup_.objects[o];
    if (!obj.moving) continue;
    const PoseMap pose(obj.motion.at(time_));
    for (Index k = 0; k < obj.count; ++k)
      vmax = std::max(vmax, pose.velocity(setup_.boundary_x[obj.first + k]).squaredNorm());
  }
  return std::sqrt(vmax);
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
  if (has_moving_boundaries()) scratch_.work.assign(static_cast<size_t>(fluid_.size()), 0.0);
  if (has_moving_boundaries() && !settling) {
    const Stopwatch t;
    move_boundaries(dt);
    update_boundary_volumes();
    st.ms_boundary = t.ms();
  }
  {
    // Algorithm 2's first loop: neighbours and density (with the periodic spatial sort).
    const Stopwatch t;
    if ((step_ + settle_steps_) % kReorderEvery == 0) reorder_fluid();
    find_neighbors_phase();
    compute_density();
    st.ms_neighbors = t.ms();
  }
  {
    const Stopwatch t;
    const Index n = fluid_.size();
    const double rho0 = settings_.rest_density;
    st.density_error_percent =
        n ? parallel_sum(n, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); }) / n : 0.0;
    apply_nonpressure(dt);
    st.ms_nonpressure = t.ms();
  }
  {
    const Stopwatch t;
    if (settings_.type == SolverType::IISPH)
      solve_pressure_iisph(dt, st);
    else
      solve_pressure_wcsph(dt, st);
    st.ms_pressure = t.ms();
  }
  {
    const Stopwatch t;
    integrate(dt);
    const Index n = fluid_.size();
    const double vmax = std::sqrt(parallel_max(n, 0.0, [&](Index i) { return fluid_.v[i].squaredNorm(); }));
    st.max_cfl = vmax * dt / setup_.spacing;
    measure_energy(st);
    st.ms_integrate = t.ms();
  }
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
  st.boundary_work = scratch_.work.size() == static_cast<size_t>(n) && has_moving_boundaries()
                         ? parallel_sum(n, [&](Index i) { return scratch_.work[i]; })
                         : 0.0;
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

void Simulation::find_neighbors_phase() {
  const PairCache none{};
  if (brute_force_) {
    find_neighbors_brute_force(fluid_.x, fluid_.x, kernel_.support(), true, ff_);
    find_neighbors_brute_force(fluid_.x, boundary_.x, kernel_.support(), false, fb_);
  } else {
    fluid_grid_.build(fluid_.x, kernel_.support());
    find_neighbors(fluid_.x, fluid_grid_, kernel_, /*exclude_self=*/true, none, ff_);
    find_neighbors(fluid_.x, boundary_grid_, kernel_, /*exclude_self=*/false, none, fb_);
  }
}

// One pass over all pairs: caches grad W (in single precision, see NeighborLists) for fluid and boundary pairs (and W for
// boundary pairs, which Eq. 25 gathers again) and sums the density of Eq. 13 with the
// boundary term of section 4.1:
//   rho_i = sum_f m_f W_if + gamma2 sum_b m_b W_ib,  m_b = rho0 V_b.
void Simulation::compute_density() {
  const double w0 = kernel_.W(0.0);
  const double rho0 = settings_.rest_density, g2 = settings_.gamma2;
  ff_.grad.resize(static_cast<size_t>(ff_.pairs()));
  fb_.grad.resize(static_cast<size_t>(fb_.pairs()));
  fb_.w.resize(static_cast<size_t>(fb_.pairs()));
  const bool correct = settings_.gradient_correction;
  if (correct) scratch_.grad_scale.resize(fluid_.size());
  parallel_for(fluid_.size(), [&](Index i) {
    const Vec2 xi = fluid_.x[i];
    double w, dw;
    double sf = w0, mf = 0.0, mb = 0.0;
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      const Vec2 r = xi - fluid_.x[ff_.j[k]];
      const double r2 = r.squaredNorm();
      kernel_.eval(std::sqrt(r2), w, dw);
      sf += w;
      mf += dw * r2;
      ff_.grad[k] = (dw * r).cast<float>();
    }
    double sb = 0.0;
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const Vec2 r = xi - boundary_.x[b];
      const double r2 = r.squaredNorm();
      kernel_.eval(std::sqrt(r2), w, dw);
      sb += boundary_.volume[b] * w;
      mb += boundary_.volume[b] * dw * r2;
      fb_.w[k] = w;
      fb_.grad[k] = (dw * r).cast<float>();
    }
    fluid_.rho[i] = mass_ * sf + g2 * rho0 * sb;
    if (correct) {
      // tr(sum_j V_j x_ji (x) grad W_ij) = -sum_j V_j r_ij^2 (dW/dr)/r: 2 for an exact gradient.
      const double trace = -(mass_ / rho0 * mf + mb);
      scratch_.grad_scale[i] = trace > kMinGradientTrace ? 2.0 / trace : 1.0;
    }
  });
  if (correct) correct_gradients();
  // Eq. 25 gathers over the fluid neighbours of each boundary particle.
  // Eq. 25 and pressure boundaries gather over the fluid neighbours of each sample.
  if (settings_.boundary_pressure == BoundaryPressure::Extrapolation ||
      settings_.boundary_pressure == BoundaryPressure::Solved)
    transpose_neighbors(fb_, boundary_.size(), bf_);
}

// The scalar gradient correction (solver.gradient_correction; the thesis uses grad W_ij as
// is in Eq. 11-24, which is 1.3 % weak on a settled arrangement): fluid pairs scale by
// (c_i + c_j) / 2, which keeps them antisymmetric (momentum is conserved), boundary pairs
// by c_i. A free-surface particle (trace below kMinGradientTrace) is left as it is.
void Simulation::correct_gradients() {
  const std::vector<double>& c = scratch_.grad_scale;
  parallel_for(fluid_.size(), [&](Index i) {
    const double ci = c[i];
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k)
      ff_.grad[k] *= static_cast<float>(0.5 * (ci + c[ff_.j[k]]));
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) fb_.grad[k] *= static_cast<float>(ci);
  });
}

// v* = v + dt (a_v + g): the viscosity of Eq. 12 and Monaghan's artificial viscosity
// (1992, Eq. 4.1; the thesis has none), against fluid and boundary neighbours (boundary
// neighbours with their own velocity, m_b = rho0 V_b, rho_b = rho0):
//   a_i += -sum_j m_j Pi_ij grad W_ij,  Pi_ij = -alpha c h mu_ij / rho_ij for v_ij . x_ij < 0,
//   mu_ij = v_ij . x_ij / (|x_ij|^2 + 0.01 h^2),  rho_ij = (rho_i + rho_j) / 2.
// With both off the neighbour pass is skipped. The boundary pairs' share of a_v, times
// the boundary velocity, is the boundaries' work on the fluid (scratch_.work).
void Simulation::apply_nonpressure(double dt) {
  const Vec2 g = settings_.gravity;
  const double nu = settings_.viscosity, rho0 = settings_.rest_density;
  const double avc = settings_.artificial_viscosity * sound_speed_ * setup_.spacing;
  const Index n = fluid_.size();
  if (nu <= 0.0 && avc <= 0.0) {
    parallel_for(n, [&](Index i) { fluid_.v[i] += dt * g; });
    return;
  }
  std::vector<Vec2>& a_v = scratch_.a_p;  // reused as scratch: a_p is recomputed later
  a_v.resize(n);
  const double eps = 0.01 * setup_.spacing * setup_.spacing;
  const bool work = has_moving_boundaries();
  parallel_for(n, [&](Index i) {
    const Vec2 xi = fluid_.x[i], vi = fluid_.v[i];
    const double rhoi = fluid_.rho[i];
    Vec2 lap = Vec2::Zero(), art = Vec2::Zero();
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      const Index j = ff_.j[k];
      const Vec2 xij = xi - fluid_.x[j], vij = vi - fluid_.v[j], gw = ff_.grad[k].cast<double>();
      const double r2 = xij.squaredNorm() + eps, vx = vij.dot(xij);
      lap += (mass_ / fluid_.rho[j]) * (xij.dot(gw) / r2) * vij;
      if (vx < 0.0) art += (mass_ * vx / (r2 * 0.5 * (rhoi + fluid_.rho[j]))) * gw;
    }
    Vec2 acc = 2.0 * nu * lap + avc * art;
    double w = 0.0;
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const Vec2 xib = xi - boundary_.x[b], vib = vi - boundary_.v[b], gw = fb_.grad[k].cast<double>();
      const double r2 = xib.squaredNorm() + eps, vx = vib.dot(xib), vb = boundary_.volume[b];
      Vec2 a = (2.0 * nu * vb * (xib.dot(gw) / r2)) * vib;
      if (vx < 0.0) a += (avc * rho0 * vb * vx / (r2 * 0.5 * (rhoi + rho0))) * gw;
      acc += a;
      if (work) w += a.dot(boundary_.v[b]);
    }
    a_v[i] = acc;
    if (work) scratch_.work[i] += dt * mass_ * w;
  });
  parallel_for(n, [&](Index i) { fluid_.v[i] += dt * (a_v[i] + g); });
}

// Per-step boundary quantities of the pressure solvers:
//   grad_b_i = sum_b m_b grad W_ib (Eq. 24 and Eq. 26 boundary sums),
//   for Eq. 25: sum_f W_bf and (g - a_b) . sum_f rho_f x_bf W_bf, the hydrostatic term
//   in the frame of a boundary sample that accelerates with a_b.
void Simulation::prepare_boundary_terms() {
  const Index n = fluid_.size(), nb = boundary_.size();
  const double rho0 = settings_.rest_density;
  scratch_.grad_b.resize(n);
  parallel_for(n, [&](Index i) {
    Vec2 g = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) g += (rho0 * boundary_.volume[fb_.j[k]]) * fb_.grad[k].cast<double>();
    scratch_.grad_b[i] = g;
  });
  scratch_.pb_over_rho2.assign(nb, 0.0);
  if (settings_.boundary_pressure != BoundaryPressure::Extrapolation) return;
  scratch_.ext_wsum.resize(nb);
  scratch_.ext_gravity.resize(nb);
  const Vec2 gravity = settings_.gravity;
  parallel_for(nb, [&](Index b) {
    double ws = 0.0;
    Vec2 xr = Vec2::Zero();
    for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
      const Index f = bf_.j[k];
      ws += bf_.w[k];
      xr += (fluid_.rho[f] * bf_.w[k]) * (boundary_.x[b] - fluid_.x[f]);
    }
    scratch_.ext_wsum[b] = ws;
    scratch_.ext_gravity[b] = (gravity - boundary_.a[b]).dot(xr);  // an accelerating wall: g - a_b
  });
}

// Density of boundary sample b from its fluid neighbours plus its wall's own share:
//   rho_b = sum_f m_f W_bf + rho0 sum_b' V_b' W_bb' ~ sum_f m_f W_bf + gamma1 rho0,
// the second by the definition of V_b (section 4.1; exact for a uniformly sampled wall).
// A sample continuing the fluid's lattice is then at rest density.
inline double boundary_density(const NeighborLists& bf, Index b, double mass, double gamma1_rho0) {
  double rf = 0.0;
  for (Index k = bf.offset[b]; k < bf.offset[b + 1]; ++k) rf += bf.w[k];
  return mass * rf + gamma1_rho0;
}

// Pressure boundaries (Band et al. 2018, "Pressure boundaries for implicit incompressible
// SPH", ACM TOG 37(2)): the density constraint of each boundary sample with fluid
// neighbours joins the PPE, so p_b is its Lagrange multiplier and the boundary term of
// Eq. 24 becomes a constraint force, which does no work while the constraints hold.
// The sample's counterparts of Eq. 19 and 22, with a_b = 0 (its motion is scripted):
//   s_b = (rho0 - rho_b) / dt - sum_f m_f (v_b - v*_f) . grad W_bf,
//   (Ap)_b = -dt sum_f m_f a_f . grad W_bf,
//   a_bb = d(Ap)_b / dp_b = -dt gamma3 (V_b m / rho0) sum_f |grad W_bf|^2.
Index Simulation::prepare_solved_boundary(double dt) {
  const SolverSettings& s = settings_;
  const double rho0 = s.rest_density, g1r = s.gamma1 * rho0, inv_rho0_2 = 1.0 / (rho0 * rho0);
  const bool thesis_init = s.pressure_init == PressureInit::Thesis;
  const Index nb = boundary_.size();
  const double vb_scale = boundary_velocity_in_source_ ? 1.0 : 0.0;
  scratch_.bnd_s.resize(nb);
  scratch_.bnd_aii.resize(nb);
  parallel_for(nb, [&](Index b) {
    double wsum = 0.0, div = 0.0, grad2 = 0.0, lumped = 0.0;
    for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
      const Index f = bf_.j[k];
      const Vec2 gw = bf_.grad[k].cast<double>();
      wsum += bf_.w[k];
      div += (vb_scale * boundary_.v[b] - fluid_.v[f]).dot(gw);
      grad2 += gw.squaredNorm();
      lumped += gw.dot(scratch_.grad_b[f]);
    }
    // rho_b as in boundary_density, summed in the same pass over the sample's pairs.
    const double sb = (rho0 - (mass_ * wsum + g1r)) / dt - mass_ * div;
    // The row's diagonal, or its lumped sum over all samples that share a fluid neighbour
    // (dt gamma3 m / rho0^2 sum_f grad W_bf . grad_b_f) when larger: samples denser than
    // the fluid, or a thin plate sampled on both sides, are near-duplicate constraints,
    // and Jacobi with the plain diagonal overshoots on them by their number and diverges.
    const double abb = std::min(-dt * s.gamma3 * boundary_.volume[b] / rho0 * mass_ * grad2,
                                dt * s.gamma3 * mass_ / (rho0 * rho0) * lumped);
    scratch_.bnd_s[b] = sb;
    scratch_.bnd_aii[b] = abb;
    double p0 = abb != 0.0 ? kWarmStartFactor * boundary_.p[b] : 0.0;
    if (thesis_init) p0 = abb != 0.0 ? std::max(s.omega * sb / abb, 0.0) : 0.0;
    boundary_.p[b] = p0;
    scratch_.pb_over_rho2[b] = p0 * inv_rho0_2;
  });
  return static_cast<Index>(parallel_sum(nb, [&](Index b) { return scratch_.bnd_aii[b] != 0.0 ? 1.0 : 0.0; }));
}

// Eq. 21 for every boundary sample, from the accelerations a_p of the iteration (all
// computed before: the sweep has finished), clamped at zero like the fluid's. Returns
// the sum of the samples' predicted compression (Eq. 23) at these accelerations.
double Simulation::jacobi_update_boundary(const PressureTerms& t) {
  const double inv_rho0_2 = 1.0 / (settings_.rest_density * settings_.rest_density);
  return parallel_sum(boundary_.size(), [&](Index b) {
    const double abb = scratch_.bnd_aii[b];
    if (abb == 0.0) return 0.0;  // no fluid neighbour: p_b stays 0
    double ap = 0.0;
    for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) ap -= scratch_.a_p[bf_.j[k]].dot(bf_.grad[k].cast<double>());
    ap *= t.dt * t.mass;
    const double p = std::max(boundary_.p[b] + t.omega / abb * (scratch_.bnd_s[b] - ap), 0.0);
    boundary_.p[b] = p;
    scratch_.pb_over_rho2[b] = p * inv_rho0_2;
    return std::max(t.err_scale * (ap - scratch_.bnd_s[b]), 0.0);
  });
}

// The pressure force's share of the boundaries' work on the fluid: the boundary pairs'
// term of Eq. 24 (with the pressures the step integrates) times the boundary velocity.
void Simulation::add_boundary_pressure_work(double dt) {
  const PressureTerms t = pressure_terms(dt);
  const std::vector<double>& pr = scratch_.p_over_rho2;
  parallel_for(fluid_.size(), [&](Index i) {
    double w = 0.0;
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      if (!boundary_.moving[b]) continue;
      const double pb = t.boundary_field ? scratch_.pb_over_rho2[b] : 0.0;
      const double c = t.c_gamma3 / settings_.gamma3;  // 2 for mirroring: p_b / rho_b^2 = p_i / rho_i^2
      const Vec2 a = -(t.gamma3_rho0 * boundary_.volume[b] * (c * pr[i] + pb)) * fb_.grad[k].cast<double>();
      w += a.dot(boundary_.v[b]);
    }
    scratch_.work[i] += dt * mass_ * w;
  });
}

// Boundary pressure seen by fluid neighbours, as p_b / rho_b^2 (rho_b = rho0):
// WCSPH with pressure boundaries: the state equation of section 2.3.1 at rho_b (the
// sample's share of the energy, so its force is conservative as well);
// extrapolation, Eq. 25: p_b = (sum_f p_f W_bf + (g - a_b) . sum_f rho_f x_bf W_bf) / sum_f W_bf,
// clamped at zero like fluid pressures. Mirroring and zero pressure need no pass.
void Simulation::update_boundary_pressure() {
  const double rho0 = settings_.rest_density, inv_rho0_2 = 1.0 / (rho0 * rho0);
  if (settings_.boundary_pressure == BoundaryPressure::Solved && settings_.type == SolverType::WCSPH) {
    const double k = settings_.stiffness, g1r = settings_.gamma1 * rho0;
    parallel_for(boundary_.size(), [&](Index b) {
      const double p = bf_.offset[b] == bf_.offset[b + 1] ? 0.0
                                                         : std::max(k * (boundary_density(bf_, b, mass_, g1r) / rho0 - 1.0), 0.0);
      boundary_.p[b] = p;
      scratch_.pb_over_rho2[b] = p * inv_rho0_2;
    });
    return;
  }
  if (settings_.boundary_pressure != BoundaryPressure::Extrapolation) return;
  parallel_for(boundary_.size(), [&](Index b) {
    const double ws = scratch_.ext_wsum[b];
    double p = 0.0;
    if (ws > 0.0) {
      double sp = 0.0;
      for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) sp += fluid_.p[bf_.j[k]] * bf_.w[k];
      p = std::max((sp + scratch_.ext_gravity[b]) / ws, 0.0);
    }
    boundary_.p[b] = p;
    scratch_.pb_over_rho2[b] = p * inv_rho0_2;
  });
}

// Eq. 24: a_i = - sum_f m_f (p_i/rho_i^2 + p_f/rho_f^2) grad W_if
//               - gamma3 sum_b m_b (p_i/rho_i^2 + p_b/rho_b^2) grad W_ib.
// Mirroring (4.2.2) sets p_b/rho_b^2 = p_i/rho_i^2, zero pressure (4.2.3) p_b = 0, so
// their boundary sum is c gamma3 (p_i/rho_i^2) grad_b_i with c = 2 or 1.
Simulation::PressureTerms Simulation::pressure_terms(double dt) const {
  const SolverSettings& s = settings_;
  PressureTerms t;
  t.mass = mass_;
  t.c_gamma3 = (s.boundary_pressure == BoundaryPressure::Mirroring ? 2.0 : 1.0) * s.gamma3;
  t.gamma3_rho0 = s.gamma3 * s.rest_density;
  t.boundary_field =
      s.boundary_pressure == BoundaryPressure::Extrapolation || s.boundary_pressure == BoundaryPressure::Solved;
  t.gamma2 = s.gamma2;
  t.omega = s.omega;
  t.dt = dt;
  t.err_scale = 100.0 * dt / s.rest_density;
  return t;
}

[[gnu::always_inline]] inline Vec2 Simulation::pressure_acceleration_of(Index i, const PressureTerms& t) const {
  const std::vector<double>& pr = scratch_.p_over_rho2;
  const double pri = pr[i];
  Vec2 a = Vec2::Zero();
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) a += (pri + pr[ff_.j[k]]) * ff_.grad[k].cast<double>();
  a *= -t.mass;
  a -= (t.c_gamma3 * pri) * scratch_.grad_b[i];
  if (t.boundary_field) {
    Vec2 ab = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      ab += (boundary_.volume[b] * scratch_.pb_over_rho2[b]) * fb_.grad[k].cast<double>();
    }
    a -= t.gamma3_rho0 * ab;
  }
  return a;
}

void Simulation::compute_pressure_acceleration() {
  const PressureTerms t = pressure_terms(0.0);
  scratch_.a_p.resize(fluid_.size());
  parallel_for(fluid_.size(), [&](Index i) { scratch_.a_p[i] = pressure_acceleration_of(i, t); });
}

// One relaxed Jacobi update of particle i (Algorithm 2's second solver loop): (Ap)_i of
// Eq. 20 from the accelerations a_p of i and its fluid neighbours, the update of Eq. 21
// with negative pressures clamped, and the predicted compression of Eq. 23 (stored in
// err). Reads neighbours' a_p, writes only particle i.
[[gnu::always_inline]] inline void Simulation::jacobi_update_of(Index i, const PressureTerms& t) {
  const Vec2 ai = scratch_.a_p[i];
  double ap = 0.0;
  for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) ap += (ai - scratch_.a_p[ff_.j[k]]).dot(ff_.grad[k].cast<double>());
  ap = t.dt * (t.mass * ap + t.gamma2 * ai.dot(scratch_.grad_b[i]));
  const double si = scratch_.s[i], aii = scratch_.a_ii[i];
  const double p = aii != 0.0 ? std::max(fluid_.p[i] + t.omega / aii * (si - ap), 0.0) : 0.0;
  fluid_.p[i] = p;
  scratch_.p_over_rho2[i] = p / (fluid_.rho[i] * fluid_.rho[i]);
  scratch_.err[i] = std::max(t.err_scale * (ap - si), 0.0);
}

// The fused Jacobi sweep pays only when the solver's arrays crowd the last-level cache;
// well inside it, the two plain passes are as fast or faster. Pressure phase of the
// 0.5 m layer (`sluice bench` on the widened column, 20 steps), fused against plain,
// median of the per-round ratios of 7 to 9 interleaved rounds, with the sweep in ranges:
// 2 threads: 10k (about 3 MB) 1.07, 30k (9 MB) 0.97, 60k (19 MB) 0.98, 100k (31 MB) 0.89
// and 0.85; 1 thread: 30k 1.05, 100k 0.80. (The 1M layer and the 130k dam break, 41 MB,
// gain more: docs/performance.md.) Returns the block size, 0 for the two plain passes.
Index Simulation::jacobi_block_size() const {
  if (jacobi_block_ != 0) return std::max<Index>(jacobi_block_, 0);
  // Bytes the iteration streams: 12 per fluid pair (index and float gradient) and about
  // 160 per particle (pressures, accelerations, source, diagonal, boundary sums).
  const double bytes = 12.0 * static_cast<double>(ff_.pairs()) + 160.0 * fluid_.size();
  return bytes < kFuseAboveBytes ? 0 : kSweepBlock;
}

// Ranges of the fused sweep: one contiguous index range per thread, cut so that each
// holds about the same work (fluid pairs, plus 4 per particle for the per-particle part).
void Simulation::plan_jacobi_ranges() {
  const Index n = fluid_.size();
  const Index ranges = jacobi_ranges_ > 0 ? jacobi_ranges_ : static_cast<Index>(omp_get_max_threads());
  auto work = [&](Index i) { return static_cast<double>(ff_.offset[i]) + 4.0 * i; };
  const double total = work(n);
  std::vector<Index>& range = scratch_.sweep_range;
  range.assign(static_cast<size_t>(ranges) + 1, n);
  range[0] = 0;
  for (Index r = 1; r < ranges; ++r) {
    const double target = total * r / ranges;
    Index lo = range[r - 1], hi = n;  // first i in [lo, n] with work(i) >= target
    while (lo < hi) {
      const Index mid = lo + (hi - lo) / 2;
      if (work(mid) < target)
        lo = mid + 1;
      else
        hi = mid;
    }
    range[r] = lo;
  }
}

// How many blocks after its own particle i's update must wait for in the fused sweep:
// the block of its last fluid neighbour jmax (earlier blocks of the same range are
// done by then). -1 (deferred) when a neighbour lies in another range, whose thread may
// not have computed its acceleration yet, or more than kMaxSweepLag blocks ahead, by
// when i's data have left the cache. jmin, jmax: i's smallest and largest neighbour
// index (i itself when it has none).
std::int8_t Simulation::sweep_lag_of(Index i, Index jmin, Index jmax, Index block) const {
  const std::vector<Index>& range = scratch_.sweep_range;
  const Index r = static_cast<Index>(std::upper_bound(range.begin(), range.end(), i) - range.begin()) - 1;
  const Index begin = range[r], end = range[r + 1];
  if (jmin < begin || jmax >= end) return -1;
  const Index lag = (jmax - begin) / block - (i - begin) / block;
  return lag <= kMaxSweepLag ? static_cast<std::int8_t>(std::max<Index>(lag, 0)) : std::int8_t(-1);
}

// One Jacobi iteration over all fluid particles: the accelerations of Eq. 24 from the
// current pressures, then the updates of Eq. 20, 21 and 23; returns the sum of Eq. 23.
//
// With block = 0, two plain passes. Otherwise fused: each thread sweeps its own range
// (sweep_range) block by block, computing a block's accelerations and at once updating
// the particles whose last fluid neighbour lies in that block, while their pairs and
// accelerations are still in cache; after all ranges are done, the deferred particles
// (see sweep_lag_of) are updated. The result is the same as two full passes, bit for
// bit: an update reads only accelerations, and every one it reads is computed before
// it, whatever the thread count. And no acceleration reads a pressure updated in the
// same iteration: a particle updated early has all its neighbours in its own range and
// in blocks already done (neighbour lists are symmetric).
double Simulation::jacobi_sweep(Index block, const PressureTerms& t) {
  const Index n = fluid_.size();
  if (block == 0) {
    // Two plain passes: all accelerations, then all updates (summed as they go).
    compute_pressure_acceleration();
    return parallel_sum(n, [&](Index i) {
      jacobi_update_of(i, t);
      return scratch_.err[i];
    });
  }
  const std::vector<Index>& range = scratch_.sweep_range;
  const Index ranges = static_cast<Index>(range.size()) - 1;
  const Index nd = static_cast<Index>(scratch_.deferred.size());
  // Sum of Eq. 23 over fixed blocks of kReduceBlock particles, added in block order as
  // in parallel_sum: the same bits whatever the sweep's blocks, ranges and threads.
  const Index sum_blocks = (n + kReduceBlock - 1) / kReduceBlock;
  std::vector<double>& partial = scratch_.err_partial;
  partial.assign(static_cast<size_t>(sum_blocks), 0.0);
  // A thread may sweep several ranges one after the other (fewer threads than ranges):
  // a range's early updates touch no particle of another range, so that is safe too.
#pragma omp parallel if (n >= kParallelMin)
  {
#pragma omp for schedule(dynamic, 1)
    for (Index r = 0; r < ranges; ++r) sweep_range(range[r], range[r + 1], block, t);
#pragma omp for schedule(dynamic, kForChunk)
    for (Index k = 0; k < nd; ++k) jacobi_update_of(scratch_.deferred[k], t);
#pragma omp for schedule(dynamic, 1)
    for (Index b = 0; b < sum_blocks; ++b) {
      const Index end = std::min(n, (b + 1) * kReduceBlock);
      double sum = 0.0;
      for (Index i = b * kReduceBlock; i < end; ++i) sum += scratch_.err[i];
      partial[static_cast<size_t>(b)] = sum;
    }
  }
  double total = 0.0;
  for (double sum : partial) total += sum;
  return total;
}

// One range of the fused sweep, blocks in order: block c's accelerations, then the
// updates of the particles of blocks c - kMaxSweepLag .. c that waited for block c.
void Simulation::sweep_range(Index begin, Index end, Index block, const PressureTerms& t) {
  const std::vector<std::int8_t>& lag = scratch_.sweep_lag;
  // (Bounds computed so that no sum exceeds end: a block may be as large as Index allows.)
  for (Index c = begin, c_end = begin; c < end; c = c_end) {
    c_end = end - c > block ? c + block : end;
    for (Index i = c; i < c_end; ++i) scratch_.a_p[i] = pressure_acceleration_of(i, t);
    for (int d = kMaxSweepLag; d >= 0; --d) {
      if (static_cast<std::int64_t>(d) * block > c - begin) continue;  // d blocks back is before the range
      const Index b0 = c - d * block, b1 = d == 0 ? c_end : b0 + block;
      for (Index i = b0; i < b1; ++i)
        if (lag[i] == d) jacobi_update_of(i, t);
    }
  }
}

// ---------------------------------------------------------------------------------
// IISPH pressure solver (chapter 3, Algorithm 2, relaxed Jacobi).
//
// With the pressure accelerations of Eq. 24, the PPE of Eq. 17 for fluid particle i is
//   (Ap)_i = dt [ sum_f m_f (a_i - a_f) . grad W_if + gamma2 sum_b m_b (a_i - a_b) . grad W_ib ]
//          = s_i = (rho0 - rho*_i) / dt                                      (Eq. 19, 20)
// where rho*_i = rho_i + dt [ sum_f m_f v*_if . grad W_if + gamma2 sum_b m_b v*_ib . grad W_ib ]
// (Eq. 16; the boundary particle enters with its own velocity, a_b = 0 for a wall).
// The predicted density after the pressure update is rho*_i + dt (Ap)_i, so the
// relative compression of Eq. 23 is 100 dt ((Ap)_i - s_i) / rho0 (the thesis writes
// Eq. 23 without the factor dt because its A and s carry 1/dt).
//
// Diagonal (Eq. 22/26), derived for the chosen boundary method: writing
//   a_i = p_i D_i + (terms without p_i),
//   D_i = -(1/rho_i^2) (sum_f m_f grad W_if + c gamma3 grad_b_i) - E_i,
// with c = 2 for mirroring (p_b/rho_b^2 = p_i/rho_i^2) and 1 otherwise, and for
// extrapolation E_i = (gamma3 / rho0^2) sum_b m_b (W_bi / sum_f W_bf) grad W_ib, the
// share of p_i in each p_b of Eq. 25. Each fluid neighbour f holds p_i through
// a_f = ... - m_i (p_i/rho_i^2) grad W_fi, so
//   a_ii = dt [ D_i . (sum_f m_f grad W_if + gamma2 grad_b_i) - (m_i^2/rho_i^2) sum_f |grad W_if|^2 ].
// Eq. 26 as printed is c = 1 and E = 0 (boundary_diagonal = false). With pressure
// boundaries p_b is an unknown of its own (prepare_solved_boundary): c = 1, E = 0, and the
// iteration stops when the samples' average predicted compression is within the
// tolerance too (st.avg_error_percent is the larger of the two averages).
void Simulation::solve_pressure_iisph(double dt, StepStats& st) {
  const Index n = fluid_.size();
  const SolverSettings& s = settings_;
  const double rho0 = s.rest_density, g2 = s.gamma2, g3 = s.gamma3, omega = s.omega;
  prepare_boundary_terms();
  scratch_.s.resize(n);
  scratch_.a_ii.resize(n);
  scratch_.p_over_rho2.resize(n);
  const bool mirror = s.boundary_pressure == BoundaryPressure::Mirroring;
  const bool extrapolate = s.boundary_pressure == BoundaryPressure::Extrapolation;
  const bool solved_boundary = s.boundary_pressure == BoundaryPressure::Solved;
  // Boundary samples with a fluid neighbour (their rows of the PPE).
  const Index active_samples = solved_boundary ? prepare_solved_boundary(dt) : 0;
  const double c = (mirror && s.boundary_diagonal) ? 2.0 : 1.0;
  const bool coupling = extrapolate && s.boundary_diagonal;
  const bool thesis_init = s.pressure_init == PressureInit::Thesis;
  const double vb_scale = boundary_velocity_in_source_ ? 1.0 : 0.0;

  const Index block = jacobi_block_size();
  if (block > 0) {
    plan_jacobi_ranges();
    scratch_.sweep_lag.resize(n);
  }

  // Source term s_i (Eq. 19), diagonal a_ii (Eq. 26), initial pressure p^(0) (Eq. 21),
  // and when the fused Jacobi sweep can update i (sweep_lag_of).
  parallel_for(n, [&](Index i) {
    const Vec2 vi = fluid_.v[i];
    const double rhoi = fluid_.rho[i];
    Index jmin = i, jmax = i;
    double div = 0.0, grad2 = 0.0;
    Vec2 sum_grad = Vec2::Zero();
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      const Index j = ff_.j[k];
      const Vec2 gw = ff_.grad[k].cast<double>();
      jmin = std::min(jmin, j);
      jmax = std::max(jmax, j);
      div += (vi - fluid_.v[j]).dot(gw);
      sum_grad += gw;
      grad2 += gw.squaredNorm();
    }
    if (block > 0) scratch_.sweep_lag[i] = sweep_lag_of(i, jmin, jmax, block);
    div *= mass_;
    sum_grad *= mass_;
    double div_b = 0.0;
    Vec2 e = Vec2::Zero();
    for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
      const Index b = fb_.j[k];
      const double mb = rho0 * boundary_.volume[b];
      div_b += mb * (vi - vb_scale * boundary_.v[b]).dot(fb_.grad[k].cast<double>());
      if (coupling && scratch_.ext_wsum[b] > 0.0) e += (mb * fb_.w[k] / scratch_.ext_wsum[b]) * fb_.grad[k].cast<double>();
    }
    scratch_.s[i] = (rho0 - rhoi) / dt - (div + g2 * div_b);
    const double inv_rho2 = 1.0 / (rhoi * rhoi);
    const Vec2 d = -inv_rho2 * (sum_grad + (c * g3) * scratch_.grad_b[i]) - (g3 / (rho0 * rho0)) * e;
    const double aii = dt * (d.dot(sum_grad + g2 * scratch_.grad_b[i]) - mass_ * mass_ * inv_rho2 * grad2);
    scratch_.a_ii[i] = aii;
    double p0 = kWarmStartFactor * fluid_.p[i];
    if (thesis_init) p0 = aii != 0.0 ? std::max(omega * scratch_.s[i] / aii, 0.0) : 0.0;
    fluid_.p[i] = p0;
    scratch_.p_over_rho2[i] = p0 * inv_rho2;
  });

  scratch_.deferred.clear();
  if (block > 0)  // the plain passes defer nothing
    for (Index i = 0; i < n; ++i)
      if (scratch_.sweep_lag[i] < 0) scratch_.deferred.push_back(i);
  scratch_.err.resize(n);
  scratch_.a_p.resize(n);
  int l = 0;
  double avg = 0.0;
  const PressureTerms terms = pressure_terms(dt);
  do {
    update_boundary_pressure();
    const double sum = jacobi_sweep(block, terms);
    avg = n ? sum / n : 0.0;
    // Pressure boundaries: the samples' constraints converge too (their own average), or
    // their pressures lag the fluid's and stop being constraint forces.
    if (solved_boundary && active_samples > 0) avg = std::max(avg, jacobi_update_boundary(terms) / active_samples);
    ++l;
  } while ((avg > s.tolerance_percent || l < s.min_iterations) && l < s.max_iterations);
  // Integrate the accelerations of the final pressures ([Ihm+14a], Algorithm 1); the
  // loop's a_p belong to the iterate before the last update.
  update_boundary_pressure();
  compute_pressure_acceleration();
  if (has_moving_boundaries()) add_boundary_pressure_work(dt);
  st.iterations = l;
  st.avg_error_percent = avg;
  st.max_error_percent = parallel_max(n, 0.0, [&](Index i) { return scratch_.err[i]; });
}

// WCSPH (section 2.3.1): p_i = max(k (rho_i / rho0 - 1), 0), then Eq. 24.
void Simulation::solve_pressure_wcsph(double dt, StepStats& st) {
  const Index n = fluid_.size();
  const double rho0 = settings_.rest_density, k = settings_.stiffness;
  prepare_boundary_terms();
  scratch_.p_over_rho2.resize(n);
  parallel_for(n, [&](Index i) {
    const double rho = fluid_.rho[i];
    const double p = std::max(k * (rho / rho0 - 1.0), 0.0);
    fluid_.p[i] = p;
    scratch_.p_over_rho2[i] = p / (rho * rho);
  });
  update_boundary_pressure();
  compute_pressure_acceleration();
  if (has_moving_boundaries()) add_boundary_pressure_work(dt);
  st.iterations = 0;
  st.avg_error_percent = st.density_error_percent;
  st.max_error_percent =
      parallel_max(n, 0.0, [&](Index i) { return compression_percent(fluid_.rho[i], rho0); });
}

// Semi-implicit Euler (Algorithm 1/2): v(t+dt) = v* + dt a_p, x(t+dt) = x + dt v(t+dt).
void Simulation::integrate(double dt) {
  parallel_for(fluid_.size(), [&](Index i) {
    fluid_.v[i] += dt * scratch_.a_p[i];
    fluid_.x[i] += dt * fluid_.v[i];
  });
}

void Simulation::check_stability(const StepStats& st) const {
  auto fail = [&](const std::string& cause) {
    std::ostringstream os;
    if (st.step <= 0)  // settle() numbers its steps 0, -1, -2, ...
      os << "unstable while settling (time.settle = " << setup_.time.settle << " s) at its step " << 1 - st.step
         << ", " << st.time << " s into it: " << cause;
    else
      os << "unstable at step " << st.step << ", t = " << st.time << " s: " << cause;
    throw SimulationUnstable(os.str());
  };
  for (Index i = 0; i < fluid_.size(); ++i) {
    const Vec2& x = fluid_.x[i];
    const Vec2& v = fluid_.v[i];
    if (!x.allFinite() || !v.allFinite() || !std::isfinite(fluid_.p[i])) {
      std::ostringstream os;
      os << "fluid particle " << fluid_.id[i] << " has a non-finite position, velocity or pressure";
      fail(os.str());
    }
    if ((x.array() < lost_min_.array()).any() || (x.array() > lost_max_.array()).any()) {
      std::ostringstream os;
      os << "fluid particle " << fluid_.id[i] << " at (" << x.x() << ", " << x.y()
         << ") left the scene's bounds by more than stability.bounds_margin = " << setup_.limits.bounds_margin
         << " scene sizes";
      fail(os.str());
    }
  }
  // Walls that no longer hold the fluid (checked at frame times: a pass over every
  // particle and object).
  if (st.frame >= 0) {
    const FluidInSolids leak = find_fluid_in_solids(setup_, fluid_.x, time_);
    if (leak.count > 0 && 100.0 * leak.count > setup_.limits.max_leaked_percent * fluid_.size()) {
      std::ostringstream os;
      os << leak.count << " of " << fluid_.size() << " fluid particles are past a wall's first sample layer (more than "
         << "stability.max_leaked_percent = " << setup_.limits.max_leaked_percent << "%); the first, particle "
         << fluid_.id[leak.first] << ", is inside boundary \"" << leak.object << "\" at (" << leak.at.x() << ", "
         << leak.at.y() << "), behind its surface at (" << leak.surface.x() << ", " << leak.surface.y() << ")";
      fail(os.str());
    }
  }
  if (st.density_error_percent > setup_.limits.max_error_percent) {
    std::ostringstream os;
    os << "average compression error " << st.density_error_percent
       << "% exceeds stability.max_error_percent = " << setup_.limits.max_error_percent << "%";
    fail(os.str());
  }
}

}  // namespace sluice
