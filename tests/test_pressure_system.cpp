// The IISPH pressure system against the operator it inverts (src/solver/iisph.cpp):
// - a_ii is d(Ap)_i / dp_i of the implemented operator, by finite differences, for each
//   boundary method (the main departure from Eq. 26 is this derived diagonal);
// - relaxed Jacobi's fixed point solves the system: on its active set (p > 0) it equals
//   Eigen's SparseLU solution of the same rows, assembled column by column from the
//   operator, and the clamped rows are not compressed.
// Refresh nothing here: these are properties, not stored numbers.
#include <gtest/gtest.h>

#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "solver/probe.h"
#include "solver/simulation.h"
#include "test_util.h"

namespace sluice {
namespace {

// A 0.2 x 0.2 m block at rest in a box (h = 0.02: 100 particles), settled, then one
// step so that the pressures are a real field.
Simulation resting_block(const std::string& method, bool boundary_diagonal = true) {
  Simulation sim(test::scene_from_json(R"({"spacing": 0.02,
    "solver": {"boundary_pressure": ")" +
                                       method + R"(", "boundary_diagonal": )" + (boundary_diagonal ? "true" : "false") +
                                       R"(},
    "time": {"duration": 0.1, "fps": 10, "dt": 1e-3, "settle": 0.2},
    "fluid": [{"shape": "rectangle", "min": [0, 0], "max": [0.2, 0.2]}],
    "boundaries": [{"shape": "box", "min": [0, 0], "max": [0.2, 0.3], "lid": false}]})"));
  sim.step();
  return sim;
}

constexpr double kDt = 1e-3;

// d(Ap)_i / dp_i by a central difference around the hydrostatic field (the operator
// is linear away from the clamps; p > 0 everywhere keeps Eq. 25's p_b off its clamp).
double numeric_diagonal(SolverProbe& probe, std::vector<double> p, const std::vector<double>& pb, Index i, double eps) {
  std::vector<double> ap_plus, ap_minus, apb;
  p[i] += eps;
  probe.apply(p, pb, ap_plus, apb);
  p[i] -= 2 * eps;
  probe.apply(p, pb, ap_minus, apb);
  return (ap_plus[i] - ap_minus[i]) / (2 * eps);
}

std::vector<double> hydrostatic(const Simulation& sim) {
  std::vector<double> p;
  for (const Vec2& x : sim.fluid().x) p.push_back(1000.0 * 9.81 * std::max(0.21 - x.y(), 0.01));
  return p;
}

class PressureSystem : public ::testing::TestWithParam<const char*> {};

TEST_P(PressureSystem, DiagonalIsTheOperatorsDerivative) {
  Simulation sim = resting_block(GetParam());
  SolverProbe probe(sim);
  probe.prepare_pressure_system(kDt);
  const std::vector<double> a = probe.diagonal();
  const std::vector<double> p = hydrostatic(sim);
  const std::vector<double> pb(static_cast<size_t>(sim.boundary().size()), 500.0);
  double worst = 0;
  for (Index i = 0; i < sim.fluid().size(); ++i) {
    const double fd = numeric_diagonal(probe, p, pb, i, 10.0);
    ASSERT_LT(a[i], 0.0) << "particle " << i;
    worst = std::max(worst, std::abs(a[i] - fd) / std::abs(fd));
  }
  std::printf("[ measured ] %s: largest |a_ii - d(Ap)_i/dp_i| / |a_ii| = %.2e over %d particles\n", GetParam(), worst,
              static_cast<int>(sim.fluid().size()));
  EXPECT_LT(worst, 1e-7);
}

INSTANTIATE_TEST_SUITE_P(EachBoundaryMethod, PressureSystem,
                         ::testing::Values("solved", "extrapolation", "mirroring", "zero"));

// Eq. 26 as printed (boundary_diagonal = false) leaves out the boundary pressure's
// dependence on p_i: with extrapolation its a_ii is not the operator's derivative next to
// a wall. This is what the derived diagonal fixes.
TEST(PressureSystemPlainDiagonal, MissesTheExtrapolatedBoundarysShareNextToWalls) {
  Simulation sim = resting_block("extrapolation", /*boundary_diagonal=*/false);
  SolverProbe probe(sim);
  probe.prepare_pressure_system(kDt);
  const std::vector<double> a = probe.diagonal();
  const std::vector<double> p = hydrostatic(sim);
  const std::vector<double> pb(static_cast<size_t>(sim.boundary().size()), 0.0);
  double worst = 0;
  for (Index i = 0; i < sim.fluid().size(); ++i)
    worst = std::max(worst, std::abs(a[i] - numeric_diagonal(probe, p, pb, i, 10.0)) / std::abs(a[i]));
  std::printf("[ measured ] Eq. 26 as printed, extrapolation: largest relative a_ii error %.3f\n", worst);
  EXPECT_GT(worst, 0.05);
}

// The samples' rows of pressure boundaries: a_bb is the exact derivative or, where the
// lumped row sum is larger, that sum (more negative: Jacobi must not overshoot on
// near-duplicate samples). Either way never smaller in magnitude than the derivative.
TEST(PressureSystemSamples, SampleDiagonalIsTheDerivativeOrTheLargerLumpedSum) {
  Simulation sim = resting_block("solved");
  SolverProbe probe(sim);
  probe.prepare_pressure_system(kDt);
  const std::vector<double> abb = probe.sample_diagonal();
  const std::vector<double> p = hydrostatic(sim);
  std::vector<double> pb(static_cast<size_t>(sim.boundary().size()), 500.0);
  int rows = 0, exact = 0;
  double largest_ratio = 0;
  for (Index b = 0; b < sim.boundary().size(); ++b) {
    if (abb[b] == 0.0) continue;
    ++rows;
    std::vector<double> ap, plus, minus;
    pb[b] += 10.0;
    probe.apply(p, pb, ap, plus);
    pb[b] -= 20.0;
    probe.apply(p, pb, ap, minus);
    pb[b] += 10.0;
    const double fd = (plus[b] - minus[b]) / 20.0;
    ASSERT_LT(fd, 0.0) << "sample " << b;
    EXPECT_LE(abb[b], fd * (1 - 1e-7)) << "sample " << b << ": a_bb smaller in magnitude than the derivative";
    exact += std::abs(abb[b] - fd) <= 1e-7 * std::abs(fd);
    largest_ratio = std::max(largest_ratio, abb[b] / fd);
  }
  std::printf("[ measured ] %d sample rows, %d with the exact derivative as diagonal, largest a_bb / derivative %.2f\n",
              rows, exact, largest_ratio);
  EXPECT_GT(rows, 20);
}

// The pressure stabilisation (solver.pressure_stabilisation, pressure_kernels.h): a
// pressure alternating row by row through the fluid and the floor's samples is nearly a
// null mode of Eq. 20 with pressure boundaries (Eq. 24's sum form gives a row no force from
// its own pressure): z.Az / z.Dz (D: the diagonal) is small. The stabilisation sees it like
// any lattice-scale error, and leaves a linear field alone inside the fluid. On the settled
// block, the same state with and without the stabilisation.
TEST(PressureStabilisation, AlternatingRowsAreNoLongerANullMode) {
  Simulation sim = resting_block("solved");
  SolverProbe probe(sim);
  probe.prepare_pressure_system(kDt);
  const std::vector<double> a = probe.diagonal(), abb = probe.sample_diagonal();
  const double h = 0.02;
  std::vector<double> z, zb, lin, linb;
  auto alternating = [&](const Vec2& x) { return std::fmod(std::floor(x.y() / h), 2.0) == 0 ? 1.0 : -1.0; };
  for (const Vec2& x : sim.fluid().x) z.push_back(alternating(x)), lin.push_back(1000.0 * (0.3 - x.y()));
  for (const Vec2& x : sim.boundary().x) zb.push_back(alternating(x)), linb.push_back(1000.0 * (0.3 - x.y()));
  auto rayleigh = [&](const std::vector<double>& az, const std::vector<double>& azb) {
    double num = 0, den = 0;
    for (size_t i = 0; i < z.size(); ++i) num += z[i] * az[i], den += z[i] * z[i] * a[i];
    for (size_t b = 0; b < zb.size(); ++b)
      if (abb[b] != 0.0) num += zb[b] * azb[b], den += zb[b] * zb[b] * abb[b];
    return num / den;
  };
  std::vector<double> az0, azb0, az2, azb2, al0, alb0, al2, alb2;
  probe.apply(z, zb, az0, azb0);
  probe.apply(lin, linb, al0, alb0);
  probe.set_pressure_stabilisation(3.0);
  probe.apply(z, zb, az2, azb2);
  probe.apply(lin, linb, al2, alb2);
  // Inside (two spacings from the walls and the surface): the stabilisation's term on the
  // linear field against its term on the alternating one, each per unit of the field's
  // lattice-scale variation (h |grad| for the linear field, 1 for the alternating one).
  double on_linear = 0, on_alternating = 0;
  for (Index i = 0; i < sim.fluid().size(); ++i) {
    const Vec2 x = sim.fluid().x[i];
    if (x.x() < 2 * h || x.x() > 0.2 - 2 * h || x.y() < 2 * h || x.y() > 0.2 - 3 * h) continue;
    on_linear = std::max(on_linear, std::abs(al2[i] - al0[i]) / (1000.0 * h));
    on_alternating = std::max(on_alternating, std::abs(az2[i] - az0[i]));
  }
  const double plain = rayleigh(az0, azb0), stabilised = rayleigh(az2, azb2);
  std::printf(
      "[ measured ] z.Az / z.Dz of the alternating rows: %.4f without, %.4f with kappa = 3; inside, the term on a "
      "linear field %.3g of that on the alternating one\n",
      plain, stabilised, on_linear / on_alternating);
  EXPECT_LT(std::abs(plain), 0.1);
  EXPECT_GT(stabilised, 1.0);
  EXPECT_LT(on_linear, 0.1 * on_alternating);  // an order of magnitude less
}

// Jacobi to a tight tolerance, then the system assembled from the operator's columns on
// the active set A = {i : p_i > 0} and solved by SparseLU: the same pressures.
TEST(PressureSystemJacobi, FixedPointMatchesSparseLUOnTheActiveSet) {
  Simulation sim = resting_block("zero");  // the fluid's pressures are the only unknowns
  sim.solver_settings().tolerance_percent = 1e-9;
  sim.solver_settings().max_iterations = 200000;
  SolverProbe probe(sim);
  probe.prepare_pressure_system(kDt);
  const std::vector<double> s = probe.source();
  const int iterations = probe.iterate_pressure();
  const std::vector<double> p_jacobi = sim.fluid().p;
  const Index n = sim.fluid().size();

  std::vector<Index> active;
  for (Index i = 0; i < n; ++i)
    if (p_jacobi[i] > 0) active.push_back(i);
  ASSERT_GT(active.size(), static_cast<size_t>(n / 2));

  // Columns of the operator (it is linear: A e_j with the zero field subtracted).
  const std::vector<double> none(static_cast<size_t>(sim.boundary().size()), 0.0);
  std::vector<double> zero(static_cast<size_t>(n), 0.0), ap0, ap, apb;
  probe.apply(zero, none, ap0, apb);
  const Index m = static_cast<Index>(active.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (Index c = 0; c < m; ++c) {
    std::vector<double> e = zero;
    e[active[c]] = 1.0;
    probe.apply(e, none, ap, apb);
    for (Index r = 0; r < m; ++r) {
      const double v = ap[active[r]] - ap0[active[r]];
      if (v != 0.0) entries.emplace_back(r, c, v);
    }
  }
  Eigen::SparseMatrix<double> a(m, m);
  a.setFromTriplets(entries.begin(), entries.end());
  Eigen::VectorXd rhs(m);
  for (Index r = 0; r < m; ++r) rhs[r] = s[active[r]] - ap0[active[r]];
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(a);
  ASSERT_EQ(lu.info(), Eigen::Success);
  const Eigen::VectorXd p_lu = lu.solve(rhs);

  double worst = 0, scale = 0;
  for (Index r = 0; r < m; ++r) {
    worst = std::max(worst, std::abs(p_lu[r] - p_jacobi[active[r]]));
    scale = std::max(scale, std::abs(p_lu[r]));
  }
  std::printf("[ measured ] %d iterations; %d of %d particles active; largest |p_Jacobi - p_LU| = %.3g Pa of %.3g\n",
              iterations, static_cast<int>(m), static_cast<int>(n), worst, scale);
  EXPECT_LT(worst, 1e-6 * scale);

  // The clamped rows: Eq. 21 keeps p_i = 0 only where the predicted density is not above
  // rest, (Ap)_i <= s_i (a_ii < 0).
  probe.apply(p_jacobi, none, ap, apb);
  for (Index i = 0; i < n; ++i) {
    if (p_jacobi[i] != 0) continue;
    EXPECT_LE(ap[i] - s[i], 1e-6 * std::abs(s[i]) + 1e-9) << "particle " << i;
  }
}

}  // namespace
}  // namespace sluice
