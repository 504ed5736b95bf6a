#pragma once
// The coarse level of the multilevel pressure solve (solver.pressure_solver = "multilevel",
// multilevel.cpp): the fluid's and the samples' pressures aggregated by square cells, and
// the Galerkin operator A_c = P^T A P of the PPE (Eq. 20 and the samples' rows) over them,
// factorised once per solve (Simulation::build_coarse_level, coarse_level.cpp).
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <cstdint>
#include <vector>

#include "core/types.h"

namespace sluice {

// The LDL^T factors of A_c's symmetric part, -(A_c + A_c^T) / 2, as BiCGSTAB's
// preconditioner for A_c itself (the interface Eigen's iterative solvers call).
struct SymmetricPartPreconditioner {
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>>* ldlt = nullptr;
  template <typename M>
  SymmetricPartPreconditioner& analyzePattern(const M&) {
    return *this;
  }
  template <typename M>
  SymmetricPartPreconditioner& factorize(const M&) {
    return *this;
  }
  template <typename M>
  SymmetricPartPreconditioner& compute(const M&) {
    return *this;
  }
  template <typename Rhs>
  Eigen::VectorXd solve(const Rhs& b) const {
    return -ldlt->solve(b);
  }
  Eigen::ComputationInfo info() const { return Eigen::Success; }
};

struct CoarseLevel {
  using Matrix = Eigen::SparseMatrix<double>;
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor>;
  // Per unknown (fluid particles 0..n-1, then boundary samples): its aggregate, or -1 for
  // one that the first sweep left clamped at p = 0 (it stays out for the solve).
  std::vector<Index> aggregate;
  Index aggregates = 0;
  RowMatrix a_c;                                                     // assembled row by row
  Matrix symmetric;                                                  // -(A_c + A_c^T) / 2
  Eigen::SimplicialLDLT<Matrix> ldlt;                                // its factors
  Eigen::BiCGSTAB<RowMatrix, SymmetricPartPreconditioner> bicgstab;  // A_c e = r
  bool factor_pending = false;  // built, not yet factorised (the solve's first correction does it)
  bool factorised = false;
  std::vector<double> residual;  // s - A x of the fluid rows at a correction
  Eigen::VectorXd rc, ec;        // restricted residual, coarse correction
  // Aggregates are cells: each one's cell, and the cells' aggregates (-1: none) on a grid
  // of nx columns.
  std::vector<std::int32_t> cell_x, cell_y;
  std::vector<std::int32_t> unknown_x, unknown_y;  // each unknown's cell; INT32_MIN: not aggregated
  std::vector<Index> cell_aggregate;
  long nx = 0, ny = 0;

  // The assembly's partial sums: per chunk of particles, per aggregate I, one slot per
  // cell J within kReach cells of I's.
  std::vector<double> partial;
  std::vector<double> slot_sum;          // the chunks' sums, per aggregate and slot
  std::vector<std::uint8_t> slot_entry;  // whether any chunk touched the slot
  std::vector<int> row_start;            // A_c's row offsets
  std::vector<double> neg_m_over_rho2;   // -m / rho_f^2 per fluid particle (the same bits as per pair)
  std::vector<Index> members, renumber;  // drop_sparse_aggregates: fluid per aggregate, new numbers
};

}  // namespace sluice
