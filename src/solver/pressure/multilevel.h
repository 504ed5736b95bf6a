#pragma once
// The coarse level of the two-level pressure solve (solver.pressure_solver = "multilevel",
// issue 37): the fluid's and the samples' pressures aggregated by square cells, and the
// Galerkin operator A_c = P^T A P of the PPE (Eq. 20 and the samples' rows) over them,
// factorised once per solve.
#include <Eigen/Sparse>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseLU>
#include <vector>

#include "core/types.h"

namespace sluice {

struct CoarseLevel {
  using Matrix = Eigen::SparseMatrix<double>;
  // Per unknown (fluid particles 0..n-1, then boundary samples): its aggregate, or -1 for
  // one that the first sweep left clamped at p = 0 (it stays out for the solve).
  std::vector<Index> aggregate;
  Index aggregates = 0;
  Matrix a_c;
  Eigen::SparseLU<Matrix> lu;
  Matrix sym;                             // -(A_c + A_c^T) / 2
  Eigen::SimplicialLDLT<Matrix> ldlt;     // its factors
  bool factorised = false;
  Eigen::VectorXd rc, ec;  // restricted residual, coarse correction
  // Scratch of the aggregation (cell -> aggregate) and of the assembly (row I's entries).
  std::vector<Index> cell_aggregate;
  std::vector<std::vector<std::pair<Index, double>>> rows;
};

}  // namespace sluice
