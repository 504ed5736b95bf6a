// Monaghan's (1994) elliptical drop: the exact ODE for the semi-axes, and the simulated
// drop (scenes/validation/elliptical_drop.json, shortened) against it for both solvers,
// as `sluice validate elliptical-drop` runs it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "analysis/elliptical_drop.h"
#include "scene/scene.h"

namespace sluice {
namespace {

using analysis::ellipse_semi_axes;

TEST(EllipticalDropOde, StartsAsTheCircle) {
  const auto e = ellipse_semi_axes(2.0, 0.7, 0.0);
  EXPECT_EQ(e.a, 0.7);
  EXPECT_EQ(e.b, 0.7);
  EXPECT_EQ(e.A, 2.0);
}

// Incompressibility (a b = R0^2) and the kinetic energy, A^2 (a^2 + b^2) = 2 A0^2 R0^2.
TEST(EllipticalDropOde, ConservesAreaAndEnergy) {
  for (double t : {0.1, 0.4, 1.0, 3.0}) {
    const auto e = ellipse_semi_axes(1.0, 1.0, t);
    EXPECT_NEAR(e.a * e.b, 1.0, 1e-9) << "t = " << t;
    EXPECT_NEAR(e.A * e.A * (e.a * e.a + e.b * e.b), 2.0, 1e-9) << "t = " << t;
    EXPECT_LT(e.a, 1.0);
    EXPECT_GT(e.b, 1.0);
  }
}

// Small t: A' = 0 and A'' = -2 A0^3 at t = 0, so A = A0 - A0^3 t^2 + O(t^3) and
// a = R0 exp(-A0 t + A0^3 t^3 / 3 + O(t^4)), b = R0^2 / a.
TEST(EllipticalDropOde, SmallTimeExpansion) {
  const double A0 = 1.5, R0 = 0.8;
  for (double t : {1e-3, 1e-2, 3e-2}) {
    const auto e = ellipse_semi_axes(A0, R0, t);
    const double s = A0 * t;
    EXPECT_NEAR(e.a, R0 * std::exp(-s + s * s * s / 3), 2 * R0 * s * s * s * s) << "t = " << t;
    EXPECT_NEAR(e.b, R0 * std::exp(s - s * s * s / 3), 2 * R0 * s * s * s * s) << "t = " << t;
    EXPECT_NEAR(e.A, A0 * (1 - s * s), 2 * A0 * s * s * s) << "t = " << t;
  }
}

// a / R0 depends on A0 t only; RK4 with the default step is converged.
TEST(EllipticalDropOde, ScalesAndConverges) {
  const auto e1 = ellipse_semi_axes(1.0, 1.0, 0.4);
  const auto e2 = ellipse_semi_axes(4.0, 2.5, 0.1);
  EXPECT_NEAR(e2.a / 2.5, e1.a, 1e-10);
  EXPECT_NEAR(e2.b / 2.5, e1.b, 1e-10);
  EXPECT_NEAR(e2.A / 4.0, e1.A, 1e-10);
  const auto coarse = ellipse_semi_axes(1.0, 1.0, 0.4, 40);
  EXPECT_NEAR(coarse.a, e1.a, 1e-9);
  EXPECT_NEAR(coarse.b, e1.b, 1e-9);
  // b / a reaches about 1.5 at t = 0.2 s and 2.5 at the validation's end time 0.5 s.
  const auto mid = ellipse_semi_axes(1.0, 1.0, 0.2);
  EXPECT_NEAR(mid.b / mid.a, 1.484, 1e-3);
  const auto end = ellipse_semi_axes(1.0, 1.0, 0.5);
  EXPECT_NEAR(end.b / end.a, 2.543, 1e-3);
}

const std::string kScene = std::string(SLUICE_SOURCE_DIR) + "/scenes/validation/elliptical_drop.json";

void check_drop(const analysis::EllipticalDropResult& r, const char* solver) {
  const auto& e = r.series.back();
  std::printf(
      "[ measured ] elliptical drop %s: h = %g, %ld particles, %ld steps, t = %.3f: a %.5f (ode %.5f, %.3f %%), "
      "b %.5f (ode %.5f, %.3f %%); largest error %.3f %% at t = %.2f s; %.1f s\n",
      solver, r.h, r.particles, r.steps, e.t, e.a_sim, e.a_ode, 100 * r.a_error, e.b_sim, e.b_ode, 100 * r.b_error,
      100 * r.error, r.error_t, r.wall_seconds);
  ASSERT_GE(r.series.size(), 2u);
  EXPECT_EQ(r.series.front().t, 0.0);
  EXPECT_NEAR(r.series.front().a_sim, r.R0, 1e-12);
  EXPECT_NEAR(r.series.front().b_sim, r.R0, 1e-12);
  // The axes stay on x and y (the set-up is symmetric about both).
  EXPECT_LT(std::abs(e.xy_moment), 1e-3);
  // The bound holds at every frame, not only at the end.
  EXPECT_LE(r.error, analysis::kEllipticalDropBound);
  for (const auto& p : r.series) {
    EXPECT_LE(std::abs(p.a_sim - p.a_ode) / p.a_ode, r.error) << "t = " << p.t;
    EXPECT_LE(std::abs(p.b_sim - p.b_ode) / p.b_ode, r.error) << "t = " << p.t;
  }
}

// The drop as `validate elliptical-drop` runs it, with `set` on top of the shipped scene.
analysis::EllipticalDropResult run_drop(std::vector<std::string> set, const std::string& solver) {
  const double A0 = analysis::kEllipticalDropA0;
  set.push_back("solver.type=" + solver);
  if (solver == "wcsph") {
    const auto w =
        analysis::elliptical_drop_wcsph_overrides(load_scene(kScene, set, analysis::elliptical_drop_velocity(A0)), A0);
    set.insert(set.end(), w.begin(), w.end());
  }
  return analysis::run_elliptical_drop(load_scene(kScene, set, analysis::elliptical_drop_velocity(A0)), A0);
}

// The target: 1 % at every frame up to b/a = 2.54 (t = 0.5 s), the validate
// command's drop as shipped (h = 0.025, 5024 particles, the cubic spline on a support of
// 3 spacings). Measured: IISPH 0.37 %, WCSPH 0.54 % (at h = 0.0125: 0.35 %, 0.51 %).
TEST(EllipticalDrop, IisphToAspectRatio2p5) { check_drop(run_drop({}, "iisph"), "iisph"); }
TEST(EllipticalDrop, WcsphToAspectRatio2p5) { check_drop(run_drop({}, "wcsph"), "wcsph"); }

// The thesis' support (2 spacings) holds 1 % up to b/a = 1.48 (t = 0.2 s), here on a
// coarser drop (h = 0.05, 1264 particles). Measured: IISPH 0.54 %, WCSPH 0.48 %. Past
// that the stretched lattice's kernel sum reads high and the drop's area grows by as much
// (7 % at b/a = 2.54, docs/validation.md): why the drop's scene asks for 3 spacings.
const std::vector<std::string> kShort{"spacing=0.05", "solver.support=2", "time.duration=0.2"};

TEST(EllipticalDrop, ThesisSupportIisph) { check_drop(run_drop(kShort, "iisph"), "iisph"); }
TEST(EllipticalDrop, ThesisSupportWcsph) { check_drop(run_drop(kShort, "wcsph"), "wcsph"); }

// The drop's motion is part of the scene it is loaded as (elliptical_drop_velocity), so
// that WCSPH's default stiffness sees it: k = rho0 (20 v0)^2 with v0 the rim's A0 R0
// (solver/setup.h). Loaded without it, the drop has neither gravity nor motion and WCSPH
// has no default (what `validate elliptical-drop` stopped on).
TEST(EllipticalDrop, WcsphDefaultStiffnessSeesTheDropsMotion) {
  std::vector<std::string> set = kShort;
  set.push_back("solver.type=wcsph");
  EXPECT_THROW(load_scene(kScene, set), SceneError);
  const Scene s = load_scene(kScene, set, analysis::elliptical_drop_velocity(analysis::kEllipticalDropA0));
  double v0 = 0;
  for (const Vec2& v : s.fluid_v) v0 = std::max(v0, v.norm());
  EXPECT_GT(v0, 0.9);
  EXPECT_LE(v0, 1.0);
  EXPECT_DOUBLE_EQ(s.solver.stiffness, s.solver.rest_density * (20 * v0) * (20 * v0));
  // The same field the run starts from: the scene's velocities are kept as they are.
  const Scene plain = load_scene(kScene, kShort);
  Scene replaced = plain;
  analysis::elliptical_drop_velocity(analysis::kEllipticalDropA0)(replaced.fluid_x, replaced.fluid_v);
  ASSERT_EQ(replaced.fluid_v.size(), s.fluid_v.size());
  for (std::size_t i = 0; i < s.fluid_v.size(); ++i) EXPECT_EQ(replaced.fluid_v[i], s.fluid_v[i]) << i;
}

TEST(EllipticalDrop, RefusesANonPositiveStrainRate) {
  EXPECT_THROW(analysis::run_elliptical_drop(load_scene(kScene, kShort), 0.0), SceneError);
}

}  // namespace
}  // namespace sluice
