// The two-level pressure solve (solver.pressure_solver = "multilevel"): relaxed Jacobi
// sweeps (Algorithm 2) with a Galerkin coarse correction of the smooth, column-long modes
// that the sweeps damp slowly (issue 37; aggregation after Trask et al. 2015 and Osaki et
// al. 2023, on square cells).
#include "solver/pressure/multilevel.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <tuple>

#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure_kernels.h"
#include "solver/simulation.h"

namespace sluice {

namespace {
using Triplet = Eigen::Triplet<double>;
double env_number(const char* name, double fallback) {
  const char* v = std::getenv(name);
  return v ? std::atof(v) : fallback;
}
}  // namespace

// A of Eq. 20 (fluid rows) and of the samples' constraints (prepare_solved_boundary) as
// D G: G maps the unknowns to the accelerations of Eq. 24, D the accelerations to (Ap).
void Simulation::assemble_pressure_matrix(const PressureTerms& t, MultilevelData& ml) const {
  const Index n = fluid_.size(), nb = boundary_.size(), unknowns = n + nb;
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  const double m = mass_, dt = t.dt, inv_rho0_2 = 1.0 / (settings_.rest_density * settings_.rest_density);
  std::vector<Triplet> g, d;
  g.reserve(static_cast<size_t>(2 * (ff_.pairs() + fb_.pairs() + n)));
  d.reserve(static_cast<size_t>(2 * (ff_.pairs() + bf_.pairs() + n)));
  for (Index i = 0; i < n; ++i) {
    const double inv2 = 1.0 / (fluid_.rho[i] * fluid_.rho[i]);
    Vec2 sum = Vec2::Zero();
    for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
      const Index f = ff_.j[k];
      const Vec2 gw = ff_.grad[k].cast<double>();
      sum += gw;
      const double cf = -m / (fluid_.rho[f] * fluid_.rho[f]);
      g.emplace_back(2 * i, f, cf * gw.x());
      g.emplace_back(2 * i + 1, f, cf * gw.y());
      d.emplace_back(i, 2 * f, -dt * m * gw.x());
      d.emplace_back(i, 2 * f + 1, -dt * m * gw.y());
    }
    const Vec2 own = -inv2 * (m * sum + t.c_gamma3 * scratch_->grad_b[i]);
    g.emplace_back(2 * i, i, own.x());
    g.emplace_back(2 * i + 1, i, own.y());
    const Vec2 div = dt * (m * sum + t.gamma2 * scratch_->grad_b[i]);
    d.emplace_back(i, 2 * i, div.x());
    d.emplace_back(i, 2 * i + 1, div.y());
    if (samples)
      for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
        const Index b = fb_.j[k];
        const Vec2 c = -(t.gamma3_rho0 * boundary_.volume[b] * inv_rho0_2) * fb_.grad[k].cast<double>();
        g.emplace_back(2 * i, n + b, c.x());
        g.emplace_back(2 * i + 1, n + b, c.y());
      }
  }
  if (samples)
    for (Index b = 0; b < nb; ++b)
      for (Index k = bf_.offset[b]; k < bf_.offset[b + 1]; ++k) {
        const Index f = bf_.j[k];
        const Vec2 gw = bf_.grad[k].cast<double>();
        d.emplace_back(n + b, 2 * f, -dt * m * gw.x());
        d.emplace_back(n + b, 2 * f + 1, -dt * m * gw.y());
      }
  Eigen::SparseMatrix<double> gm(2 * n, unknowns), dm(unknowns, 2 * n);
  gm.setFromTriplets(g.begin(), g.end());
  dm.setFromTriplets(d.begin(), d.end());
  ml.a = dm * gm;
}

// The coarse level for this solve: A, the active set (the unknowns the first sweep left
// above zero; those clamped stay out for the solve), aggregates of the active unknowns
// by cells of ML_CELL spacings, P (plain or smoothed aggregation) and R A P, factorised.
void Simulation::multilevel_setup(const PressureTerms& t) {
  if (!scratch_->multilevel) scratch_->multilevel = std::make_shared<MultilevelData>();
  MultilevelData& ml = *scratch_->multilevel;
  const Index n = fluid_.size(), nb = boundary_.size(), unknowns = n + nb;
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  assemble_pressure_matrix(t, ml);
  ml.active.assign(static_cast<size_t>(unknowns), -1);
  Index na = 0;
  for (Index i = 0; i < n; ++i)
    if (fluid_.p[i] > 0.0) ml.active[i] = na++;
  static const bool coarse_samples = env_number("ML_NO_SAMPLES", 0.0) == 0.0;
  if (samples && coarse_samples)
    for (Index b = 0; b < nb; ++b)
      if (scratch_->bnd_aii[b] != 0.0 && boundary_.p[b] > 0.0) ml.active[n + b] = na++;
  ml.n_active = na;
  // Aggregates: cells of the positions, numbered in order of first appearance.
  static const double cell_factor = env_number("ML_CELL", 4.0);
  static const bool own_samples = env_number("ML_OWN_SAMPLES", 0.0) != 0.0;
  const double inv_cell = 1.0 / (cell_factor * setup_.spacing);
  std::map<std::tuple<int, long, long>, Index> cells;
  std::vector<Triplet> sel, pt;
  for (Index u = 0; u < unknowns; ++u) {
    if (ml.active[u] < 0) continue;
    const Vec2 x = u < n ? fluid_.x[u] : boundary_.x[u - n];
    const auto key = std::make_tuple(own_samples && u >= n ? 1 : 0, static_cast<long>(std::floor(x.x() * inv_cell)),
                                     static_cast<long>(std::floor(x.y() * inv_cell)));
    const auto it = cells.emplace(key, static_cast<Index>(cells.size())).first;
    sel.emplace_back(ml.active[u], u, 1.0);
    pt.emplace_back(ml.active[u], it->second, 1.0);
  }
  const Index nc = static_cast<Index>(cells.size());
  Eigen::SparseMatrix<double> s(na, unknowns), p0(na, nc);
  s.setFromTriplets(sel.begin(), sel.end());
  p0.setFromTriplets(pt.begin(), pt.end());
  const Eigen::SparseMatrix<double> aa = s * ml.a * s.transpose();
  static const double smooth = env_number("ML_SMOOTH", 0.0);
  if (smooth > 0.0) {
    Eigen::VectorXd dinv = aa.diagonal();
    for (Index k = 0; k < na; ++k) dinv[k] = dinv[k] != 0.0 ? smooth / dinv[k] : 0.0;
    const Eigen::SparseMatrix<double> ap0 = aa * p0;
    ml.p = p0 - dinv.asDiagonal() * ap0;
  } else {
    ml.p = p0;
  }
  ml.a_c = Eigen::SparseMatrix<double>(ml.p.transpose()) * aa * ml.p;
  ml.a_c.makeCompressed();
  ml.lu.compute(ml.a_c);
  ml.ok = ml.lu.info() == Eigen::Success;
  if (std::getenv("ML_DEBUG"))
    std::fprintf(stderr, "ml: unknowns %ld active %ld aggregates %ld nnz A %ld Ac %ld lu %d\n", (long)unknowns,
                 (long)na, (long)nc, (long)ml.a.nonZeros(), (long)ml.a_c.nonZeros(), ml.ok ? 1 : 0);
  if (std::getenv("ML_TEST")) {
    // Synthetic: x* = rho0 g (top - y) on the active unknowns; one coarse solve from x = 0.
    double top = -1e30;
    for (Index i = 0; i < n; ++i) top = std::max(top, fluid_.x[i].y());
    Eigen::VectorXd xs = Eigen::VectorXd::Zero(unknowns);
    for (Index u = 0; u < unknowns; ++u)
      if (ml.active[u] >= 0) xs[u] = 1000.0 * 9.81 * (top - (u < n ? fluid_.x[u].y() : boundary_.x[u - n].y()));
    const Eigen::VectorXd b = ml.a * xs;
    Eigen::VectorXd ba(na);
    for (Index u = 0; u < unknowns; ++u)
      if (ml.active[u] >= 0) ba[ml.active[u]] = b[u];
    const Eigen::VectorXd ea = ml.p * ml.lu.solve(Eigen::VectorXd(ml.p.transpose() * ba));
    for (Index i = 0; i < n; i += n / 20)
      if (ml.active[i] >= 0)
        std::fprintf(stderr, "ml test: y %.3f x* %.1f e %.1f  (A x*)_i %.3g\n", fluid_.x[i].y(), xs[i],
                     ea[ml.active[i]], b[i]);
    const Eigen::VectorXd one = Eigen::VectorXd::Ones(unknowns);
    const Eigen::VectorXd a1 = ml.a * one;
    double asym = (Eigen::SparseMatrix<double>(ml.a.transpose()) - ml.a).norm() / ml.a.norm();
    std::fprintf(stderr, "ml test: |A-A^T|/|A| %.3g, |A 1| %.3g vs |A x*|/|x*|inf %.3g\n", asym, a1.norm(),
                 b.norm() / xs.maxCoeff());
  }
  if (std::getenv("ML_CHECK")) {
    // A x against the sweep's operator at the current pressures.
    Eigen::VectorXd x(unknowns);
    for (Index i = 0; i < n; ++i) x[i] = fluid_.p[i];
    for (Index b = 0; b < nb; ++b) x[n + b] = samples ? boundary_.p[b] : 0.0;
    const Eigen::VectorXd ax = ml.a * x;
    const_cast<Simulation*>(this)->compute_pressure_acceleration();
    double worst = 0.0, scale = 0.0, dworst = 0.0;
    for (Index i = 0; i < n; ++i) {
      const double op = pressure_operator_of(i, t);
      worst = std::max(worst, std::abs(op - ax[i]));
      scale = std::max(scale, std::abs(op));
      dworst = std::max(dworst, std::abs(ml.a.coeff(i, i) - scratch_->a_ii[i]) / std::abs(scratch_->a_ii[i]));
    }
    double bworst = 0.0;
    if (samples)
      for (Index b = 0; b < nb; ++b) bworst = std::max(bworst, std::abs(sample_operator_of(b, t) - ax[n + b]));
    std::fprintf(stderr, "ml check: |Ax - op| fluid %.3g (scale %.3g) samples %.3g, diag rel %.3g\n", worst, scale,
                 bworst, dworst);
  }
}

// One coarse correction: r = s - A x, x_active += alpha P (R A P)^-1 R r, clamped at zero
// like Eq. 21. alpha = ML_ALPHA (a number), or the residual-minimising step when it is 0.
// Returns the applications of A it cost (1, or 2 with the line search).
int Simulation::multilevel_correction(const PressureTerms& t) {
  MultilevelData& ml = *scratch_->multilevel;
  if (!ml.ok) return 0;
  const Index n = fluid_.size(), nb = boundary_.size(), unknowns = n + nb;
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  ml.x.resize(unknowns);
  Eigen::VectorXd rhs(unknowns);
  for (Index i = 0; i < n; ++i) {
    ml.x[i] = fluid_.p[i];
    rhs[i] = scratch_->s[i];
  }
  for (Index b = 0; b < nb; ++b) {
    ml.x[n + b] = samples ? boundary_.p[b] : 0.0;
    rhs[n + b] = samples ? scratch_->bnd_s[b] : 0.0;
  }
  const Eigen::VectorXd r = rhs - ml.a * ml.x;
  Eigen::VectorXd ra(ml.n_active);
  for (Index u = 0; u < unknowns; ++u)
    if (ml.active[u] >= 0) ra[ml.active[u]] = r[u];
  const Eigen::VectorXd ec = ml.lu.solve(Eigen::VectorXd(ml.p.transpose() * ra));
  const Eigen::VectorXd ea = ml.p * ec;
  static const double fixed_alpha = env_number("ML_ALPHA", 1.0);
  double alpha = fixed_alpha;
  int cost = 1;
  if (alpha == 0.0) {
    Eigen::VectorXd e = Eigen::VectorXd::Zero(unknowns);
    for (Index u = 0; u < unknowns; ++u)
      if (ml.active[u] >= 0) e[u] = ea[ml.active[u]];
    const Eigen::VectorXd ae = ml.a * e;
    double num = 0.0, den = 0.0;
    for (Index u = 0; u < unknowns; ++u)
      if (ml.active[u] >= 0) {
        num += r[u] * ae[u];
        den += ae[u] * ae[u];
      }
    alpha = den > 0.0 ? num / den : 0.0;
    cost = 2;
  }
  if (std::getenv("ML_DEBUG")) {
    double pmax = 0.0;
    for (Index i = 0; i < n; ++i) pmax = std::max(pmax, fluid_.p[i]);
    std::fprintf(stderr, "ml: |r| %.4g alpha %.4g |e|max %.4g p max %.4g ec range %.4g %.4g\n", ra.norm(), alpha,
                 ea.cwiseAbs().maxCoeff(), pmax, ec.minCoeff(), ec.maxCoeff());
  }
  const double inv_rho0_2 = 1.0 / (settings_.rest_density * settings_.rest_density);
  for (Index i = 0; i < n; ++i) {
    if (ml.active[i] < 0) continue;
    const double p = std::max(fluid_.p[i] + alpha * ea[ml.active[i]], 0.0);
    fluid_.p[i] = p;
    scratch_->p_over_rho2[i] = p / (fluid_.rho[i] * fluid_.rho[i]);
  }
  if (samples)
    for (Index b = 0; b < nb; ++b) {
      if (ml.active[n + b] < 0) continue;
      const double p = std::max(boundary_.p[b] + alpha * ea[ml.active[n + b]], 0.0);
      boundary_.p[b] = p;
      scratch_->pb_over_rho2[b] = p * inv_rho0_2;
    }
  return cost;
}

}  // namespace sluice
