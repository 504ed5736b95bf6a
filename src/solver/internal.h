#pragma once
// Private to the solver's files: the solvers' scratch arrays, and constants and helpers
// that several phases share.
// Not part of the public interface (src/solver/simulation.h).
#include <algorithm>
#include <chrono>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/types.h"
#include "solver/settings.h"

namespace sluice {

// Per-step scratch of the pressure solvers ("hot" arrays, reused between steps).
struct SolverScratch {
  std::vector<Vec2> a_p;           // pressure acceleration (Eq. 11/24)
  std::vector<Vec2> grad_b;        // sum_b m_b grad W_ib, fixed within a step
  std::vector<double> a_ii;        // diagonal (Eq. 22/26)
  std::vector<double> grad_scale;  // c_i of the gradient correction (compute_density)
  std::vector<double> s;           // source term (Eq. 19)
  std::vector<double> err;         // predicted compression of Eq. 23 [%]
  // The largest compression a particle starts the step with [%] (the non-pressure phase's),
  // and the step it belongs to (Simulation::step_stamp; read only in the same step).
  double start_compression_max = 0;
  long start_compression_stamp = -1;
  // Pressure stabilisation (stabilisation_of): the mean offset x_j - x_i of each particle's
  // neighbours (fluid and samples), fixed within a step, and q_bar of the current iterate.
  std::vector<Vec2> stab_offset;
  std::vector<double> stab_mean;
  std::vector<std::uint8_t> stab_on;  // the stabilised rows: the wall band (plan_wall_band reuses it)
  // Fused Jacobi sweep (Simulation::jacobi_sweep): the bounds of its ranges (one per
  // thread), for each particle the number of blocks after its own that its update
  // waits for (-1: deferred until every range is done), and the deferred particles.
  std::vector<Index> sweep_range;
  std::vector<std::int8_t> sweep_lag;
  std::vector<Index> deferred;      // ascending
  std::vector<double> err_partial;  // sums of err over blocks of kReduceBlock
  // Next to the walls (Simulation::plan_wall_band): the band (the fluid particles with a
  // boundary neighbour and their fluid neighbours) and its reach (the band and its fluid
  // neighbours), ascending.
  std::vector<Index> wall_band, wall_reach;
  // plan_wall_band's flags: the reach (and mark_wall_band's scratch), the band when the
  // stabilisation has not marked it.
  std::vector<std::uint8_t> wall_flag_a, wall_flag_b;
  std::vector<double> p_over_rho2;   // p_i / rho_i^2 of fluid particles
  std::vector<double> pb_over_rho2;  // p_b / rho0^2 of boundary particles
  std::vector<double> ext_wsum;      // sum_f W_bf of each boundary particle (Eq. 25 denominator)
  std::vector<double> ext_gravity;   // g . sum_f rho_f x_bf W_bf (Eq. 25 hydrostatic term)
  // Pressure boundaries (BoundaryPressure::Solved): each sample's source term and
  // diagonal, the counterparts of Eq. 19 and 22 for its density constraint.
  std::vector<double> bnd_s, bnd_aii;
  // Chebyshev's semi-iteration: the fluid's and the samples' pressures one iteration back.
  std::vector<double> p_prev, pb_prev;
  std::vector<double> volume;                  // m / rho_i of fluid particles (apply_nonpressure)
  std::vector<double> work;                    // boundary work on each fluid particle in this step [J/m]
  std::shared_ptr<struct CoarseLevel> coarse;  // the two-level solve's coarse level (multilevel.h)
};

}  // namespace sluice

namespace sluice::solver_detail {

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
inline double compression_percent(double rho, double rho0) { return std::max(100.0 * (rho - rho0) / rho0, 0.0); }

}  // namespace sluice::solver_detail
