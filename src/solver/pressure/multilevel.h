#pragma once
// The coarse level of the two-level pressure solve (solver.pressure_solver = "multilevel",
// issue 37): the PPE's operator A assembled as a sparse matrix over the fluid's and the
// samples' pressures, the unknowns aggregated by square cells, and a Galerkin coarse
// operator A_c = R A P (R = P^T) factorised once per solve. Serial: the same bits for any
// thread count.
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <vector>

#include "core/types.h"

namespace sluice {

struct MultilevelData {
  using Matrix = Eigen::SparseMatrix<double>;
  Matrix a;                // A over all unknowns: fluid 0..n-1, samples n..n+nb-1
  std::vector<Index> active;  // unknown -> active index, -1 when held at p = 0
  Index n_active = 0;
  Matrix p;                // prolongation: active unknowns x aggregates
  Matrix a_c;              // R A P
  Eigen::SparseLU<Matrix> lu;
  bool ok = false;
  Eigen::VectorXd x, r, e;  // scratch
};

}  // namespace sluice
