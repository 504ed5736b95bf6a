#pragma once
// Scripted rigid motion of a boundary object (thesis chapter 4: dynamic boundaries).
// A motion is a list of components, each a rigid transform that depends on time only;
// the object's pose at time t is their composition evaluated from the script at t (no
// increments are accumulated, so nothing drifts), and its velocity and acceleration are
// the analytic time derivatives.
#include <vector>

#include "core/types.h"

namespace sluice {

// A rigid transform x -> R(angle) x + shift with its first and second time derivatives.
struct Pose {
  double angle = 0, omega = 0, alpha = 0;  // rotation [rad], d/dt [rad/s], d2/dt2 [rad/s^2]
  Vec2 shift{0, 0}, vel{0, 0}, acc{0, 0};  // translation [m], d/dt [m/s], d2/dt2 [m/s^2]

  // Position, velocity and acceleration of the point that sits at x0 at rest.
  Vec2 position(const Vec2& x0) const;
  Vec2 velocity(const Vec2& x0) const;
  Vec2 acceleration(const Vec2& x0) const;
};

// A pose with its rotation evaluated once, for mapping many points (no trigonometry per point).
class PoseMap {
 public:
  explicit PoseMap(const Pose& p);
  Vec2 rotated(const Vec2& x0) const { return {c_ * x0.x() - s_ * x0.y(), s_ * x0.x() + c_ * x0.y()}; }
  Vec2 position(const Vec2& x0) const { return rotated(x0) + p_.shift; }
  Vec2 velocity(const Vec2& x0) const {
    const Vec2 r = rotated(x0);
    return p_.omega * Vec2(-r.y(), r.x()) + p_.vel;
  }
  Vec2 acceleration(const Vec2& x0) const {
    const Vec2 r = rotated(x0);
    return p_.alpha * Vec2(-r.y(), r.x()) - p_.omega * p_.omega * r + p_.acc;
  }

 private:
  Pose p_;
  double c_, s_;
};

// `outer` applied after `inner` (x -> outer(inner(x))), derivatives by the product rule.
Pose compose(const Pose& outer, const Pose& inner);

struct MotionComponent {
  enum class Kind { Rotation, Translation, Oscillation, Keyframes };
  Kind kind = Kind::Rotation;
  double start = 0;  // the component is at rest (identity) before this time [s]

  // Rotation about `pivot`: angular velocity omega [rad/s] (> 0 counter-clockwise),
  // reached from rest over `ramp` seconds with a smooth (C1) profile, 0 for a jump.
  Vec2 pivot{0, 0};
  double omega = 0, ramp = 0;
  // Translation with `velocity` [m/s] from start to `end` (infinite: forever).
  Vec2 velocity{0, 0};
  double end = 0;
  // Oscillation: shift amplitude * sin(2 pi (t - start) / period + phase) along the unit
  // `direction`; or, with angular_amplitude != 0, a rotation about `pivot` by
  // angular_amplitude * sin(...) [rad].
  double amplitude = 0, angular_amplitude = 0, period = 1, phase = 0;
  Vec2 direction{1, 0};
  // Keyframes: poses (offset [m], angle [rad] about `pivot`) at increasing times; held
  // before the first and after the last. Linear: straight lines between keys. Smooth:
  // cubic Hermite with Catmull-Rom tangents (zero at the first and last key), so the
  // velocity is continuous.
  struct Key {
    double time = 0;
    Vec2 offset{0, 0};
    double angle = 0;
  };
  std::vector<Key> keys;
  bool smooth = false;

  Pose at(double t) const;
};

// Components applied in list order: the first acts on the rest shape, the next on the result.
struct Motion {
  std::vector<MotionComponent> components;

  bool empty() const { return components.empty(); }
  Pose at(double t) const;
};

}  // namespace sluice
