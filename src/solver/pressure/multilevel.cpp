// A two-level solve of the PPE (issue 37): Algorithm 2's relaxed Jacobi sweeps smooth the
// lattice-scale error, and a Galerkin coarse correction on cells of particles
// (coarse_level.cpp) removes the smooth, column-long error that the sweeps damp in a
// number of iterations growing with the depth. Aggregation by cells after Osaki et al.
// 2023; the Galerkin operator P^T A P as in algebraic multigrid for SPH (Trask et al. 2015).
#include <memory>

#include "solver/pressure/pressure_solver.h"
#include "solver/pressure/system.h"

namespace sluice {

namespace {

// A further correction every this many sweeps while the error is above the tolerance.
constexpr int kCorrectionEvery = 2;
// The tolerance bounds the average compression. In a splash, 4 iterations can leave a
// single squeezed particle 15-80 % compressed (Jacobi, with its many more sweeps, left
// none above 10 % in the same window), and its pressure then shoots it out: the 130k dam
// break went unstable at t = 2.26 s (docs/performance.md, "The multilevel solve past 2 s").
// Sweeps, which damp such local errors fast, go on while a particle is above this
// compression, at most kLocalSweeps more.
constexpr double kLocalBoundPercent = 5.0;
constexpr int kLocalSweeps = 10;
// A step that starts with a particle compressed past this is an impact. At CFL 1 a
// particle can pass its neighbours within a step, and the 130k dam break then starts
// steps 20-100 % compressed where the surge hits a wall or the lid, with either solver. The
// two-level solve turned such a compression into kinetic energy (+53 J/m in 0.07 s where
// Jacobi's solve from the same state took 234 J/m out; unstable at t = 2.97 s), so such a
// step takes Algorithm 2's sweeps alone (docs/performance.md, "Impacts at CFL 1"), and
// then the same local bound: warm-started from two-level solves, the sweeps meet the
// average in 3-5 iterations and left a particle 20 % compressed, step after step, where
// the surge ran up the wall (Wendland's C2: unstable at t = 0.688 s; docs/performance.md,
// "Impact steps under the local bound"). With solver.multilevel_impact_damping > 0 such a
// step takes the two-level solve with each correction scaled down instead ("Impacts with a
// damped correction").
constexpr double kImpactPercent = 5.0;
// A correction made on an iterate above the tolerance, after which the next sweep measures
// more than this many times the error before it, made the iterate worse: it is taken back,
// and the rest of the solve is sweeps alone. The rotor at spacing 0.02 (its spike tips
// sampled at 0.004 m, a fifth of the fluid's spacing) met such a state at t = 0.176 s: the
// first correction took the error from 0.123 to 4.62 %, each next one multiplied it by
// 12.7, until a particle left at 10^22 m. The first correction of a solve that is already
// within its tolerance is not judged: it may raise a tiny error several times (up to 7x at
// 0.005 % on the 130k dam break), and taking such corrections back made the shipped tank
// at tolerance 0.03 % take 42 iterations a step instead of 4.
constexpr double kDivergenceFactor = 2.0;

class MultilevelSolver final : public PressureSolverMethod {
 public:
  const char* name() const override { return "multilevel"; }
  double warm_start_factor() const override { return kJacobiWarmStartFactor; }

  PressureSolveResult iterate(PressureSystem& system, const PressureSolveLimits& limits) override {
    const double damping = system.settings().multilevel_impact_damping;
    PressureSolveResult r;
    if (system.largest_start_compression() < kImpactPercent)
      r = iterate_two_level(system, limits, 1.0);
    else
      r = damping > 0.0 ? iterate_two_level(system, limits, damping) : iterate_jacobi(system, limits);
    for (int extra = 0;
         extra < kLocalSweeps && r.iterations < limits.max_iterations && system.largest_error() > kLocalBoundPercent;
         ++extra) {
      r.avg_error_percent = system.sweep();
      ++r.iterations;
    }
    return r;
  }

 private:
  // The first sweep fixes the clamp (who is at p = 0 stays out of the coarse level for this
  // solve), then one coarse correction in every solve, even one already within the
  // tolerance: a smooth compression that stays under the tolerance step after step would
  // otherwise build up until a solve removes it at once and throws the fluid up (a 2 m
  // column went from 15 to 470 J/m in one step). Each correction counts as one iteration
  // (it applies A once), and a sweep always follows it, so the error returned is measured.
  // scale: each correction's share that is applied (1: all of it).
  // A correction that diverges (kDivergenceFactor) is taken back: the iterate before it
  // is kept aside, and put back when the sweep after it measures the divergence.
  static PressureSolveResult iterate_two_level(PressureSystem& system, const PressureSolveLimits& limits,
                                               double scale) {
    int l = 0, corrections = 0;
    double avg = 0.0, before = 0.0;
    bool corrected = false, coarse = true;
    do {
      avg = system.sweep();
      ++l;
      if (corrected && before > limits.tolerance_percent && avg > kDivergenceFactor * before) {
        system.restore_saved_iterate();
        avg = before;
        coarse = false;
      }
      corrected = false;
      if (coarse && (l == 1 || (avg > limits.tolerance_percent && (l - 1) % kCorrectionEvery == 0))) {
        if (l == 1) system.build_coarse_level();
        before = avg;
        system.save_previous_iterate();
        corrected = system.coarse_correction(scale);
        if (corrected) system.smooth_near_walls(system.settings().multilevel_wall_sweeps);
        corrections += corrected;
      }
    } while ((avg > limits.tolerance_percent || l < limits.min_iterations || corrected) &&
             l + corrections < limits.max_iterations);
    return {l + corrections, avg};
  }
};

}  // namespace

std::unique_ptr<PressureSolverMethod> make_multilevel_solver() { return std::make_unique<MultilevelSolver>(); }

}  // namespace sluice
