// The scene's settings sections: solver, time, stability, output, render, and the name.
#include <algorithm>
#include <cmath>

#include "scene/sections.h"

namespace sluice::scene_detail {

namespace {

// Frames of a run (duration x fps): frame numbers are 32-bit, and every frame is a file.
constexpr double kMaxFrames = 1e7;
// Steps of a run: the fewest it can take (duration / dt, or / dt_max when adaptive). A
// typo in dt would otherwise run for days and fill the disk with stats.csv rows.
constexpr double kMaxSteps = 1e7;

// The run must end within kMaxSteps steps, and its smallest step must move the clock:
// t + dt == t in double precision would repeat the same time forever.
void check_step_count(Reader& r, const Context& ctx, const TimeSettings& t, bool fixed) {
  const double step = fixed ? t.dt : t.dt_max;
  const std::string key = fixed ? "dt" : "dt_max";
  const double settle = t.auto_settle ? kAutoSettleSeconds : t.settle;  // the longest it can be
  const double steps = (settle + t.duration) / step;
  std::string what = "settle";
  if (t.auto_settle) what = "an automatic settle of up to " + num(settle) + " s";
  if (!(steps <= kMaxSteps))
    ctx.fail(r.at(key), key + " " + num(step) + " s for " + num(settle + t.duration) + " s (" + what +
                            " + duration) makes at least " + num(std::ceil(steps)) + " steps; the limit is " +
                            num(kMaxSteps) + " (raise " + key + " or shorten the run)");
  const double smallest = fixed ? t.dt : t.dt_min;
  const double end = settle + t.duration;
  if (!(end + smallest > end))
    ctx.fail(r.at(fixed ? "dt" : "dt_min"), "value " + num(smallest) +
                                                " s does not advance the time at t = " + num(end) +
                                                " s in double precision; must be > " + num(end * 0x1p-52) + " [s]");
}

// time.settle: "auto" (absent: the same) or a number of seconds >= 0.
void read_settle(Reader& r, const Context& ctx, TimeSettings& t) {
  const json* v = r.find("settle");
  t.auto_settle = !v || (v->is_string() && v->get<std::string>() == "auto");
  if (!t.auto_settle) {
    if (!v->is_number()) ctx.fail(r.at("settle"), "expected a number >= 0 [s] or \"auto\", got " + show(*v));
    t.settle = ctx.number(*v, r.at("settle"), Range::at_least(0, "[s]"));
  }
  r.resolved()["settle"] = t.auto_settle ? json("auto") : json(t.settle);
}

}  // namespace

SolverSettings read_solver(Reader& r, const Context& ctx) {
  SolverSettings s;
  s.type = r.enumeration("type", s.type, {{"iisph", SolverType::IISPH}, {"wcsph", SolverType::WCSPH}});
  s.rest_density = r.number("rest_density", s.rest_density, Range::positive("[kg/m^2]"));
  s.gravity = r.vec2("gravity", s.gravity);
  s.viscosity = r.number("viscosity", s.viscosity, Range::at_least(0, "[m^2/s]"));
  s.artificial_viscosity = r.number("artificial_viscosity", s.artificial_viscosity, Range::at_least(0, "(alpha)"));
  s.sound_speed = r.number("sound_speed", s.sound_speed, Range::at_least(0, "[m/s]"));
  s.gradient_correction = r.boolean("gradient_correction", s.gradient_correction);
  s.kernel = r.enumeration("kernel", s.kernel,
                           {{"cubic_spline", KernelKind::CubicSpline}, {"wendland_c2", KernelKind::WendlandC2}});
  s.support = r.number("support", s.support, Range::closed(1.5, 4, "[particle spacings]"));
  s.tolerance_percent = r.number("tolerance", s.tolerance_percent, Range::positive("(percent)"));
  s.omega = r.number("omega", s.omega, Range::open_closed(0, 1));
  s.min_iterations = r.integer("min_iterations", s.min_iterations, 1, 10000);
  s.max_iterations = r.integer("max_iterations", s.max_iterations, 1, 10000);
  if (s.min_iterations > s.max_iterations)
    ctx.fail(r.at("min_iterations"), "min_iterations " + std::to_string(s.min_iterations) +
                                         " is larger than max_iterations " + std::to_string(s.max_iterations) +
                                         "; need 1 <= min_iterations <= max_iterations <= 10000");
  s.pressure_init = r.enumeration("pressure_init", s.pressure_init,
                                  {{"warm", PressureInit::WarmStart}, {"thesis", PressureInit::Thesis}});
  s.pressure_solver = r.enumeration("pressure_solver", s.pressure_solver,
                                    {{"jacobi", PressureSolver::Jacobi},
                                     {"chebyshev", PressureSolver::Chebyshev},
                                     {"multilevel", PressureSolver::Multilevel}});
  s.chebyshev_rho = r.number("chebyshev_rho", s.chebyshev_rho, Range::closed_open(0, 1));
  s.multilevel_cell = r.number("multilevel_cell", s.multilevel_cell, Range::closed(2, 64, "[particle spacings]"));
  s.multilevel_wall_sweeps = r.integer("multilevel_wall_sweeps", s.multilevel_wall_sweeps, 0, 100);
  s.multilevel_impact_damping = r.number("multilevel_impact_damping", s.multilevel_impact_damping, Range::closed(0, 1));
  // Absent or null: the solver's own kappa (stabilisation_kappa).
  if (const json* k = r.find("pressure_stabilisation"); k && !k->is_null())
    s.pressure_stabilisation = ctx.number(*k, r.at("pressure_stabilisation"), Range::closed(0, 10, "(kappa)"));
  r.resolved()["pressure_stabilisation"] =
      s.pressure_stabilisation >= 0 ? json(s.pressure_stabilisation) : json(nullptr);
  // Absent or null: the scene's default (wcsph_default_stiffness), set in parse_scene once
  // the fluid exists.
  if (const json* k = r.find("stiffness"); k && !k->is_null())
    s.stiffness = ctx.number(*k, r.at("stiffness"), Range::positive("[Pa*m]"));
  r.resolved()["stiffness"] = s.stiffness > 0 ? json(s.stiffness) : json(nullptr);
  s.boundary_pressure = r.enumeration("boundary_pressure", s.boundary_pressure,
                                      {{"solved", BoundaryPressure::Solved},
                                       {"extrapolation", BoundaryPressure::Extrapolation},
                                       {"mirroring", BoundaryPressure::Mirroring},
                                       {"zero", BoundaryPressure::Zero}});
  s.gamma1 = r.number("gamma1", s.gamma1, Range::positive());
  s.gamma2 = r.number("gamma2", s.gamma2, Range::at_least(0));
  s.gamma3 = r.number("gamma3", s.gamma3, Range::at_least(0));
  s.boundary_diagonal = r.boolean("boundary_diagonal", s.boundary_diagonal);
  if (s.type == SolverType::IISPH && s.pressure_solver == PressureSolver::Multilevel &&
      s.boundary_pressure == BoundaryPressure::Extrapolation)
    ctx.fail(r.at("pressure_solver"),
             "\"multilevel\" needs boundary_pressure \"solved\", \"mirroring\" or \"zero\", not \"extrapolation\": "
             "its coarse operator has no term for Eq. 25's extrapolated wall pressure");
  if (s.type == SolverType::IISPH && s.pressure_solver == PressureSolver::Multilevel && s.multilevel_cell < s.support)
    ctx.fail(r.at("multilevel_cell"), "multilevel_cell " + num(s.multilevel_cell) +
                                          " is smaller than the kernel's support " + num(s.support) +
                                          " [particle spacings]; the coarse operator couples cells at most two apart, "
                                          "which needs multilevel_cell >= support");
  r.finish();
  return s;
}

TimeSettings read_time(Reader& r, const Context& ctx) {
  TimeSettings t;
  t.duration = r.number("duration", t.duration, Range::positive("[s]"));
  t.fps = r.number("fps", t.fps, Range::positive("[frames/s]"));
  if (!(t.duration * t.fps <= kMaxFrames))
    ctx.fail(r.path(), "duration " + num(t.duration) + " s at fps " + num(t.fps) + " makes " +
                           num(std::ceil(t.duration * t.fps)) + " frames; the limit is " + num(kMaxFrames) +
                           " (shorten duration or lower fps)");
  const json* dt = r.find("dt");
  const json* cfl = r.find("cfl");
  bool fixed = dt && !dt->is_null(), has_cfl = cfl && !cfl->is_null();
  if (fixed && has_cfl) {
    // An override of one replaces the file's other: `--set time.dt=1e-3` (or a sweep of
    // time.dt) on a scene with a cfl runs at that fixed step. Both in the file, or both
    // overridden, is a mistake.
    auto overridden = [&](const char* key) {
      const std::string p = r.at(key);
      return std::any_of(ctx.overridden.begin(), ctx.overridden.end(),
                         [&](const std::string& o) { return p == o || p.starts_with(o + "/"); });
    };
    const bool dt_set = overridden("dt"), cfl_set = overridden("cfl");
    if (dt_set == cfl_set)
      ctx.fail(r.path(),
               "both dt and cfl are given; remove \"cfl\" for a fixed time step, or \"dt\" for the adaptive CFL step "
               "(an override can remove a key with null, e.g. time.dt=null)");
    (dt_set ? has_cfl : fixed) = false;
  }
  if (fixed) t.dt = ctx.number(*dt, r.at("dt"), Range::positive("[s]"));
  if (has_cfl) t.cfl = ctx.number(*cfl, r.at("cfl"), Range::open_closed(0, 2));
  r.resolved()["dt"] = fixed ? json(t.dt) : json(nullptr);
  r.resolved()["cfl"] = fixed ? json(nullptr) : json(t.cfl);
  t.dt_max = r.number("dt_max", t.dt_max, Range::positive("[s]"));
  t.dt_min = r.number("dt_min", t.dt_min, Range::positive("[s]"));
  read_settle(r, ctx, t);
  t.relax_start = r.boolean("relax_start", t.relax_start);
  if (t.dt_min > t.dt_max)
    ctx.fail(r.at("dt_min"),
             "dt_min " + num(t.dt_min) + " is larger than dt_max " + num(t.dt_max) + "; need 0 < dt_min <= dt_max");
  if (t.duration < kMinDuration)
    ctx.fail(r.at("duration"), "value " + num(t.duration) + " is out of range; must be >= " + num(kMinDuration) +
                                   " [s] (shorter runs are below the resolution of the time steps)");
  check_step_count(r, ctx, t, fixed);
  r.finish();
  return t;
}

StabilityLimits read_stability(Reader& r) {
  StabilityLimits s;
  s.max_error_percent = r.number("max_error_percent", s.max_error_percent, Range::positive("(percent)"));
  s.bounds_margin = r.number("bounds_margin", s.bounds_margin, Range::positive("(scene sizes)"));
  s.max_leaked_percent = r.number("max_leaked_percent", s.max_leaked_percent,
                                  Range{0, 100, false, false, "(percent of the fluid particles)"});
  s.max_energy_gain = r.number("max_energy_gain", s.max_energy_gain,
                               Range::positive("(fraction of the energy available to the fluid)"));
  s.max_speed_ratio = r.number("max_speed_ratio", s.max_speed_ratio,
                               Range::at_least(1, "(times the speed the fluid can have been given)"));
  r.finish();
  return s;
}

OutputSettings read_output(Reader& r, const Context& ctx, const std::string& name) {
  OutputSettings o;
  o.directory = r.string("directory", "renders/" + name);
  if (const json* e = r.find("export")) {
    if (!e->is_array())
      ctx.fail(r.at("export"), "expected an array of formats, got " + show(*e) + "; allowed formats: csv, vtk");
    for (std::size_t i = 0; i < e->size(); ++i) {
      const std::string path = r.at("export") + "/" + std::to_string(i);
      std::string f = ctx.choice((*e)[i], path, {"csv", "vtk"});
      if (std::find(o.export_formats.begin(), o.export_formats.end(), f) != o.export_formats.end())
        ctx.fail(path, "duplicate format \"" + f + "\"; list each of csv, vtk at most once");
      o.export_formats.push_back(f);
    }
  }
  r.resolved()["export"] = o.export_formats;
  r.finish();
  return o;
}

RenderSettings read_render(Reader& r, const Context& ctx) {
  RenderSettings s;
  if (const json* res = r.find("resolution")) {
    const std::string path = r.at("resolution");
    if (!res->is_array() || res->size() != 2) ctx.fail(path, "expected [width, height] in pixels, got " + show(*res));
    s.width = ctx.integer((*res)[0], path + "/0", 2, 16384);
    s.height = ctx.integer((*res)[1], path + "/1", 2, 16384);
  }
  r.resolved()["resolution"] = {s.width, s.height};
  s.color_by = r.choice("color_by", {"cfl", "speed", "pressure", "density_error"}, "cfl");
  s.colormap = r.choice("colormap", {"spectrum", "viridis", "turbo"}, "spectrum");
  const json* range = r.find("range");
  if (range && !range->is_null()) {
    const Vec2 lohi = ctx.vec2(*range, r.at("range"));
    // hi - lo must be finite too: the colour of a value is (v - lo) / (hi - lo).
    if (!(lohi.y() > lohi.x()) || !std::isfinite(lohi.y() - lohi.x()))
      ctx.fail(
          r.at("range"),
          "range " + show(*range) +
              " must be [lo, hi] with lo < hi and hi - lo finite (in the units of color_by), or null for automatic");
    s.fixed_range = true;
    s.range_lo = lohi.x();
    s.range_hi = lohi.y();
  }
  r.resolved()["range"] = s.fixed_range ? json{s.range_lo, s.range_hi} : json(nullptr);
  const json* view = r.find("view");
  if (view && !view->is_null()) {
    Reader v(ctx, view, r.at("view"));
    s.view_min = v.vec2("min");
    s.view_max = v.vec2("max");
    v.finish();
    if (!(s.view_max.x() > s.view_min.x() && s.view_max.y() > s.view_min.y()))
      ctx.fail(v.at("max"), "max [" + num(s.view_max.x()) + ", " + num(s.view_max.y()) + "] must be above min [" +
                                num(s.view_min.x()) + ", " + num(s.view_min.y()) + "] in x and y");
    s.fixed_view = true;
    r.resolved()["view"] = v.resolved();
  } else {
    r.resolved()["view"] = nullptr;
  }
  r.finish();
  return s;
}

// The name becomes a folder (renders/<name>) and a file (<name>.mp4): it must stay one
// path component, so that a scene cannot write outside its output directory.
void check_name(const Context& ctx, const std::string& name) {
  const bool control =
      std::any_of(name.begin(), name.end(), [](char c) { return static_cast<unsigned char>(c) < 0x20; });
  if (name == "." || name == ".." || name.find_first_of("/\\") != std::string::npos || control)
    ctx.fail("/name", "invalid value " + show(json(name)) +
                          "; a name must not contain '/', '\\' or control characters, nor be '.' or '..' (it names the "
                          "output folder renders/<name> and the video <name>.mp4)");
}

// Clears the fluid inside the boundaries as they stand at t = 0: objects at rest (and
// moving ones whose script leaves them at rest at t = 0) together, every other moving

}  // namespace sluice::scene_detail
