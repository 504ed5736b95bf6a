#include "analysis/elliptical_drop.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "solver/simulation.h"

namespace sluice::analysis {

// The ODE (Monaghan 1994, section 5, re-derived here). For the linear velocity field
// u = -A(t) x, v = A(t) y (divergence free), a material ellipse x^2/a^2 + y^2/b^2 = 1
// stays an ellipse with
//   da/dt = -A a,  db/dt = A b   (so a b = R0^2).
// Its accelerations are Du/Dt = du/dt + u du/dx = (A^2 - A') x and
// Dv/Dt = (A^2 + A') y. Try the pressure p = p0(t) (1 - x^2/a^2 - y^2/b^2), zero on the
// surface; Euler's equations Du/Dt = -(1/rho) dp/dx, Dv/Dt = -(1/rho) dp/dy give
//   A^2 - A' = 2 p0 / (rho a^2),   A^2 + A' = 2 p0 / (rho b^2),
// and eliminating p0: (A^2 - A') a^2 = (A^2 + A') b^2, i.e.
//   dA/dt = A^2 (a^2 - b^2) / (a^2 + b^2).
// At t = 0 (a = b) A' = 0 and p0 = rho A0^2 R0^2 / 2; then a < b and A decays. The kinetic
// energy (rho/8) pi a b A^2 (a^2 + b^2) is conserved (the pressure does no work at the
// free surface), which the derivative of A^2 (a^2 + b^2) confirms: 2 A^3 (a^2 - b^2) +
// A^2 (-2 A a^2 + 2 A b^2) = 0.
EllipseAxes ellipse_semi_axes(double A0, double R0, double t, long steps) {
  EllipseAxes s{R0, R0, A0};
  if (t <= 0) return s;
  if (steps <= 0) steps = std::max(100L, static_cast<long>(std::ceil(t * std::abs(A0) / 1e-4)));
  const double dt = t / static_cast<double>(steps);
  auto f = [](const EllipseAxes& e) {
    const double a2 = e.a * e.a, b2 = e.b * e.b;
    return EllipseAxes{-e.A * e.a, e.A * e.b, e.A * e.A * (a2 - b2) / (a2 + b2)};
  };
  auto add = [](const EllipseAxes& e, double w, const EllipseAxes& d) {
    return EllipseAxes{e.a + w * d.a, e.b + w * d.b, e.A + w * d.A};
  };
  for (long i = 0; i < steps; ++i) {
    const EllipseAxes k1 = f(s), k2 = f(add(s, 0.5 * dt, k1)), k3 = f(add(s, 0.5 * dt, k2)), k4 = f(add(s, dt, k3));
    s.a += dt / 6 * (k1.a + 2 * k2.a + 2 * k3.a + k4.a);
    s.b += dt / 6 * (k1.b + 2 * k2.b + 2 * k3.b + k4.b);
    s.A += dt / 6 * (k1.A + 2 * k2.A + 2 * k3.A + k4.A);
  }
  return s;
}

double ellipse_max_speed(double A0, double R0, double t_end) {
  double v = A0 * R0;
  const int samples = 200;
  for (int i = 1; i <= samples; ++i) {
    const EllipseAxes e = ellipse_semi_axes(A0, R0, t_end * i / samples);
    v = std::max(v, std::abs(e.A) * std::max(e.a, e.b));
  }
  return v;
}

std::vector<std::string> elliptical_drop_wcsph_overrides(const Scene& scene, double A0) {
  const double R0 = std::sqrt(static_cast<double>(scene.fluid_x.size()) / M_PI) * scene.spacing;
  const double c = 10 * ellipse_max_speed(A0, R0, scene.time.duration);
  const double k = scene.solver.rest_density * c * c;
  const double frame = 1 / scene.time.fps;
  const double dt = frame / std::ceil(frame / (0.4 * scene.spacing / c));
  auto full = [](double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.17g", x);
    return std::string(buf);
  };
  return {"solver.type=wcsph", "solver.stiffness=" + full(k), "time.cfl=null", "time.dt=" + full(dt)};
}

namespace {

struct Moments {
  Vec2 centroid{0, 0};
  double xx = 0, yy = 0, xy = 0;  // central second moments (means) [m^2]
};

Moments moments(const std::vector<Vec2>& x) {
  Moments m;
  for (const Vec2& p : x) m.centroid += p;
  m.centroid /= static_cast<double>(x.size());
  for (const Vec2& p : x) {
    const Vec2 d = p - m.centroid;
    m.xx += d.x() * d.x();
    m.yy += d.y() * d.y();
    m.xy += d.x() * d.y();
  }
  const double n = static_cast<double>(x.size());
  m.xx /= n;
  m.yy /= n;
  m.xy /= n;
  return m;
}

}  // namespace

InitialVelocity elliptical_drop_velocity(double A0) {
  return [A0](const std::vector<Vec2>& x, std::vector<Vec2>& v) {
    if (x.empty()) return;
    const Vec2 c = moments(x).centroid;
    v.resize(x.size());
    for (std::size_t i = 0; i < x.size(); ++i) {
      const Vec2 d = x[i] - c;
      v[i] = Vec2(-A0 * d.x(), A0 * d.y());
    }
  };
}

EllipticalDropResult run_elliptical_drop(const Scene& scene, double A0) {
  if (scene.fluid_x.empty()) throw SceneError(scene.file + ": /fluid: the elliptical drop needs a fluid drop");
  if (!(A0 > 0))
    throw SceneError(scene.file + ": the elliptical drop needs a strain rate A0 > 0, got " + std::to_string(A0));
  EllipticalDropResult r;
  r.A0 = A0;
  r.h = scene.spacing;
  r.particles = static_cast<long>(scene.fluid_x.size());
  // Each particle fills an h x h cell: the drop's area is N h^2.
  r.R0 = std::sqrt(static_cast<double>(r.particles) * r.h * r.h / M_PI);

  // The initial field, whatever the scene was loaded with (the solver reads Scene::fluid_v).
  Scene s = scene;
  elliptical_drop_velocity(A0)(s.fluid_x, s.fluid_v);
  const Moments m0 = moments(s.fluid_x);

  // Semi-axes from the second moments. A uniformly filled ellipse has <x^2> = a^2/4, but
  // the lattice disc's <x^2> differs from R0^2/4 by the cells' own h^2/12 and the stair-
  // stepped rim. The exact solution maps every material point linearly, x -> (a/R0) x,
  // y -> (b/R0) y, so <x^2>(t) / <x^2>(0) = (a/R0)^2 holds for the particles themselves
  // whatever the fill: a_sim = R0 sqrt(<x^2>(t) / <x^2>(0)) compares like with like. The
  // moments average all particles, so a few ragged surface particles barely move them
  // (unlike the extreme extents).
  auto sample = [&](double t, const std::vector<Vec2>& x) {
    const Moments m = moments(x);
    const EllipseAxes e = ellipse_semi_axes(A0, r.R0, t);
    EllipseSample es;
    es.t = t;
    es.a_sim = r.R0 * std::sqrt(m.xx / m0.xx);
    es.b_sim = r.R0 * std::sqrt(m.yy / m0.yy);
    es.a_ode = e.a;
    es.b_ode = e.b;
    es.xy_moment = m.xy / std::sqrt(m.xx * m.yy);
    r.series.push_back(es);
  };

  const auto t0 = std::chrono::steady_clock::now();
  Simulation sim(s);
  sample(0, sim.fluid().x);
  double iterations = 0;
  while (!sim.finished()) {
    const StepStats st = sim.step();
    ++r.steps;
    iterations += st.iterations;
    if (st.frame >= 0) sample(sim.time(), sim.fluid().x);
  }
  if (r.series.back().t < sim.time()) sample(sim.time(), sim.fluid().x);
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.avg_iterations = r.steps ? iterations / static_cast<double>(r.steps) : 0;
  for (const Vec2& v : sim.fluid().v) r.max_speed_end = std::max(r.max_speed_end, v.norm());

  const EllipseSample& end = r.series.back();
  r.a_error = std::abs(end.a_sim - end.a_ode) / end.a_ode;
  r.b_error = std::abs(end.b_sim - end.b_ode) / end.b_ode;
  for (const EllipseSample& e : r.series) {
    if (e.error() > r.error) {
      r.error = e.error();
      r.error_t = e.t;
    }
  }
  return r;
}

}  // namespace sluice::analysis
