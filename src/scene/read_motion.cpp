// The scripted motion of a boundary object (solver/motion.h): one component or a list.
#include <cmath>

#include "scene/sections.h"

namespace sluice::scene_detail {

namespace {

// One scripted motion component (see motion.h); the object at rest is its shape as given.
MotionComponent read_motion_component(Reader& r, const Context& ctx) {
  MotionComponent m;
  const std::string type = r.choice("type", {"rotation", "translation", "oscillation", "keyframes"}, nullptr);
  if (type != "keyframes") m.start = r.number("start", 0.0, Range::at_least(0, "[s]"));
  if (type == "rotation") {
    m.kind = MotionComponent::Kind::Rotation;
    m.pivot = r.vec2("pivot");
    m.omega = r.number("angular_velocity", Range::any("[rad/s], > 0 counter-clockwise"));
    m.ramp = r.number("ramp", 0.0, Range::at_least(0, "[s]"));
  } else if (type == "translation") {
    m.kind = MotionComponent::Kind::Translation;
    m.velocity = r.vec2("velocity");
    const json* end = r.find("end");
    m.end = kInf;
    if (end && !end->is_null()) {
      m.end = ctx.number(*end, r.at("end"), Range::at_least(0, "[s]"));
      if (m.end < m.start)
        ctx.fail(r.at("end"), "end " + num(m.end) + " s is before start " + num(m.start) +
                                  " s; need start <= end, or null for no end");
    }
    r.resolved()["end"] = std::isfinite(m.end) ? json(m.end) : json(nullptr);
  } else if (type == "oscillation") {
    m.kind = MotionComponent::Kind::Oscillation;
    m.period = r.number("period", Range::positive("[s]"));
    m.phase = r.number("phase", 0.0, Range::any("[rad]"));
    const json* amp = r.find("amplitude");
    const json* ang = r.find("angular_amplitude");
    if ((amp != nullptr) == (ang != nullptr))
      ctx.fail(r.path(),
               "give exactly one of \"amplitude\" (a shift along direction, [m]) and \"angular_amplitude\" (a rotation "
               "about pivot, [rad])");
    if (amp) {
      m.amplitude = ctx.number(*amp, r.at("amplitude"), Range::at_least(0, "[m]"));
      r.resolved()["amplitude"] = m.amplitude;
      const json* dir = r.find("direction");
      const json* angle = r.find("angle");
      if (dir && angle)
        ctx.fail(r.path(), "give at most one of \"direction\" ([x, y]) and \"angle\" ([rad] from the x axis)");
      if (angle) {
        const double a = ctx.number(*angle, r.at("angle"), Range::any("[rad]"));
        m.direction = {std::cos(a), std::sin(a)};
      } else if (dir) {
        m.direction = ctx.vec2(*dir, r.at("direction"));
        if (m.direction.norm() == 0)
          ctx.fail(r.at("direction"), "the direction [0, 0] has no length; give a non-zero vector");
        m.direction.normalize();
      }
      r.resolved()["direction"] = {m.direction.x(), m.direction.y()};
    } else {
      m.angular_amplitude = ctx.number(*ang, r.at("angular_amplitude"), Range::any("[rad]"));
      r.resolved()["angular_amplitude"] = m.angular_amplitude;
      m.pivot = r.vec2("pivot");
    }
  } else {
    m.kind = MotionComponent::Kind::Keyframes;
    m.smooth = r.choice("interpolation", {"linear", "smooth"}, "linear") == "smooth";
    m.pivot = r.vec2("pivot", Vec2::Zero());
    const json& keys = r.require("keys", "an array of at least 2 keys {\"time\", \"offset\", \"angle\"}");
    if (!keys.is_array() || keys.size() < 2)
      ctx.fail(r.at("keys"),
               "expected an array of at least 2 keys {\"time\", \"offset\", \"angle\"}, got " + show(keys));
    json resolved_keys = json::array();
    for (std::size_t i = 0; i < keys.size(); ++i) {
      Reader k(ctx, &keys[i], r.at("keys") + "/" + std::to_string(i));
      MotionComponent::Key key;
      key.time = k.number("time", Range::at_least(0, "[s]"));
      key.offset = k.vec2("offset", Vec2::Zero());
      key.angle = k.number("angle", 0.0, Range::any("[rad]"));
      k.finish();
      if (i > 0 && !(key.time > m.keys.back().time))
        ctx.fail(k.at("time"), "time " + num(key.time) + " s is not after the previous key's " +
                                   num(m.keys.back().time) + " s; key times must increase");
      m.keys.push_back(key);
      resolved_keys.push_back(k.resolved());
    }
    r.resolved()["keys"] = resolved_keys;
  }
  r.finish();
  return m;
}

// "motion": one component or an array of them, applied in order.
Motion read_motion(const json& v, const std::string& path, const Context& ctx, json& resolved) {
  Motion motion;
  const bool single = v.is_object();
  if (!single && !v.is_array())
    ctx.fail(
        path,
        "expected a motion object or an array of them (types: rotation, translation, oscillation, keyframes), got " +
            show(v));
  const std::size_t n = single ? 1 : v.size();
  resolved = json::array();
  for (std::size_t i = 0; i < n; ++i) {
    Reader r(ctx, single ? &v : &v[i], single ? path : path + "/" + std::to_string(i));
    motion.components.push_back(read_motion_component(r, ctx));
    resolved.push_back(r.resolved());
  }
  return motion;
}
}  // namespace

// The optional "motion" key of a boundary object.
void read_object_motion(Reader& r, const Context& ctx, BoundaryObject& obj) {
  if (const json* m = r.find("motion"); m && !m->is_null()) {
    obj.motion = read_motion(*m, r.at("motion"), ctx, r.resolved()["motion"]);
    obj.moving = true;
  } else {
    r.resolved()["motion"] = nullptr;
  }
}

}  // namespace sluice::scene_detail
