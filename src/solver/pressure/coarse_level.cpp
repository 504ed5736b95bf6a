// The coarse level of the multilevel pressure solve (multilevel.cpp): the unknowns of the
// PPE aggregated by cells, the Galerkin operator P^T A P over them, and the correction it
// gives. Serial or in fixed chunks: the same bits for any thread count.
#include "solver/pressure/coarse_level.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <utility>

#include "core/check.h"
#include "core/parallel.h"
#include "solver/internal.h"
#include "solver/pressure_kernels.h"
#include "solver/simulation.h"

namespace sluice {

namespace {
// A particle's acceleration (Eq. 24) and its (Ap) contributions as functions of the
// aggregates' pressures, per distinct aggregate: g_iJ, and h_iJ / (dt m) less the
// particle's own term. Both come from the same pairs, so they share the aggregates.
struct AggregateTerms {
  static constexpr int kMax = 24;
  Index id[kMax];
  Vec2 g[kMax], h[kMax];
  int size = 0, last = 0;
  void reset(Index own) {
    size = 0;
    last = 0;
    if (own >= 0) {
      id[0] = own;
      g[0] = h[0] = Vec2::Zero();
      size = 1;
    }
  }
  void add(Index a, const Vec2& gv, const Vec2& hv) {
    if (a < 0) return;
    if (size > 0 && id[last] == a) {  // neighbours come in index order, mostly cell by cell
      g[last] += gv;
      h[last] += hv;
      return;
    }
    for (int k = 0; k < size; ++k)
      if (id[k] == a) {
        g[k] += gv;
        h[k] += hv;
        last = k;
        return;
      }
    // Cells of at least 2 spacings (the key's range): a support spans at most 3 x 3 cells.
    SLUICE_ASSERT(size < kMax, "a particle touches at most 9 aggregates");
    id[size] = a;
    g[size] = gv;
    h[size] = hv;
    last = size++;
  }
};

// An aggregate keeps its place on the coarse level only where the fluid is not sparse: at
// least a full cell's worth of fluid particles in its own and the 8 adjacent cells. A few
// particles alone (spray, a splash against the lid) with their wall samples make a nearly
// decoupled block whose constant correction, solved exactly, throws them off the wall (the
// 130k dam break: a particle that hit the lid at 11.8 m/s left it at 32 m/s); the sweeps
// alone settle such local errors, and the column-long modes live where the fluid is full.
// Samples' own cells (fluid-free below a floor) stay beside the fluid above them.
void drop_sparse_aggregates(CoarseLevel& cl, Index count, Index fluid, double cell) {
  const Index min_fluid = static_cast<Index>(std::floor(cell * cell));
  std::vector<Index>& members = cl.members;  // kept between solves: no allocation per step
  std::vector<Index>& renumber = cl.renumber;
  members.assign(static_cast<size_t>(count), 0);
  renumber.assign(static_cast<size_t>(count), -1);
  for (Index u = 0; u < fluid; ++u)
    if (cl.aggregate[u] >= 0) ++members[static_cast<size_t>(cl.aggregate[u])];
  Index kept = 0;
  for (Index a = 0; a < count; ++a) {
    Index near = 0;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) {
        const long x = long{cl.cell_x[static_cast<size_t>(a)]} + dx, y = long{cl.cell_y[static_cast<size_t>(a)]} + dy;
        if (x < 0 || y < 0 || x >= cl.nx || y >= cl.ny) continue;
        const Index b = cl.cell_aggregate[static_cast<size_t>(y * cl.nx + x)];
        if (b >= 0) near += members[static_cast<size_t>(b)];
      }
    if (near < min_fluid) continue;
    renumber[static_cast<size_t>(a)] = kept;
    cl.cell_x[static_cast<size_t>(kept)] = cl.cell_x[static_cast<size_t>(a)];
    cl.cell_y[static_cast<size_t>(kept)] = cl.cell_y[static_cast<size_t>(a)];
    ++kept;
  }
  cl.cell_x.resize(static_cast<size_t>(kept));
  cl.cell_y.resize(static_cast<size_t>(kept));
  for (long c = 0; c < cl.nx * cl.ny; ++c) {  // the table has headroom past nx * ny (all -1)
    Index& a = cl.cell_aggregate[static_cast<size_t>(c)];
    if (a >= 0) a = renumber[static_cast<size_t>(a)];
  }
  for (Index& a : cl.aggregate)
    if (a >= 0) a = renumber[static_cast<size_t>(a)];
  cl.aggregates = kept;
}

}  // namespace

// Aggregates: the unknowns with p > 0 at the call (after the solve's first sweep) among the
// fluid and the samples of pressure boundaries that have a row, grouped by square cells of
// solver.multilevel_cell spacings, numbered in order of first appearance. The unknowns
// clamped at zero (the free surface) stay out for the rest of the solve, and so do the
// cells where the fluid is sparse (drop_sparse_aggregates).
void Simulation::aggregate_unknowns(CoarseLevel& cl) const {
  const Index n = fluid_.size(), nb = boundary_.size(), nu = n + nb;
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  const double inv_cell = 1.0 / (settings_.multilevel_cell * setup_.spacing);
  constexpr std::int32_t kOut = std::numeric_limits<std::int32_t>::min();
  cl.aggregate.assign(static_cast<size_t>(nu), -1);
  cl.unknown_x.resize(static_cast<size_t>(nu));
  cl.unknown_y.resize(static_cast<size_t>(nu));
  // Each unknown's cell, in parallel; the numbering below is serial (order of appearance).
  parallel_for(nu, [&](Index u) {
    const bool active =
        u < n ? fluid_.p[u] > 0.0 : samples && scratch_->bnd_aii[u - n] != 0.0 && boundary_.p[u - n] > 0.0;
    if (!active) {
      cl.unknown_x[u] = kOut;
      return;
    }
    const Vec2 x = u < n ? fluid_.x[u] : boundary_.x[u - n];
    cl.unknown_x[u] = static_cast<std::int32_t>(std::floor(x.x() * inv_cell));
    cl.unknown_y[u] = static_cast<std::int32_t>(std::floor(x.y() * inv_cell));
  });
  std::int32_t x0 = std::numeric_limits<std::int32_t>::max(), y0 = x0, x1 = kOut, y1 = kOut;
  for (Index u = 0; u < nu; ++u) {
    if (cl.unknown_x[u] == kOut) continue;
    x0 = std::min(x0, cl.unknown_x[u]), x1 = std::max(x1, cl.unknown_x[u]);
    y0 = std::min(y0, cl.unknown_y[u]), y1 = std::max(y1, cl.unknown_y[u]);
  }
  const long nx = x1 >= x0 ? long{x1} - x0 + 1 : 0, ny = y1 >= y0 ? long{y1} - y0 + 1 : 0;
  cl.nx = nx;
  cl.ny = ny;
  // With headroom, as the neighbour lists' pairs (resize_pairs): a table that grows each
  // step as the fluid spreads would be allocated and faulted in again each time.
  resize_pairs(cl.cell_aggregate, static_cast<size_t>(nx * ny));
  std::fill(cl.cell_aggregate.begin(), cl.cell_aggregate.end(), -1);
  cl.cell_x.clear();
  cl.cell_y.clear();
  Index count = 0;
  for (Index u = 0; u < nu; ++u) {
    if (cl.unknown_x[u] == kOut) continue;
    const std::int32_t cx = cl.unknown_x[u] - x0, cy = cl.unknown_y[u] - y0;
    Index& a = cl.cell_aggregate[static_cast<size_t>(cy * nx + cx)];
    if (a < 0) {
      a = count++;
      cl.cell_x.push_back(cx);
      cl.cell_y.push_back(cy);
    }
    cl.aggregate[u] = a;
  }
  drop_sparse_aggregates(cl, count, n, settings_.multilevel_cell);
}

// A_c = P^T A P for P the aggregates' indicator. With A = D G (G: the unknowns to the
// accelerations of Eq. 24; D: the accelerations to (Ap) of Eq. 20 and the samples' rows),
//   A_c[I][J] = sum_i h_iI . g_iJ,
// g_iJ = d a_i / d p_J and h_iI = d (sum_{u in I} (Ap)_u) / d a_i, both from particle i's
// own pairs: a_i enters its own row and, through the pair's antisymmetric gradient, the
// rows of its fluid neighbours and of its samples. I and J lie within one support of i,
// so within kReach cells of each other. Chunks of particles set by n alone (up to 8, for
// load balance without a table per 2048 particles), each summed in index order into its
// own table, added in chunk order: the same bits for any thread count.
void Simulation::assemble_coarse_operator(const PressureTerms& t, CoarseLevel& cl) const {
  constexpr int kReach = 2, kSide = 2 * kReach + 1, kSlots = kSide * kSide;
  constexpr Index kMinChunk = 2048, kMaxChunks = 8;
  const Index n = fluid_.size(), na = cl.aggregates;
  const Index chunks = std::clamp<Index>((n + kMinChunk - 1) / kMinChunk, 1, kMaxChunks);
  const Index chunk = (n + chunks - 1) / chunks;
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  const double m = mass_, dt = t.dt, g3_rho0 = t.gamma3_rho0 / (settings_.rest_density * settings_.rest_density);
  const std::vector<Index>& agg = cl.aggregate;
  resize_pairs(cl.partial, static_cast<size_t>(chunks * na * kSlots));
  std::fill(cl.partial.begin(), cl.partial.end(), 0.0);
  // g_iJ's neighbour coefficient once per particle rather than once per pair (one division).
  std::vector<double>& coef = cl.neg_m_over_rho2;
  coef.resize(static_cast<size_t>(n));
  parallel_for(n, [&](Index f) { coef[f] = -m / (fluid_.rho[f] * fluid_.rho[f]); });

  // The stabilisation's terms (pressure_kernels.h), which the sweeps invert with A: for a
  // band row i, d/dp_J of kappa a_ii rho_i^2 (q_i - q_bar_i), q = p / rho^2 and q_bar_i the
  // neighbours' mean plus a_i . x_bar_i / rho_i; for a sample row b, of kappa_s a_bb rho0^2
  // (q_b - mean_f (q_f - a_f . (x_b - x_f) / rho_f)). The q parts are entries of their own
  // (put); the a parts enter through g_iJ as h does. Left out, a correction overshot where
  // A + kappa S is stiffer (docs/performance.md, "The stabilisation in the coarse operator").
  const bool stabilised = t.stabilisation > 0.0;
  const double rho0 = settings_.rest_density, inv_rho0_2 = 1.0 / (rho0 * rho0);
  auto put = [&](double* table, Index row, Index col, double v) {
    const int dx = cl.cell_x[col] - cl.cell_x[row] + kReach, dy = cl.cell_y[col] - cl.cell_y[row] + kReach;
    SLUICE_ASSERT(dx >= 0 && dx < kSide && dy >= 0 && dy < kSide, "coupled aggregates lie within kReach cells");
    table[row * kSlots + dy * kSide + dx] += v;
  };
  // Particle i's share: its own row's term if it is in the band, and what its q and a_i
  // give the rows of its samples.
  auto add_stabilisation = [&](Index i, AggregateTerms& at, double* table) {
    const Index own = agg[i];
    const double rho_i = fluid_.rho[i];
    const Index count = ff_.count(i) + (t.boundary_field ? fb_.count(i) : 0);
    if (own >= 0 && scratch_->stab_on[i] && count > 0) {
      const double k = t.stabilisation * scratch_->a_ii[i];
      const double k_mean = k * rho_i * rho_i / static_cast<double>(count);
      put(table, own, own, k);
      for (Index e = ff_.offset[i]; e < ff_.offset[i + 1]; ++e) {
        const Index f = ff_.j[e];
        if (agg[f] >= 0) put(table, own, agg[f], -k_mean / (fluid_.rho[f] * fluid_.rho[f]));
      }
      if (samples)
        for (Index e = fb_.offset[i]; e < fb_.offset[i + 1]; ++e)
          if (agg[n + fb_.j[e]] >= 0) put(table, own, agg[n + fb_.j[e]], -k_mean * inv_rho0_2);
      at.h[0] += (-k * rho_i) * scratch_->stab_offset[i];
    }
    if (!samples) return;
    for (Index e = fb_.offset[i]; e < fb_.offset[i + 1]; ++e) {
      const Index b = fb_.j[e], row = agg[n + b];
      if (row < 0 || scratch_->bnd_aii[b] == 0.0) continue;
      const double kb = kSampleStabilisation * t.stabilisation * scratch_->bnd_aii[b];
      const double ks = kb * rho0 * rho0 / static_cast<double>(bf_.count(b));
      if (bf_.j[bf_.offset[b]] == i) put(table, row, row, kb);  // once per sample, from its first neighbour
      if (own >= 0) put(table, row, own, -ks / (rho_i * rho_i));
      at.add(row, Vec2::Zero(), (ks / rho_i) * (boundary_.x[b] - fluid_.x[i]));
    }
  };

#pragma omp parallel for schedule(dynamic, 1) if (n >= kParallelMin)
  for (Index c = 0; c < chunks; ++c) {
    double* table = cl.partial.data() + c * na * kSlots;
    AggregateTerms at;
    for (Index i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
      at.reset(agg[i]);
      const double inv2 = 1.0 / (fluid_.rho[i] * fluid_.rho[i]);
      Vec2 sum = Vec2::Zero();
      for (Index k = ff_.offset[i]; k < ff_.offset[i + 1]; ++k) {
        const Index f = ff_.j[k];
        const Vec2 gw = ff_.grad[k].cast<double>();
        sum += gw;
        at.add(agg[f], coef[f] * gw, gw);
      }
      if (samples)
        for (Index k = fb_.offset[i]; k < fb_.offset[i + 1]; ++k) {
          const Index b = fb_.j[k];
          const Vec2 gw = fb_.grad[k].cast<double>();
          at.add(agg[n + b], -(g3_rho0 * boundary_.volume[b]) * gw, gw);
        }
      for (int a = 0; a < at.size; ++a) at.h[a] *= dt * m;
      if (agg[i] >= 0) {  // slot 0: the particle's own terms
        at.g[0] += -inv2 * (m * sum + t.c_gamma3 * scratch_->grad_b[i]);
        at.h[0] += dt * (m * sum + t.gamma2 * scratch_->grad_b[i]);
      }
      if (stabilised) add_stabilisation(i, at, table);
      if (at.size == 1) {  // inside a cell
        table[at.id[0] * kSlots + kSlots / 2] += at.h[0].dot(at.g[0]);
        continue;
      }
      int cx[AggregateTerms::kMax], cy[AggregateTerms::kMax];
      for (int a = 0; a < at.size; ++a) cx[a] = cl.cell_x[at.id[a]], cy[a] = cl.cell_y[at.id[a]];
      for (int a = 0; a < at.size; ++a) {
        double* row = table + at.id[a] * kSlots;
        for (int b = 0; b < at.size; ++b) {
          const int dx = cx[b] - cx[a] + kReach, dy = cy[b] - cy[a] + kReach;
          SLUICE_ASSERT(dx >= 0 && dx < kSide && dy >= 0 && dy < kSide, "coupled aggregates lie within kReach cells");
          row[dy * kSide + dx] += at.h[a].dot(at.g[b]);
        }
      }
    }
  }
  // Each row's slots summed over the chunks in order (rows in parallel), then A_c filled
  // row by row with its columns sorted.
  resize_pairs(cl.slot_sum, static_cast<size_t>(na * kSlots));
  cl.row_start.assign(static_cast<size_t>(na) + 1, 0);
  std::vector<double>& sum = cl.slot_sum;
  std::vector<int>& start = cl.row_start;
  std::vector<std::uint8_t>& entry = cl.slot_entry;  // a slot is an entry when any chunk touched it
  resize_pairs(entry, static_cast<size_t>(na * kSlots));
  parallel_for(na, [&](Index r) {
    int count = 0;
    for (int k = 0; k < kSlots; ++k) {
      double v = 0.0;
      bool any = false;
      for (Index c = 0; c < chunks; ++c) {
        const double x = cl.partial[static_cast<size_t>((c * na + r) * kSlots + k)];
        v += x;
        any = any || x != 0.0;
      }
      sum[static_cast<size_t>(r * kSlots + k)] = v;
      entry[static_cast<size_t>(r * kSlots + k)] = any;
      count += any;
    }
    start[static_cast<size_t>(r) + 1] = count;
  });
  for (Index r = 0; r < na; ++r) start[static_cast<size_t>(r) + 1] += start[static_cast<size_t>(r)];
  cl.a_c.resize(na, na);
  cl.a_c.resizeNonZeros(start[static_cast<size_t>(na)]);
  std::copy(start.begin(), start.end(), cl.a_c.outerIndexPtr());
  int* column = cl.a_c.innerIndexPtr();
  double* value = cl.a_c.valuePtr();
  parallel_for(na, [&](Index r) {
    int e = start[static_cast<size_t>(r)];
    for (int k = 0; k < kSlots; ++k) {
      if (!entry[static_cast<size_t>(r * kSlots + k)]) continue;
      const double v = sum[static_cast<size_t>(r * kSlots + k)];
      const long cx = cl.cell_x[r] + k % kSide - kReach, cy = cl.cell_y[r] + k / kSide - kReach;
      const int col = cl.cell_aggregate[static_cast<size_t>(cy * cl.nx + cx)];
      int at = e++;  // insertion by column
      for (; at > start[static_cast<size_t>(r)] && column[at - 1] > col; --at) {
        column[at] = column[at - 1];
        value[at] = value[at - 1];
      }
      column[at] = col;
      value[at] = v;
    }
  });
}

// The coarse level of this solve: aggregates, P^T A P, and its symmetric part. A_c is
// symmetric up to the rows' densities (A = D G with D = -dt rho_i^2 G^T for the fluid's
// rows) and the stabilisation's terms, so the LDL^T factors of -(A_c + A_c^T) / 2
// precondition BiCGSTAB on A_c itself (coarse_correction). One step of refinement against
// A_c, enough before the stabilisation joined A_c, left the cubic spline's deep column
// unstable at kappa = 2; Eigen's SparseLU of A_c cost 15 ms a solve on the 130k dam break
// (docs/performance.md, "The stabilisation in the coarse operator").
void Simulation::build_coarse_level(const PressureTerms& t) {
  if (settings_.boundary_pressure == BoundaryPressure::Extrapolation)
    throw std::invalid_argument(
        "solver.pressure_solver \"multilevel\" needs boundary_pressure solved, mirroring or zero (Eq. 25 is not "
        "in its coarse operator)");
  if (!scratch_->coarse) scratch_->coarse = std::make_shared<CoarseLevel>();
  CoarseLevel& cl = *scratch_->coarse;
  aggregate_unknowns(cl);
  assemble_coarse_operator(t, cl);
  // The row-major A_c's storage is A_c^T's column-major one.
  const CoarseLevel::Matrix a_t = cl.a_c.transpose(), a = cl.a_c;
  cl.symmetric = -0.5 * (a_t + a);
  cl.factorised = false;
  cl.factor_pending = cl.aggregates > 0;  // factorised by the first correction, beside its residual
}

// One coarse correction: r = s - A x (Eq. 19, 20 and the samples' rows, from the current
// pressures), then x_u += scale (A_c^-1 P^T r)_{I(u)} on the aggregated unknowns, clamped at zero
// as in Eq. 21. Costs one application of A. The first correction of a solve also
// factorises A_c's symmetric part: Eigen's factorisation is serial, so one thread takes it
// while the others start on the residual's two passes, and joins them when it is done
// (neither depends on the other; each value is computed the same way by any thread).
// Returns false (and changes nothing) when the coarse operator could not be factorised or
// its solve did not converge.
bool Simulation::coarse_correction(const PressureTerms& t, double scale) {
  constexpr double kCoarseTolerance = 1e-6;
  constexpr int kCoarseIterations = 50;
  CoarseLevel& cl = *scratch_->coarse;
  if (cl.aggregates == 0) return false;
  const Index n = fluid_.size(), nb = boundary_.size();
  const bool samples = settings_.boundary_pressure == BoundaryPressure::Solved;
  update_boundary_pressure();
  // As compute_pressure_acceleration, with the stabilisation's means for the residual.
  PressureTerms t_acc = pressure_terms(0.0);
  t_acc.stabilisation = t.stabilisation;
  std::vector<Vec2>& acc = scratch_->a_p;
  acc.resize(static_cast<size_t>(n));
  std::vector<double>& r = cl.residual;
  r.resize(static_cast<size_t>(n));
  constexpr Index kResidualGrain = 4096;  // particles per task: a few dozen tasks per pass
  const bool factorise = cl.factor_pending;
  cl.factor_pending = false;
#pragma omp parallel if (n >= kParallelMin)
#pragma omp single
  {
    if (factorise) {
#pragma omp task
      {
        cl.ldlt.compute(cl.symmetric);
        cl.factorised = cl.ldlt.info() == Eigen::Success;
      }
    }
#pragma omp taskloop grainsize(kResidualGrain)
    for (Index i = 0; i < n; ++i) acc[i] = pressure_acceleration_of(i, t_acc);
#pragma omp taskloop grainsize(kResidualGrain)
    for (Index i = 0; i < n; ++i)
      r[i] = scratch_->s[i] - pressure_operator_of(i, t) - (stabilised_row(i, t) ? stabilisation_of(i, t) : 0.0);
  }
  if (!cl.factorised) return false;
  cl.rc = Eigen::VectorXd::Zero(cl.aggregates);
  for (Index i = 0; i < n; ++i)
    if (cl.aggregate[i] >= 0) cl.rc[cl.aggregate[i]] += r[i];
  if (samples)
    for (Index b = 0; b < nb; ++b)
      if (cl.aggregate[n + b] >= 0)
        cl.rc[cl.aggregate[n + b]] += scratch_->bnd_s[b] - sample_operator_of(b, t) -
                                      (t.stabilisation > 0.0 ? sample_stabilisation_of(b, t) : 0.0);
  // A relative residual of 1e-6: 8.6 iterations on average in the 130k dam break's first
  // 0.05 s, at most 11; the shipped tank and the deep columns read as with an exact LU.
  cl.bicgstab.preconditioner().ldlt = &cl.ldlt;
  cl.bicgstab.setTolerance(kCoarseTolerance);
  cl.bicgstab.setMaxIterations(kCoarseIterations);
  cl.bicgstab.compute(cl.a_c);
  cl.ec = cl.bicgstab.solve(cl.rc);
  if (cl.bicgstab.info() != Eigen::Success) return false;
  if (scale != 1.0) cl.ec *= scale;
  const double inv_rho0_2 = 1.0 / (settings_.rest_density * settings_.rest_density);
  parallel_for(n, [&](Index i) {
    if (cl.aggregate[i] < 0) return;
    const double p = std::max(fluid_.p[i] + cl.ec[cl.aggregate[i]], 0.0);
    fluid_.p[i] = p;
    scratch_->p_over_rho2[i] = p / (fluid_.rho[i] * fluid_.rho[i]);
  });
  if (samples)
    parallel_for(nb, [&](Index b) {
      if (cl.aggregate[n + b] < 0) return;
      const double p = std::max(boundary_.p[b] + cl.ec[cl.aggregate[n + b]], 0.0);
      boundary_.p[b] = p;
      scratch_->pb_over_rho2[b] = p * inv_rho0_2;
    });
  return true;
}

}  // namespace sluice
