#pragma once
// One 2D SPH simulation: fluid and boundary particles, neighbour search, the IISPH
// (chapter 3, Algorithm 2) or WCSPH (section 2.3.1) pressure solver, boundary
// handling of chapter 4, and time control landing exactly on frame times. IISPH's PPE
// is set up here (iisph.cpp) and iterated by one of the schemes in solver/pressure/
// (pressure_solver.h), through a PressureSystem (solver/pressure/system.h).
// No globals: several simulations can coexist in one process.
#include <memory>
#include <stdexcept>
#include <string>

#include "solver/settings.h"
#include "solver/setup.h"
#include "solver/stats.h"
#include "sph/kernel.h"
#include "sph/neighbors.h"
#include "sph/particles.h"

namespace sluice {

// A run that went unstable: NaN/Inf, a particle far outside the scene, or a
// compression error above the limit. what() names the step, time and cause.
class SimulationUnstable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct SolverScratch;        // per-step arrays of the pressure solvers (solver/internal.h)
class PressureSolverMethod;  // an iteration scheme of the PPE (solver/pressure/pressure_solver.h)
struct CoarseLevel;          // the multilevel scheme's coarse level (solver/pressure/multilevel.h)

double lattice_kernel_sum(const Kernel2D& kernel, double spacing, int top_row = 1 << 20);
double lattice_jacobi_bound(const Kernel2D& kernel, double spacing);
double lattice_wall_share(const Kernel2D& kernel, double spacing);

// Everything a simulation carries from one step to the next, in its own order (fluid
// arrays as last sorted in space, boundary samples in their fixed spatial order), so
// that restoring it into a Simulation of the same scene continues bit for bit
// (checkpoints). What every step rebuilds before reading it (grids, neighbour lists,
// solver scratch) is left out, and so is what the scene determines (masses, x0,
// object ids, moving flags). The time step is not carried: Eq. 14 is evaluated from
// the velocities at each step.
struct SimulationState {
  double time = 0;
  long step = 0;
  Index frame = 0;
  // x, v, the density of the last step's start (exports and colours read it), the
  // pressure (the next IISPH solve's warm start) and the initial-order id.
  FluidParticles fluid;
  // Boundary samples: moving ones change position, velocity and acceleration, volumes
  // change near moving ones and are updated incrementally, pressures are the last
  // solve's. Static positions are carried only to be checked against the scene.
  std::vector<Vec2> boundary_x, boundary_v, boundary_a;
  std::vector<double> boundary_volume, boundary_p;
  // Static samples that had a moving one in their support at the last volume update:
  // they are recomputed once more when it leaves (update_boundary_volumes).
  std::vector<std::uint8_t> near_moving;
};

class Simulation {
 public:
  explicit Simulation(const SimulationSetup& setup);
  ~Simulation();
  Simulation(Simulation&&) noexcept;
  Simulation& operator=(Simulation&&) noexcept;

  // Advances by one time step (Algorithm 2 for IISPH) and returns its statistics.
  // Throws SimulationUnstable when the state is no longer valid.
  StepStats step();

  bool finished() const { return time_ >= setup_.time.duration; }
  double time() const { return time_; }
  long steps() const { return step_; }
  Index frame() const { return frame_; }             // last frame index reached (0 at t = 0)
  Index frame_count() const { return last_frame_; }  // index of the final frame

  // The state between two steps, and its restoration: a Simulation built from the same
  // scene that restores state() continues exactly as this one would. restore() throws
  // std::invalid_argument naming what does not fit this simulation (particle counts,
  // ids, static boundary positions, time or frame out of range) and then changes nothing.
  SimulationState state() const;
  void restore(const SimulationState& s);

  const SimulationSetup& setup() const { return setup_; }
  const FluidParticles& fluid() const { return fluid_; }
  const BoundaryParticles& boundary() const { return boundary_; }
  const Kernel2D& kernel() const { return kernel_; }
  double fluid_mass() const { return mass_; }
  // Kinetic plus potential energy of the fluid now [J/m] (StepStats::mechanical_energy).
  double mechanical_energy() const;
  // Speed c of the artificial viscosity (SolverSettings::sound_speed, resolved) [m/s].
  double sound_speed() const { return sound_speed_; }
  // What the start's relaxation did (TimeSettings::relax_start; zero rounds: not needed or off).
  const RelaxStats& relax_stats() const { return relax_stats_; }
  // Seconds settled before t = 0 (time.settle, or kAutoSettleSeconds where "auto" found
  // the fluid at rest), 0 if none.
  double settled_seconds() const { return settle_seconds_; }

  // Benchmark switch: the O(n m) neighbour search instead of the grid.
  void set_brute_force_neighbors(bool on) { brute_force_ = on; }
  bool has_moving_boundaries() const { return !moving_.empty(); }
  SolverSettings& solver_settings() { return settings_; }

  // Density (Eq. 13 with the boundary term of section 4.1) of every fluid particle,
  // computed from the current positions (for tests and exports).
  void recompute_density();

 private:
  friend class SolverProbe;     // tests' window into the pressure system (solver/probe.h)
  friend class PressureSystem;  // a pressure solver's handle on one step's PPE (solver/pressure/system.h)

  // Phases of a step, in the order of Algorithm 2.
  double choose_time_step() const;
  double hydrostatic_speed() const;                       // sqrt(|g| H), for choose_time_step
  void advance(double dt, StepStats& st, bool settling);  // one step of Algorithm 2 without time bookkeeping
  void reset_boundary_work();                             // the moving walls' per-particle work, zeroed
  void run_phase(Phase phase, double dt, StepStats& st);  // one phase of it
  void settle(double duration);                           // TimeSettings::settle, before t = 0
  bool starts_at_rest() const;                            // still, its free surface facing up
  RelaxStats relax_start();                               // TimeSettings::relax_start, before settle()
  void measure_energy(StepStats& st) const;
  void find_neighbors_phase();
  void compute_density();             // grad W per pair, then Eq. 13 + section 4.1
  void apply_nonpressure(double dt);  // Eq. 12 + gravity: v* = v + dt (a_v + g)
  template <bool kViscous>
  void viscous_accelerations(double dt, double avc, std::vector<Vec2>& a_v);  // its pair sums
  void solve_pressure_iisph(double dt, StepStats& st);  // prepare_pressure_system, then iterate_pressure
  Index prepare_pressure_system(double dt);             // Eq. 19, 22/26, p^(0); returns the samples with a row
  double extrapolation_coupling(Index i) const;         // a_ii's share of p_i through the neighbours' p_b (Eq. 25)
  // Algorithm 2's solver loop: the chosen scheme's iterate (solver/pressure/), then a_p of the
  // final pressures.
  void iterate_pressure(double dt, Index active_samples, StepStats& st);
  PressureSolverMethod& pressure_method();  // settings_.pressure_solver's scheme (iterate, warm start)
  void solve_pressure_wcsph(double dt, StepStats& st);
  void integrate(double dt);  // semi-implicit Euler (Algorithm 1, last loop)
  void check_stability(const StepStats& st) const;
  double energy_gain_bound() const;  // largest rise of the mechanical energy [J/m] (check_stability)
  double speed_bound() const;        // largest plausible particle speed [m/s] (check_stability)
  void reorder_fluid();
  std::vector<double> boundary_volumes_from_scratch() const;  // section 4.1 for every sample (SolverProbe)

  // Building blocks of the pressure solvers.
  void correct_gradients();                    // pair gradients times (c_i + c_j) / 2
  void prepare_boundary_terms();               // grad_b, Eq. 25 weights
  void update_boundary_pressure();             // Eq. 25 / 4.2.2 / 4.2.3 / WCSPH's solved p_b -> pb_over_rho2
  Index prepare_solved_boundary(double dt);    // bnd_s, bnd_aii, p_b^(0); returns the samples with fluid neighbours
  void add_boundary_pressure_work(double dt);  // scratch work += the pressure force's share
  void compute_pressure_acceleration();        // Eq. 24 -> a_p
  // Constants of Eq. 20, 21, 23, 24 within a step, read once per sweep.
  struct PressureTerms {
    double mass, c_gamma3, gamma3_rho0, gamma2, omega, dt, err_scale;
    // Chebyshev's weight of this iteration (chebyshev_weight); 0: plain relaxed Jacobi.
    double chebyshev = 0.0;
    double stabilisation = 0.0;  // kappa of stabilisation_of; 0: none
    bool boundary_field;         // p_b from its own array (extrapolated or solved), not p_i or 0
  };
  PressureTerms pressure_terms(double dt) const;
  void compute_pressure_acceleration(const PressureTerms& t);            // Eq. 24 -> a_p (and stab_mean)
  double sample_operator_of(Index b, const PressureTerms& t) const;      // (Ap)_b of a pressure-boundary sample
  double jacobi_update_boundary(const PressureTerms& t);                 // Eq. 21 for every boundary sample's p_b
  Vec2 pressure_acceleration_of(Index i, const PressureTerms& t) const;  // Eq. 24 for one particle
  double pressure_operator_of(Index i, const PressureTerms& t) const;    // Eq. 20: (Ap)_i from a_p
  void jacobi_update_of(Index i, const PressureTerms& t);                // Eq. 20, 21, 23 for one particle
  template <bool kSumQ>  // Eq. 24 for one particle; kSumQ: and its neighbours' p / rho^2 summed
  Vec2 eq24_of(Index i, const PressureTerms& t, double& q_sum) const;
  double stabilisation_mean_of(Index i, const Vec2& a_i, double q_sum, const PressureTerms& t) const;  // q_bar_i
  bool stabilised_row(Index i, const PressureTerms& t) const;             // kappa > 0 and i in the wall band
  double stabilisation_of(Index i, const PressureTerms& t) const;         // the fluid row's added term
  double sample_stabilisation_of(Index b, const PressureTerms& t) const;  // the sample row's added term
  void prepare_stabilisation();                                           // stab_offset
  Index plan_jacobi_sweep();  // block size (0: plain passes), ranges, lags, deferred particles
  Index jacobi_block_size() const;
  void plan_jacobi_ranges();  // the sweep's ranges
  std::int8_t sweep_lag_of(Index i, Index jmin, Index jmax, Index block) const;
  double jacobi_sweep(Index block,
                      const PressureTerms& t);  // Eq. 24, then 20, 21, 23 for all; returns the sum of Eq. 23
  void sweep_range(Index begin, Index end, Index block, const PressureTerms& t);
  void grow_by_neighbours(const std::vector<std::uint8_t>& from, std::vector<std::uint8_t>& to) const;
  void mark_wall_band(std::vector<std::uint8_t>& band, std::vector<std::uint8_t>& wall) const;
  const std::vector<std::uint8_t>& wall_band_flags();  // this step's band, marked once
  void plan_wall_band();                               // scratch wall_band, wall_reach
  void smooth_wall_band(const PressureTerms& t);       // one Jacobi iteration on the band and the samples
  // The multilevel scheme's coarse level (solver/pressure/coarse_level.cpp).
  void aggregate_unknowns(CoarseLevel& cl) const;                                // the unknowns with p > 0 by cells
  void assemble_coarse_operator(const PressureTerms& t, CoarseLevel& cl) const;  // A_c = P^T A P
  void build_coarse_level(const PressureTerms& t);                               // aggregates, A_c, its factors
  bool coarse_correction(const PressureTerms& t, double scale = 1.0);            // x += scale P A_c^-1 P^T (s - A x)

  // Boundaries (chapter 4).
  void move_boundaries(double dt);          // scripted poses at time_ -> x, v, a of moving samples
  void update_boundary_volumes();           // section 4.1 where the neighbourhood can change
  void compute_sample_wall_shares();        // sample_wall_share_ and sample_gamma_, from the fluid at the start
  double sample_density_of(Index b) const;  // sum_f m W_bf + its wall share (last neighbour phase's pairs)
  // Section 4.1 for the samples `which`, over the grid's points.
  void compute_volumes(const SpatialHashGrid& grid, const std::vector<Index>& which, std::vector<double>& volume) const;
  double max_boundary_speed() const;  // fastest moving sample at time_ (for Eq. 14)
  double boundary_speed_at(double t) const;

  SimulationSetup setup_;
  SolverSettings settings_;
  Kernel2D kernel_;
  // The boundary volumes' kernel (section 4.1): the thesis' cubic spline on min(support, 2)
  // spacings, the calibration of gamma1, whatever the support of the fluid's kernel.
  Kernel2D volume_kernel_;
  double mass_;  // fluid particle mass rho0 / lattice_kernel_sum [kg/m]
  // The wall's share of a wall sample's density (boundary_density): gamma1 on the volume
  // kernel, scaled by the lattice's wall share on the fluid's kernel over that on the
  // volume kernel (exactly gamma1 on the thesis' support).
  double wall_share_;
  // The fluid particle's volume m / rho0 on the fluid's kernel over that on the volume
  // kernel: V_b = gamma1 volume_scale_ / sum_b' W_bb' (exactly 1 on the thesis' support).
  double volume_scale_;
  // Each sample's own wall share (boundary_density) at the start: what of its support the
  // fluid cannot fill. wall_share_ for a sample with fluid on one side or none; down to its
  // own row's share for one that starts with fluid on both sides (a one-layer plate). Its
  // volume's gamma1 scales with the same share on the volume kernel (compute_sample_wall_shares).
  std::vector<double> sample_wall_share_;
  std::vector<double> sample_gamma_;  // V_b = sample_gamma_ / sum_b' W_bb' (section 4.1)
  // The relaxation of Eq. 21 on this kernel: solver.omega times the lattice's largest
  // eigenvalue of D^-1 A on the thesis' kernel over that on this one (lattice_jacobi_bound),
  // so that a wider support keeps the thesis' margin to Jacobi's divergence (exactly
  // solver.omega on the thesis' support).
  double omega_;
  bool has_no_slip_ = false;   // a boundary object with wall = no_slip and a viscosity > 0
  double sound_speed_ = 0;     // c of the artificial viscosity [m/s]
  double wcsph_speed_ = 0;     // sqrt(k / rho0), WCSPH's acoustic time step [m/s]
  long settle_steps_ = 0;      // steps taken by settle()
  double settle_seconds_ = 0;  // settle()'s duration (time.settle or the automatic one), 0: none
  RelaxStats relax_stats_;     // relax_start()'s rounds and compressions
  // Steps taken so far, settling included: which step a per-step value belongs to.
  long step_stamp() const { return step_ + settle_steps_; }

  FluidParticles fluid_;
  BoundaryParticles boundary_;

  SpatialHashGrid fluid_grid_, boundary_grid_;
  NeighborLists ff_, fb_, bf_;              // fluid-fluid, fluid-boundary, boundary-fluid (transpose of fb)
  std::unique_ptr<SolverScratch> scratch_;  // never null
  // The IISPH scheme of pressure_method_kind_, made by pressure_method() when first needed
  // or when settings_.pressure_solver has changed.
  std::unique_ptr<PressureSolverMethod> pressure_method_;
  PressureSolver pressure_method_kind_ = PressureSolver::Jacobi;
  bool brute_force_ = false;
  bool boundary_velocity_in_source_ = true;
  Index jacobi_block_ = 0;   // 0: jacobi_block_size() chooses
  Index jacobi_ranges_ = 0;  // 0: one per thread

  // Moving boundaries: the samples on moving objects, and the static samples whose
  // kernel support held a moving sample at the last update (their volumes must be
  // recomputed once more when it leaves).
  std::vector<Index> moving_;
  std::vector<std::uint8_t> near_moving_;
  std::vector<Index> volume_update_;  // scratch: samples whose volume is recomputed this step

  double time_ = 0;
  long step_ = 0;
  Index frame_ = 0;
  Index last_frame_ = 0;
  Vec2 lost_min_, lost_max_;  // a particle outside this box is lost (instability)
  // Before settling (a resume computes the same): the mechanical energy, and the
  // kinetic energy plus the fall of the fluid to the scene's lowest point (its bounds'
  // lowest corner along g) [J/m].
  double initial_energy_ = 0, initial_available_energy_ = 0;
  double initial_max_speed_ = 0;    // fastest fluid particle at t = 0, before settling [m/s]
  double peak_boundary_speed_ = 0;  // fastest moving sample over the run, sampled 4 times per frame
};

}  // namespace sluice
