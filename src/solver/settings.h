#pragma once
// Solver and time settings: plain structs, every default in one place.
// Units are SI in 2D: m, s, kg/m^2 (density), Pa*m = N/m (2D pressure).
#include <string>

#include "core/types.h"
#include "sph/kernel.h"

namespace sluice {

enum class SolverType { IISPH, WCSPH };

// How a fluid particle sees the pressure of its boundary neighbours (section 4.2).
enum class BoundaryPressure {
  // Pressure boundaries (Band et al. 2018): each boundary sample has its own density
  // constraint in the PPE and its pressure is solved with the fluid's (WCSPH: its own
  // equation of state). The boundary force is then a constraint force and does no work
  // on a fluid at rest; Eq. 25 does (docs/validation.md, "Energy").
  Solved,
  Extrapolation,  // Eq. 25: p_b from its fluid neighbours plus the hydrostatic term
  Mirroring,      // section 4.2.2: p_b = p_f, rho_b = rho_f
  Zero,           // section 4.2.3: p_b = 0
};

// Initial pressure guess p^(0) of the relaxed Jacobi solver (Algorithm 2).
enum class PressureInit {
  Thesis,     // p^(0) = max(omega s_i / a_ii, 0), Eq. 21 with p = 0, Ap = 0
  WarmStart,  // p^(0) = 0.5 * p from the previous step ([Ihm+14a]'s choice)
};

// How IISPH solves its PPE (chapter 3).
enum class PressureSolver {
  Jacobi,      // Algorithm 2: relaxed Jacobi (Eq. 21)
  Chebyshev,   // the same sweeps, each extrapolated by Chebyshev's semi-iteration (chebyshev_rho)
  Multilevel,  // the same sweeps and, each solve, a Galerkin coarse correction (multilevel_cell)
};

const char* to_string(SolverType t);
const char* to_string(BoundaryPressure b);
const char* to_string(PressureInit p);
const char* to_string(PressureSolver p);

struct SolverSettings {
  SolverType type = SolverType::IISPH;
  double rest_density = 1000.0;  // rho0 [kg/m^2], > 0
  Vec2 gravity{0.0, -9.81};      // a_ext [m/s^2]
  double viscosity = 0.0;        // kinematic nu [m^2/s], >= 0, Eq. 12; 0 skips the pass
  // Artificial viscosity of Monaghan (1992, Eq. 4.1): Pi_ij = -alpha c h mu_ij / rho_ij on
  // approaching pairs, for both solvers; >= 0, 0 skips it. 0.01 is DualSPHysics' default.
  double artificial_viscosity = 0.01;
  // Speed c of the artificial viscosity [m/s]; 0: WCSPH's sound speed sqrt(k / rho0),
  // IISPH 10 sqrt(2 g H) (Monaghan's c >= 10 v_max with H the fluid's initial height).
  double sound_speed = 0.0;
  // Scale every pair gradient by (c_i + c_j) / 2, c_i = 2 / tr(sum_j V_j x_ji (x) grad W_ij),
  // so that the SPH gradient of a linear field is exact on average over directions
  // (a scalar, pair-symmetric kernel gradient correction after Bonet & Lok 1999).
  bool gradient_correction = true;
  // The SPH kernel (sph/kernel.h) and its support radius in particle spacings (h = support
  // spacing / 2): the thesis' cubic spline on 2 spacings, or Wendland's C2.
  KernelKind kernel = KernelKind::CubicSpline;
  // 2 for either kernel: wider supports hold the stretched drop but not yet the walls
  // (docs/validation.md, "Kernels and support radius").
  double support = 2.0;
  // IISPH (chapter 3)
  double tolerance_percent = 0.1;  // average predicted compression error (Eq. 23) [%], > 0
  double omega = 0.5;              // relaxation of Eq. 21, in (0, 1]
  int min_iterations = 3;          // [Cor+19]: at least 3 iterations
  int max_iterations = 100;
  PressureInit pressure_init = PressureInit::WarmStart;
  PressureSolver pressure_solver = PressureSolver::Jacobi;
  // Chebyshev: the spectral radius assumed for the relaxed Jacobi iteration, in [0, 1).
  // Any value converges where Jacobi does; near the true radius is fastest.
  double chebyshev_rho = 0.98;
  // Multilevel: the side of the cells that aggregate the pressures, in particle spacings,
  // in [2, 64] (coupled aggregates then lie within two cells of each other).
  double multilevel_cell = 6.0;
  // Multilevel: Jacobi iterations on the fluid next to the walls and the samples after each
  // coarse correction (Simulation::smooth_wall_band), in [0, 100]; 0: none.
  int multilevel_wall_sweeps = 2;
  // Multilevel: 0, a step that starts with a particle past 5 % compressed (an impact) takes
  // Jacobi's sweeps alone; in (0, 1], it takes the two-level solve with each coarse
  // correction scaled by this (docs/performance.md, "Impacts with a damped correction").
  double multilevel_impact_damping = 0.0;
  // IISPH: kappa of the pressure stabilisation of the wall band's and the samples' rows
  // (Simulation::stabilisation_of), in [0, 10]; 0: none, Eq. 20 as printed. The odd-even
  // pattern of rows that Eq. 24's sum form cannot see stops being a null mode; linear
  // pressure fields are left alone. Negative: the solver's own (stabilisation_kappa).
  double pressure_stabilisation = -1.0;
  // Include in a_ii the dependence of the boundary pressure on p_i (mirroring: p_b = p_i
  // doubles the boundary part; extrapolation: p_b carries p_i with weight W_bi / sum W).
  // Off: Eq. 26 as printed, where the boundary enters d_ii once. See solve_pressure_iisph.
  bool boundary_diagonal = true;
  // WCSPH (section 2.3.1)
  // k [Pa*m], > 0; 0: the scene's default, wcsph_default_stiffness (solver/setup.h).
  double stiffness = 0.0;
  // Boundaries (chapter 4)
  BoundaryPressure boundary_pressure = BoundaryPressure::Solved;
  // Boundary volume scale, V_b = gamma1 / sum_b W (section 4.1), > 0. Akinci's volume
  // over-estimates the cell of a wall sample, whose kernel sum misses the fluid side:
  // for two or more layers at the fluid spacing (the default sampling) V_b = 1.188 h^2,
  // and a fluid row one spacing off the wall reaches 1.031 rho0 with gamma1 = 1. With
  // 0.84 that row is at rest density, so a block placed against a wall starts at rest
  // instead of being pushed off in the first step (tests/test_physics.cpp checks it).
  double gamma1 = 0.84;
  double gamma2 = 1.0;  // boundary density contribution (section 4.1), >= 0
  double gamma3 = 1.0;  // boundary pressure force (Eq. 24), >= 0
};

struct TimeSettings {
  double duration = 4.0;   // simulated seconds, > 0
  double fps = 30.0;       // frame rate; steps always land on frame times, > 0
  double dt = 0.0;         // fixed step [s]; 0 selects the adaptive CFL step
  double cfl = 0.4;        // lambda of Eq. 14, in (0, 2]
  double dt_max = 1.0e-3;  // largest adaptive step [s]
  double dt_min = 1.0e-6;  // smallest adaptive step [s]; a smaller one means the run went unstable
  // Settling before t = 0 [s], >= 0: the fluid is stepped under gravity with its
  // velocities damped (time constant settle / 10) and boundaries held at their t = 0
  // pose, then starts at rest with its pressure field established. 0: none. Used when
  // auto_settle is false.
  double settle = 0.0;
  // time.settle "auto" (the default): kAutoSettleSeconds where the fluid starts at rest
  // (Simulation::starts_at_rest), none where it does not.
  bool auto_settle = true;
  // Relax the start before t = 0 (and before any settling) where the sampling left a fluid
  // particle more than kRelaxStartPercent compressed (Simulation::relax_start): a boundary
  // off the fluid's lattice. A start on the lattice is not touched. false: never.
  bool relax_start = true;
};

// The start's relaxation: rounds until no particle is more than this compressed [%], and
// at most this many (a 14 % compressed column next to a plate takes 5-11).
constexpr double kRelaxStartPercent = 1.0;
constexpr int kRelaxStartRounds = 100;
// A fluid that starts at rest, with time.settle "auto", settles this long [s]: neither the
// lattice nor the relaxed start is in equilibrium under gravity next to a boundary, and the
// first steps' pressure rings through the tank for seconds (docs/validation.md, "Every
// start at rest settles").
constexpr double kAutoSettleSeconds = 0.1;
// How messages name a settle: its origin, followed by its seconds.
inline const char* settle_origin(const TimeSettings& t) {
  return t.auto_settle ? "automatic, as the fluid starts at rest: " : "time.settle = ";
}
// A fluid is at rest when none of it moves and at least this share of its free surface
// faces up, within 45 degrees of -g (a dam break's column faces sideways too).
constexpr double kAtRestSurfaceShare = 0.9;

// What the start's relaxation did: its rounds and the largest compression before and after.
struct RelaxStats {
  int rounds = 0;
  double largest_before_percent = 0.0;
  double largest_after_percent = 0.0;
};

// WCSPH's acoustic limit (Monaghan 1992): dt <= kAcousticCfl h / (c + v_max).
constexpr double kAcousticCfl = 0.4;
// The ambient-pressure limit of an adaptive step: dt <= kHydrostaticCfl h / sqrt(|g| H),
// H the fluid's extent along g (Simulation::hydrostatic_speed). A 2 m column at rest, h =
// 0.01, Jacobi: 0.5 to 0.7 held still, 1.0 boiled and stopped at 0.12 s (docs/performance.md).
constexpr double kHydrostaticCfl = 0.6;

// The multilevel solve's own kappa, from a sweep with the term in its coarse operator
// (the shipped tank at 0.1 and 0.01 %, the thin plate, the deep column, on either kernel):
// 1 and 3 hold all of them, 2 leaves the cubic spline's bottom row at -3.98 % at 0.01 %
// (bound 3 %); the smallest is kept (docs/performance.md, "The stabilisation in the coarse
// operator"). Jacobi and Chebyshev pay for it in iterations: 0.
constexpr double kMultilevelStabilisation = 1.0;

// The kappa a solve uses: the scene's, or the solver's own.
inline double stabilisation_kappa(const SolverSettings& s) {
  if (s.pressure_stabilisation >= 0.0) return s.pressure_stabilisation;
  return s.pressure_solver == PressureSolver::Multilevel ? kMultilevelStabilisation : 0.0;
}

// Limits of the instability detector: a run stops with a message when one is exceeded.
struct StabilityLimits {
  double max_error_percent = 50.0;  // largest per-step compression error [%]
  double bounds_margin = 10.0;      // particles farther than this many scene sizes are lost
  // Fluid particles found past a wall's first sample layer at a frame time, as a percentage
  // of all fluid particles; more means the boundary no longer holds the fluid.
  double max_leaked_percent = 1.0;
  // The fluid's mechanical energy may rise above its start by at most this fraction of
  // the energy available to it (Simulation::energy_gain_bound): a fluid that gains more
  // has blown up, even one that stays inside the bounds and out of the walls.
  double max_energy_gain = 0.1;
  // The fastest particle may move at most this many times the speed the fluid can have
  // been given (Simulation::speed_bound): a few particles shot off at tens of m/s are a
  // blow-up that the energy test, summed over the fluid, does not see.
  double max_speed_ratio = 3.0;
};

}  // namespace sluice
