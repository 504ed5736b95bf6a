#pragma once
// The handle through which a PressureSolverMethod (pressure_solver.h) iterates on one
// step's PPE: built by Simulation::iterate_pressure after prepare_pressure_system (s_i,
// a_ii, p^(0) and the samples' rows are set up), valid for that call only.
#include "solver/simulation.h"

namespace sluice {

class PressureSystem {
 public:
  // terms: the step's constants (Simulation::pressure_terms); block: the sweep's schedule
  // (Simulation::plan_jacobi_sweep); active_samples: the boundary samples with a row.
  PressureSystem(Simulation& sim, const Simulation::PressureTerms& terms, Index block, Index active_samples)
      : sim_(sim), terms_(terms), block_(block), active_samples_(active_samples) {}

  Index fluid_count() const;
  Index active_samples() const { return active_samples_; }
  const SolverSettings& settings() const;

  // One relaxed Jacobi iteration (Algorithm 2's loop body: Eq. 25, then Eq. 24, 20, 21,
  // 23 for every particle, and Eq. 21 for the samples of pressure boundaries), each update
  // extrapolated with the weight set below when it is nonzero. Returns the average
  // predicted compression (Eq. 23) in percent: the fluid's, or with pressure boundaries
  // the larger of the fluid's and the samples' averages.
  double sweep();
  // The largest predicted compression (Eq. 23) of a fluid particle after the last sweep, in
  // percent (the step's max_error_percent).
  double largest_error() const;
  // The largest compression a fluid particle starts the step with (its density of Eq. 13
  // against rho0), in percent.
  double largest_start_compression() const;

  // Chebyshev's semi-iteration (pressure_kernels.h, chebyshev_extrapolate).
  void set_extrapolation_weight(double w) { terms_.chebyshev = w; }  // 0: plain relaxed Jacobi
  // p_prev, pb_prev := p, p_b: Chebyshev's previous iterate, or the multilevel solve's
  // iterate before a coarse correction.
  void save_previous_iterate();
  // Puts back the iterate saved last (p_prev, pb_prev) with its p / rho^2.
  void restore_saved_iterate();

  // The multilevel scheme's coarse level (coarse_level.h): aggregates of the unknowns
  // with p > 0 now and the Galerkin operator over them; then a correction from the
  // current residual (one application of A), false when the coarse operator could not be
  // factorised (nothing changed).
  void build_coarse_level();
  bool coarse_correction(double scale = 1.0);  // the correction times scale
  // Jacobi iterations on the fluid next to the walls and the samples only (after
  // McAdams et al. 2010's extra boundary smoothing); the band is planned on first use.
  void smooth_near_walls(int iterations);

 private:
  Simulation& sim_;
  Simulation::PressureTerms terms_;
  Index block_;
  Index active_samples_;
  bool band_planned_ = false;
};

}  // namespace sluice
