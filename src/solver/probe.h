#pragma once
// A window into a Simulation for tests and diagnostics (programs do not use it): the
// pressure system of a step (source, diagonal and operator of Eq. 19-22/26), and the
// switches with which tests show that a term matters or that the bits do not depend on
// the Jacobi schedule.
#include <vector>

#include "solver/simulation.h"

namespace sluice {

class SolverProbe {
 public:
  explicit SolverProbe(Simulation& sim) : sim_(sim) {}

  // The phases of a step up to the set-up of the pressure solve with step dt (neighbours
  // and density, v*, then s, a_ii and p^(0)), without advancing time. IISPH only.
  void prepare_pressure_system(double dt);
  // Then Algorithm 2's solver loop with the simulation's settings; returns its iterations
  // (and, given stats, the solve's figures: iterations, average and largest error).
  int iterate_pressure(StepStats* stats = nullptr);
  const std::vector<double>& source() const;    // s_i of the fluid particles (Eq. 19)
  const std::vector<double>& diagonal() const;  // a_ii (Eq. 22/26 as derived in iisph.cpp)
  // Pressure boundaries: each sample's source and diagonal (0: no row).
  const std::vector<double>& sample_source() const;
  const std::vector<double>& sample_diagonal() const;
  // Each sample's density at the last neighbour phase, sum_f m W_bf plus its wall's share
  // (boundary.cpp's boundary_density); 0 for a sample without fluid neighbours.
  std::vector<double> sample_density() const;
  // (Ap) for the fluid pressures p and, with pressure boundaries, the samples' pressures
  // pb (ignored otherwise): Eq. 24 from these pressures (extrapolation, mirroring or zero
  // derive p_b from p), then Eq. 20 for each fluid particle into ap and each sample into
  // apb, with the pressure stabilisation's terms when it is on. Leaves the simulation's
  // pressures at p and pb.
  void apply(const std::vector<double>& p, const std::vector<double>& pb, std::vector<double>& ap,
             std::vector<double>& apb);

  // Sets solver.pressure_stabilisation = kappa for the prepared system (its neighbour
  // offsets computed when kappa > 0), to compare the operator with and without it.
  void set_pressure_stabilisation(double kappa) {
    sim_.settings_.pressure_stabilisation = kappa;
    if (kappa > 0.0) sim_.prepare_stabilisation();
  }

  // The scheme of the following solves (solver.pressure_solver), to solve one state with two.
  void set_pressure_solver(PressureSolver kind) { sim_.settings_.pressure_solver = kind; }

  // The multilevel scheme's coarse level (solver/pressure/coarse_level.h) at the current
  // pressures, after prepare_pressure_system: the unknowns with p > 0 aggregated by cells,
  // and A_c = P^T A P.
  const CoarseLevel& coarse_level();

  // The walls' pressure force on the whole fluid: the sum over fluid particles of m times
  // the boundary part of Eq. 24, at the current pressures and the last step's pairs [N/m].
  // Mirroring's p_b = p_i is not applied (c gamma3 covers it). After a step: its force.
  Vec2 boundary_pressure_force() const;
  // Each fluid particle's pressure acceleration (Eq. 24) at the pressures of the last
  // apply() or solve.
  const std::vector<Vec2>& pressure_acceleration() const;

  // Off: the boundary velocity is left out of the IISPH source term (Eq. 16/19), as in
  // the thesis' own code; only to show that the term matters.
  void set_boundary_velocity_in_source(bool on) { sim_.boundary_velocity_in_source_ = on; }
  // Particles per block of the fused Jacobi sweep (0: automatic, negative: two plain
  // passes) and its number of ranges (0: one per thread). Only the speed depends on them.
  void set_jacobi_sweep(Index block, Index ranges = 0) {
    sim_.jacobi_block_ = block;
    sim_.jacobi_ranges_ = ranges;
  }
  // Volumes of section 4.1 of every boundary particle from scratch at the current
  // positions (the reference for the incremental update of moving boundaries).
  std::vector<double> boundary_volumes_from_scratch() const { return sim_.boundary_volumes_from_scratch(); }

 private:
  Simulation& sim_;
  double dt_ = 0;
  Index active_samples_ = 0;
};

}  // namespace sluice
