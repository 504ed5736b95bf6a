#include "solver/simulation.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure/pressure_solver.h"  // ~Simulation deletes pressure_method_

// Construction: the fluid and boundary arrays from a SimulationSetup, the boundary
// volumes of 4.1, the particle mass and the sound speed; then the optional settling.
namespace sluice {

using namespace solver_detail;

namespace {

// IISPH has no sound speed; its artificial viscosity takes Monaghan's (1994) choice for a
// weakly compressible fluid, c = 10 v_max, with v_max = sqrt(2 g H) of the fluid's
// initial height H (or its fastest initial particle, if faster).
double incompressible_sound_speed(const SimulationSetup& setup) {
  const double v0 = fastest_initial_speed(setup), H = fluid_height(setup);
  return 10.0 * std::max(v0, std::sqrt(2.0 * setup.solver.gravity.norm() * H));
}

}  // namespace

// sum_j W(x_ij) over a square lattice of the given spacing (self included): 1.000862 /
// spacing^2 for the cubic spline on 2 spacings. The fluid mass is rho0 / this sum, so that
// a filled lattice is at rest density exactly; with m = rho0 h^2 every particle of the
// initial block would be 0.086% compressed and IISPH would push the whole block apart in
// its first step.
double lattice_kernel_sum(const Kernel2D& kernel, double spacing, int top_row) {
  const int reach = static_cast<int>(std::ceil(kernel.support() / spacing));
  double sum = 0.0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= std::min(reach, top_row); ++j)
      sum += kernel.W(spacing * std::sqrt(double(i * i + j * j)));
  return sum;
}

// The largest eigenvalue of D^-1 A (Eq. 20 over the diagonal of Eq. 26) for the pressure
// modes exp(i k.x) of a filled square lattice. There d_ii = 0 and, with S(k) =
// sum_r sin(k.r) grad W(r), the operator's symbol over its diagonal is |S(k)|^2 /
// sum_r |grad W(r)|^2: 2.149 for the cubic spline on 2 spacings, 3.773 on 3, 6.703 on 4.
// Relaxed Jacobi diverges once omega times this exceeds 2. Scanned over a 64 x 64 grid
// of k in [0, pi]^2 (the symbol is even in each component).
double lattice_jacobi_bound(const Kernel2D& kernel, double spacing) {
  const int reach = static_cast<int>(std::ceil(kernel.support() / spacing));
  std::vector<std::pair<Vec2, Vec2>> pairs;  // lattice offset r (in spacings) and grad W(r)
  double diagonal = 0.0;
  for (int i = -reach; i <= reach; ++i)
    for (int j = -reach; j <= reach; ++j) {
      const Vec2 r(i, j);
      const Vec2 g = kernel.gradW(spacing * r);
      if ((i == 0 && j == 0) || g.squaredNorm() == 0.0) continue;
      pairs.emplace_back(r, g);
      diagonal += g.squaredNorm();
    }
  constexpr int kSteps = 64;
  double bound = 0.0;
  for (int a = 0; a <= kSteps; ++a)
    for (int b = 0; b <= kSteps; ++b) {
      const Vec2 k(M_PI * a / kSteps, M_PI * b / kSteps);
      Vec2 s = Vec2::Zero();
      for (const auto& [r, g] : pairs) s += std::sin(k.dot(r)) * g;
      bound = std::max(bound, s.squaredNorm() / diagonal);
    }
  return bound;
}

// The share of a lattice sample's kernel sum that lies in its own row and below: the wall's
// share of the density of a wall sample whose wall continues the fluid's lattice, with the
// fluid above it.
double lattice_wall_share(const Kernel2D& kernel, double spacing) {
  return lattice_kernel_sum(kernel, spacing, 0) / lattice_kernel_sum(kernel, spacing);
}

// Section 4.1's rest state, sample by sample. A sample's density is its fluid neighbours'
// sum plus the wall's share of its support, wall_share_ rho0: the lattice's share of the
// sample's own row and those below, for a wall with fluid on one side. A one-layer plate
// has fluid on both sides; with that share its samples start 13 % over rho0 and, through
// V_b = gamma1 / sum_b' W_bb' (1.23 lattice cells for a single row), the fluid next to it
// 3.7 % compressed, and the tank sloshes from the first step (docs/validation.md, "Still
// water without time.settle"). So each sample's share is what of its support the initial
// fluid leaves, 1 - m sum_f W_bf / rho0, between its own row's share (a plate in still
// water) and wall_share_ (one side, none, or part of a surface row: unchanged), and its
// gamma1 scales with the same share on the volume kernel (a single row then has the
// lattice cell's volume). The thesis and Akinci et al. 2012 calibrate gamma1 on walls
// with fluid on one side only; this extends it to thin objects.
void Simulation::compute_sample_wall_shares() {
  const Index nb = boundary_.size();
  const double h = setup_.spacing, gamma = settings_.gamma1 * volume_scale_, r = kernel_.support();
  // The lowest share, a row alone: the fluid's kernel for the density, the volume kernel
  // (gamma1's own) for the volume.
  const auto own_row = [h](const Kernel2D& k) {
    return (lattice_kernel_sum(k, h, 0) - lattice_kernel_sum(k, h, -1)) / lattice_kernel_sum(k, h, 0);
  };
  const double lowest = wall_share_ * own_row(kernel_), lowest_v = settings_.gamma1 * own_row(volume_kernel_);
  const double lattice = lattice_kernel_sum(kernel_, h), lattice_v = lattice_kernel_sum(volume_kernel_, h);
  sample_wall_share_.assign(static_cast<size_t>(nb), wall_share_);
  sample_gamma_.assign(static_cast<size_t>(nb), gamma);
  if (fluid_.size() == 0 || nb == 0) return;
  SpatialHashGrid grid;
  grid.build(fluid_.x, r);
#pragma omp parallel if (nb >= kParallelMin / 8)
  {
    std::vector<Index> near;  // one per thread, as compute_volumes
#pragma omp for schedule(dynamic, kForChunk)
    for (Index b = 0; b < nb; ++b) {
      const size_t count = grid.gather_within(boundary_.x[b], r, -1, near, 0);
      std::sort(near.begin(), near.begin() + static_cast<std::ptrdiff_t>(count));  // index order: any thread count
      double w = 0.0, wv = 0.0;
      for (size_t k = 0; k < count; ++k) {
        const double d = (boundary_.x[b] - fluid_.x[near[k]]).norm();
        w += kernel_.W(d);
        wv += volume_kernel_.W(d);
      }
      const double left = 1.0 - w / lattice, left_v = 1.0 - wv / lattice_v;
      if (left < wall_share_) sample_wall_share_[b] = std::max(left, lowest);
      if (left_v < settings_.gamma1) sample_gamma_[b] = gamma * (std::max(left_v, lowest_v) / settings_.gamma1);
    }
  }
}

Simulation::~Simulation() = default;
Simulation::Simulation(Simulation&&) noexcept = default;
Simulation& Simulation::operator=(Simulation&&) noexcept = default;

Simulation::Simulation(const SimulationSetup& setup)
    : setup_(setup),
      settings_(setup.solver),
      kernel_(0.5 * setup.solver.support * setup.spacing, setup.solver.kernel),
      volume_kernel_(0.5 * std::min(setup.solver.support, 2.0) * setup.spacing, KernelKind::CubicSpline),
      mass_(setup.solver.rest_density / lattice_kernel_sum(kernel_, setup.spacing)),
      wall_share_(setup.solver.gamma1),
      volume_scale_(1.0),
      omega_(setup.solver.omega),
      scratch_(std::make_unique<SolverScratch>()) {
  SLUICE_ASSERT(setup.spacing > 0, "the setup's spacing is positive (the scene checks it)");
  // gamma1 and omega are calibrated on the thesis' kernel; another kernel or support scales
  // them by the lattice (see simulation.h). On the thesis' own they stay as they are.
  if (kernel_.kind() != KernelKind::CubicSpline || setup.solver.support != 2.0) {
    const double h = setup.spacing;
    wall_share_ *= lattice_wall_share(kernel_, h) / lattice_wall_share(volume_kernel_, h);
    volume_scale_ = lattice_kernel_sum(volume_kernel_, h) / lattice_kernel_sum(kernel_, h);
    omega_ *= lattice_jacobi_bound(Kernel2D(h), h) / lattice_jacobi_bound(kernel_, h);
  }
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
  boundary_.wall_nu.assign(nb, 0.0);
  for (Index k = 0; k < nb; ++k) {
    const Index o = boundary_.object[k];
    if (o < static_cast<Index>(setup.objects.size()) && setup.objects[o].no_slip)
      boundary_.wall_nu[k] = setup.objects[o].wall_viscosity;
    has_no_slip_ = has_no_slip_ || boundary_.wall_nu[k] > 0.0;
  }
  boundary_.x0 = boundary_.x;
  boundary_.v.assign(nb, Vec2::Zero());
  boundary_.a.assign(nb, Vec2::Zero());
  boundary_.p.assign(nb, 0.0);
  boundary_.volume.assign(nb, 0.0);
  near_moving_.assign(nb, 0);
  if (has_moving_boundaries()) move_boundaries(0.0);  // the pose at t = 0 (a script may start displaced), grid
  compute_sample_wall_shares();
  if (has_moving_boundaries()) {
    volume_update_.resize(static_cast<size_t>(nb));
    for (Index b = 0; b < nb; ++b) volume_update_[b] = b;
    compute_volumes(boundary_grid_, volume_update_, boundary_.volume);
  } else {
    // Walls at rest: a grid with many cells per point (built once) and volumes once.
    boundary_grid_.build(boundary_.x, kernel_.support(), /*cells_per_point=*/1024.0);
    boundary_grid_.mark_reachable_cells();  // most fluid particles have no wall in reach
    std::vector<Index> all(static_cast<size_t>(nb));
    for (Index b = 0; b < nb; ++b) all[b] = b;
    compute_volumes(boundary_grid_, all, boundary_.volume);
  }

  const Vec2 size = (setup.bounds_max - setup.bounds_min).cwiseMax(Vec2::Constant(setup.spacing));
  const double margin = setup.limits.bounds_margin * size.maxCoeff();
  lost_min_ = setup.bounds_min - Vec2::Constant(margin);
  lost_max_ = setup.bounds_max + Vec2::Constant(margin);

  last_frame_ = static_cast<Index>(std::ceil(setup.time.duration * setup.time.fps - 1e-9));
  if (!(settings_.stiffness > 0)) settings_.stiffness = wcsph_default_stiffness(setup);
  SLUICE_ASSERT(settings_.type != SolverType::WCSPH || settings_.stiffness > 0,
                "WCSPH has a stiffness (the scene refuses a setup without one)");
  wcsph_speed_ = std::sqrt(settings_.stiffness / settings_.rest_density);
  sound_speed_ = settings_.sound_speed;
  if (sound_speed_ <= 0)
    sound_speed_ = settings_.type == SolverType::WCSPH ? wcsph_speed_ : incompressible_sound_speed(setup);
  {
    StepStats st;
    measure_energy(st);
    const Vec2 g = settings_.gravity;
    double lowest = std::numeric_limits<double>::infinity();  // min over the bounds' corners of -g . c
    for (const Vec2& c : {setup.bounds_min, setup.bounds_max, Vec2(setup.bounds_min.x(), setup.bounds_max.y()),
                          Vec2(setup.bounds_max.x(), setup.bounds_min.y())})
      lowest = std::min(lowest, -g.dot(c));
    initial_energy_ = st.mechanical_energy;
    for (const Vec2& v : fluid_.v) initial_max_speed_ = std::max(initial_max_speed_, v.norm());
    initial_available_energy_ = st.kinetic_energy + std::max(st.potential_energy - mass_ * fluid_.size() * lowest, 0.0);
    if (has_moving_boundaries()) {
      const double samples = std::clamp(std::ceil(4.0 * setup.time.duration * setup.time.fps), 256.0, 20000.0);
      for (double k = 0; k <= samples; ++k)
        peak_boundary_speed_ = std::max(peak_boundary_speed_, boundary_speed_at(setup.time.duration * k / samples));
    }
  }
  reorder_fluid();
  recompute_density();
  if (setup.time.relax_start) relax_stats_ = relax_start();
  if (!setup.time.auto_settle) {
    if (setup.time.settle > 0) settle(setup.time.settle);
  } else if (starts_at_rest()) {
    settle(kAutoSettleSeconds);
  }
}

}  // namespace sluice
