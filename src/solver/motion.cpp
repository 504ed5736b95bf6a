#include "solver/motion.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace sluice {

namespace {

Vec2 rotate(double angle, const Vec2& x) {
  const double c = std::cos(angle), s = std::sin(angle);
  return {c * x.x() - s * x.y(), s * x.x() + c * x.y()};
}
// J x: x turned by +90 degrees (d/dtheta R(theta) = J R(theta)).
Vec2 perp(const Vec2& x) { return {-x.y(), x.x()}; }

// Rotation by phi(t) (with its derivatives) about the fixed point c:
// x -> R(phi) (x - c) + c.
Pose rotation_about(const Vec2& c, double phi, double dphi, double ddphi) {
  Pose p;
  p.angle = phi;
  p.omega = dphi;
  p.alpha = ddphi;
  const Vec2 rc = rotate(phi, c);
  p.shift = c - rc;
  p.vel = -dphi * perp(rc);
  p.acc = -(ddphi * perp(rc) - dphi * dphi * rc);
  return p;
}

Pose translation(const Vec2& s, const Vec2& v, const Vec2& a) {
  Pose p;
  p.shift = s;
  p.vel = v;
  p.acc = a;
  return p;
}

// One channel of a keyframe track at time t: value, d/dt, d2/dt2.
struct Channel {
  double value = 0, rate = 0, accel = 0;
};

Channel interpolate(const std::vector<MotionComponent::Key>& keys, bool smooth, double t,
                    double (*get)(const MotionComponent::Key&)) {
  const std::size_t n = keys.size();
  if (t <= keys.front().time) return {get(keys.front()), 0, 0};
  if (t >= keys.back().time) return {get(keys.back()), 0, 0};
  std::size_t k = 0;
  while (k + 2 < n && keys[k + 1].time <= t) ++k;
  const double t0 = keys[k].time, t1 = keys[k + 1].time, span = t1 - t0;
  const double p0 = get(keys[k]), p1 = get(keys[k + 1]);
  const double u = (t - t0) / span;
  if (!smooth) return {p0 + u * (p1 - p0), (p1 - p0) / span, 0};
  // Catmull-Rom tangents for uneven key times; zero at the ends.
  auto tangent = [&](std::size_t i) {
    if (i == 0 || i + 1 == n) return 0.0;
    return (get(keys[i + 1]) - get(keys[i - 1])) / (keys[i + 1].time - keys[i - 1].time);
  };
  const double m0 = tangent(k) * span, m1 = tangent(k + 1) * span;
  const double u2 = u * u, u3 = u2 * u;
  Channel c;
  c.value = (2 * u3 - 3 * u2 + 1) * p0 + (u3 - 2 * u2 + u) * m0 + (-2 * u3 + 3 * u2) * p1 + (u3 - u2) * m1;
  c.rate = ((6 * u2 - 6 * u) * p0 + (3 * u2 - 4 * u + 1) * m0 + (-6 * u2 + 6 * u) * p1 + (3 * u2 - 2 * u) * m1) / span;
  c.accel = ((12 * u - 6) * p0 + (6 * u - 4) * m0 + (-12 * u + 6) * p1 + (6 * u - 2) * m1) / (span * span);
  return c;
}

}  // namespace

PoseMap::PoseMap(const Pose& p) : p_(p), c_(std::cos(p.angle)), s_(std::sin(p.angle)) {}

Vec2 Pose::position(const Vec2& x0) const { return PoseMap(*this).position(x0); }
Vec2 Pose::velocity(const Vec2& x0) const { return PoseMap(*this).velocity(x0); }
Vec2 Pose::acceleration(const Vec2& x0) const { return PoseMap(*this).acceleration(x0); }

// x -> R_o (R_i x + s_i) + s_o: angles add; the shift is R_o s_i + s_o, differentiated
// with d/dt R_o = omega_o J R_o.
Pose compose(const Pose& o, const Pose& i) {
  Pose p;
  p.angle = o.angle + i.angle;
  p.omega = o.omega + i.omega;
  p.alpha = o.alpha + i.alpha;
  const Vec2 rs = rotate(o.angle, i.shift), rv = rotate(o.angle, i.vel), ra = rotate(o.angle, i.acc);
  p.shift = rs + o.shift;
  p.vel = o.omega * perp(rs) + rv + o.vel;
  p.acc = o.alpha * perp(rs) - o.omega * o.omega * rs + 2 * o.omega * perp(rv) + ra + o.acc;
  return p;
}

Pose MotionComponent::at(double t) const {
  const double tau = t - start;
  switch (kind) {
    case Kind::Rotation: {
      if (tau <= 0) return Pose{};
      if (ramp > 0 && tau < ramp) {
        // omega(t) = Omega (3u^2 - 2u^3), u = tau / ramp: zero rate and acceleration at
        // the start, full rate with zero acceleration at the end of the ramp.
        const double u = tau / ramp;
        const double phi = omega * ramp * (u * u * u - 0.5 * u * u * u * u);
        return rotation_about(pivot, phi, omega * (3 * u * u - 2 * u * u * u), omega / ramp * 6 * u * (1 - u));
      }
      return rotation_about(pivot, omega * (tau - 0.5 * ramp), omega, 0);
    }
    case Kind::Translation: {
      const double run = std::clamp(tau, 0.0, end - start);
      const bool moving = tau > 0 && tau < end - start;
      return translation(run * velocity, moving ? velocity : Vec2::Zero(), Vec2::Zero());
    }
    case Kind::Oscillation: {
      if (tau <= 0) return Pose{};
      const double w = 2 * std::numbers::pi / period, arg = w * tau + phase;
      const double s = std::sin(arg), c = std::cos(arg);
      if (angular_amplitude != 0) {
        const double a = angular_amplitude;
        return rotation_about(pivot, a * s, a * w * c, -a * w * w * s);
      }
      return translation(amplitude * s * direction, amplitude * w * c * direction, -amplitude * w * w * s * direction);
    }
    case Kind::Keyframes: {
      const Channel x = interpolate(keys, smooth, t, [](const Key& k) { return k.offset.x(); });
      const Channel y = interpolate(keys, smooth, t, [](const Key& k) { return k.offset.y(); });
      const Channel a = interpolate(keys, smooth, t, [](const Key& k) { return k.angle; });
      const Pose turn = rotation_about(pivot, a.value, a.rate, a.accel);
      const Pose move = translation({x.value, y.value}, {x.rate, y.rate}, {x.accel, y.accel});
      return compose(move, turn);
    }
  }
  return Pose{};
}

Pose Motion::at(double t) const {
  Pose p;
  for (const MotionComponent& c : components) p = compose(c.at(t), p);
  return p;
}

}  // namespace sluice
