// `sluice validate hydrostatic|dam-break|elliptical-drop`: the validation runs against known answers.
// Each prints its error figures, writes CSV and a gnuplot figure (PNG) into the output
// directory, and exits 1 when an error exceeds the bound the tests hold it to.
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>

#include "analysis/elliptical_drop.h"
#include "analysis/plot.h"
#include "analysis/validation.h"
#include "app/commands.h"
#include "app/run.h"
#include "io/output.h"

namespace sluice::app {

namespace fs = std::filesystem;

namespace {

void report_figure(const std::string& why, const fs::path& png) {
  if (why.empty()) std::printf("figure: %s\n", png.string().c_str());
  else std::fprintf(stderr, "sluice: warning: no figure: %s (the CSV is written)\n", why.c_str());
}

// "iisph_mirroring" -> "IISPH, mirroring" for a legend.
std::string case_label(const std::string& name) {
  const auto u = name.find('_');
  std::string solver = name.substr(0, u);
  for (char& c : solver) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return solver + ", " + name.substr(u + 1) + (name.find("zero") != std::string::npos ? " (p_b = 0)" : "");
}

int validate_hydrostatic(const ValidateOptions& o, const fs::path& dir) {
  const std::string scene_file = o.scene.empty() ? "scenes/validation/hydrostatic.json" : o.scene;
  std::printf("hydrostatic tank %s: <p> per depth bin over the last 0.5 s against rho0 g d\n", scene_file.c_str());
  std::printf("%-22s %6s %7s %11s %9s %11s %9s %11s  %s\n", "case", "steps", "capped", "worst_bin_%", "at_d_m",
              "bin_tol_%", "slope_%", "slope_tol_%", "result");
  std::string profile = "case,depth_m,pressure,ratio,samples\n";
  std::string summary = "case,steps,capped,surface_m,worst_bin_error,worst_depth_m,bin_tolerance,slope_error,slope_tolerance,floor_ratio,passed\n";
  std::vector<std::string> names;
  int failed = 0;
  for (const auto& c : analysis::hydrostatic_cases()) {
    if (!o.only.empty() && c.name != o.only) continue;
    std::vector<std::string> set = c.set;
    set.insert(set.end(), o.set.begin(), o.set.end());
    const Scene scene = load_scene(scene_file, set);
    // The tank's width: the fluid block spans [0, width] (see the scene file).
    double width = 0;
    for (const Vec2& x : scene.fluid_x) width = std::max(width, x.x() + 0.5 * scene.spacing);
    const auto r = analysis::run_hydrostatic(scene, width, scene.time.duration - 0.5, c.zero_pressure_wall);
    const bool ok = r.worst_bin_error < c.bin_tolerance && r.slope_error < c.slope_tolerance;
    failed += !ok;
    std::printf("%-22s %6ld %7ld %11.2f %9.3f %11.1f %9.2f %11.1f  %s\n", c.name.c_str(), r.steps, r.capped,
                100 * r.worst_bin_error, r.worst_depth, 100 * c.bin_tolerance, 100 * r.slope_error,
                100 * c.slope_tolerance, ok ? "ok" : "FAILED");
    std::fflush(stdout);
    for (const auto& b : r.bins) {
      char line[256];
      std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%.6f,%ld\n", c.name.c_str(), b.depth, b.pressure, b.ratio, b.samples);
      profile += line;
    }
    char line[512];
    std::snprintf(line, sizeof line, "%s,%ld,%ld,%.5f,%.6f,%.5f,%.3f,%.6f,%.3f,%.4f,%d\n", c.name.c_str(), r.steps,
                  r.capped, r.surface, r.worst_bin_error, r.worst_depth, c.bin_tolerance, r.slope_error,
                  c.slope_tolerance, r.floor_ratio, ok ? 1 : 0);
    summary += line;
    names.push_back(c.name);
  }
  if (names.empty()) throw view::FlagError("--case", o.only, "iisph_ or wcsph_ followed by extrapolation, mirroring or zero");
  write_file_atomic((dir / "hydrostatic_profile.csv").string(), profile);
  write_file_atomic((dir / "hydrostatic.csv").string(), summary);
  // p/(rho0 g d) against depth, one line per case: 1 is the exact answer.
  std::ostringstream gp;
  gp << analysis::gnuplot_png_preamble("hydrostatic.png")
     << "set title \"Hydrostatic tank: time-averaged pressure / ({/Symbol r}_0 g d)\"\n"
        "set xlabel \"depth below the free surface d [m]\"\nset ylabel \"p / ({/Symbol r}_0 g d)\"\n"
        "set yrange [0.7:1.9]\nset key top center\n"
        "plot 1 with lines lc rgb \"black\" dt 2 title \"exact\"";
  for (const auto& n : names)
    gp << ", \"hydrostatic_profile.csv\" using 2:(strcol(1) eq " << analysis::gnuplot_quote(n)
       << " ? $4 : NaN) with linespoints title " << analysis::gnuplot_quote(case_label(n)) << " noenhanced";
  gp << "\n";
  // The first column holds strings: read it as such.
  std::string script = gp.str();
  script.insert(0, "set datafile missing \"NaN\"\n");
  report_figure(analysis::run_gnuplot((dir / "hydrostatic.gp").string(), script), dir / "hydrostatic.png");
  std::printf("wrote %s, %s\n", (dir / "hydrostatic.csv").string().c_str(), (dir / "hydrostatic_profile.csv").string().c_str());
  return failed ? 1 : 0;
}

// WCSPH on the 2 m column: k = 2e6 Pa m keeps the hydrostatic compression near 1 % at the
// floor; the fixed step keeps 0.4 h / c (c = sqrt(k / rho0)) at h = 0.02.
const std::vector<std::string> kWcsphDamBreak{"solver.type=wcsph", "solver.stiffness=2e6", "time.cfl=null",
                                              "time.dt=1e-4"};

int validate_dam_break(const ValidateOptions& o, const fs::path& dir) {
  const std::string scene_file = o.scene.empty() ? "scenes/validation/dam_break_martin_moyce.json" : o.scene;
  std::vector<std::string> solvers;
  if (o.solver != "wcsph") solvers.push_back("iisph");
  if (o.solver != "iisph") solvers.push_back("wcsph");
  std::string series = "solver,t_s,T,z_m,Z\n";
  std::string points = "solver,T,Z_experiment,Z_simulated,relative_error\n";
  int failed = 0;
  for (const auto& solver : solvers) {
    std::vector<std::string> set;
    if (solver == "wcsph") set = kWcsphDamBreak;
    else set.push_back("solver.type=iisph");
    if (o.spacing > 0) set.push_back("spacing=" + std::to_string(o.spacing));
    set.insert(set.end(), o.set.begin(), o.set.end());
    const Scene scene = load_scene(scene_file, set);
    std::printf("dam break %s, %s: %zu fluid particles, h = %g m\n", scene_file.c_str(), solver.c_str(),
                scene.fluid_x.size(), scene.spacing);
    std::fflush(stdout);
    const auto r = analysis::run_dam_break_front(scene);
    std::printf("  column a = %.3f m x %.3f m (n^2 = %.2f); the far wall at Z = %.2f\n", r.a, r.height, r.height / r.a,
                r.wall_Z);
    std::printf("  %8s %12s %12s %10s\n", "T", "Z_experiment", "Z_simulated", "error_%");
    for (const auto& p : r.compared)
      std::printf("  %8.3f %12.3f %12.3f %10.2f\n", p.T, p.Z_experiment, p.Z_simulated, 100 * p.relative_error);
    const bool ok = r.rms_relative_error <= o.max_rms;
    failed += !ok;
    std::printf("  %s: RMS relative error %.2f %% over %zu points (bound %.1f %%): %s; %ld steps, %.2f iterations, %.1f s\n",
                solver.c_str(), 100 * r.rms_relative_error, r.compared.size(), 100 * o.max_rms, ok ? "ok" : "FAILED",
                r.steps, r.avg_iterations, r.wall_seconds);
    std::fflush(stdout);
    for (const auto& s : r.front) {
      char line[256];
      std::snprintf(line, sizeof line, "%s,%.6f,%.6f,%.6f,%.6f\n", solver.c_str(), s.t, s.T, s.z, s.Z);
      series += line;
    }
    for (const auto& p : r.compared) {
      char line[256];
      std::snprintf(line, sizeof line, "%s,%.4f,%.4f,%.4f,%.6f\n", solver.c_str(), p.T, p.Z_experiment, p.Z_simulated,
                    p.relative_error);
      points += line;
    }
  }
  write_file_atomic((dir / "dam_break_front.csv").string(), series);
  write_file_atomic((dir / "dam_break_points.csv").string(), points);
  std::string exp = "T,Z\n";
  for (const auto& [T, Z] : analysis::martin_moyce_n2_a225()) exp += std::to_string(T) + "," + std::to_string(Z) + "\n";
  write_file_atomic((dir / "martin_moyce_1952.csv").string(), exp);
  std::ostringstream gp;
  gp << "set datafile missing \"NaN\"\n"
     << analysis::gnuplot_png_preamble("dam_break_front.png")
     << "set title \"Dam break surge front against Martin and Moyce (1952), n^2 = 2\"\n"
        "set xlabel \"T = t (2g/a)^{1/2}\"\nset ylabel \"Z = z / a\"\n"
        "plot \"martin_moyce_1952.csv\" using 1:2 skip 1 with points pt 7 ps 1.5 lc rgb \"black\" title \"experiment (a = 2.25 in)\"";
  for (const auto& s : solvers)
    gp << ", \"dam_break_front.csv\" using 3:(strcol(1) eq " << analysis::gnuplot_quote(s) << " ? $5 : NaN) with lines title "
       << analysis::gnuplot_quote(s == "iisph" ? "IISPH" : "WCSPH");
  gp << "\n";
  report_figure(analysis::run_gnuplot((dir / "dam_break_front.gp").string(), gp.str()), dir / "dam_break_front.png");
  std::printf("wrote %s, %s\n", (dir / "dam_break_front.csv").string().c_str(), (dir / "dam_break_points.csv").string().c_str());
  return failed ? 1 : 0;
}

// Monaghan's (1994) inviscid elliptical drop: the semi-axes against the exact ODE.
int validate_elliptical_drop(const ValidateOptions& o, const fs::path& dir) {
  const std::string scene_file = o.scene.empty() ? "scenes/validation/elliptical_drop.json" : o.scene;
  std::vector<std::string> solvers;
  if (o.solver != "wcsph") solvers.push_back("iisph");
  if (o.solver != "iisph") solvers.push_back("wcsph");
  const double A0 = analysis::kEllipticalDropA0, bound = analysis::kEllipticalDropBound;
  std::printf("elliptical drop %s: u = -A0 x, v = A0 y with A0 = %g 1/s; semi-axes from the second moments against "
              "Monaghan's (1994) ODE\n", scene_file.c_str(), A0);
  std::printf("%-6s %9s %6s %6s %9s %9s %9s %9s %8s %8s  %s\n", "solver", "particles", "steps", "t_s", "a_sim", "a_ode",
              "b_sim", "b_ode", "error_%", "bound_%", "result");
  std::string series = "solver,t_s,a_sim_m,a_ode_m,b_sim_m,b_ode_m,a_rel_error,b_rel_error,xy_correlation\n";
  std::string summary = "solver,spacing_m,particles,steps,avg_iterations,wall_s,t_end_s,a_sim_m,a_ode_m,b_sim_m,b_ode_m,a_error,b_error,bound,passed\n";
  int failed = 0;
  for (const auto& solver : solvers) {
    std::vector<std::string> base{"solver.type=" + solver};
    if (o.spacing > 0) base.push_back(number_override("spacing", o.spacing));
    std::vector<std::string> set = base;
    set.insert(set.end(), o.set.begin(), o.set.end());
    Scene scene = load_scene(scene_file, set);
    if (solver == "wcsph") {
      // The step and stiffness depend on the spacing and the drop; --set still wins.
      set = base;
      const auto w = analysis::elliptical_drop_wcsph_overrides(scene, A0);
      set.insert(set.end(), w.begin(), w.end());
      set.insert(set.end(), o.set.begin(), o.set.end());
      scene = load_scene(scene_file, set);
    }
    const auto r = analysis::run_elliptical_drop(scene, A0);
    const auto& e = r.series.back();
    const bool ok = r.error <= bound;
    failed += !ok;
    std::printf("%-6s %9ld %6ld %6.3f %9.5f %9.5f %9.5f %9.5f %8.3f %8.1f  %s\n", solver.c_str(), r.particles, r.steps, e.t,
                e.a_sim, e.a_ode, e.b_sim, e.b_ode, 100 * r.error, 100 * bound, ok ? "ok" : "FAILED");
    std::printf("       h = %g m, R0 = %.4f m, %.1f s, %.2f iterations/step, max speed at the end %.3f m/s", r.h, r.R0,
                r.wall_seconds, r.avg_iterations, r.max_speed_end);
    if (solver == "wcsph") std::printf(", k = %.4g Pa m, dt = %.4g s", scene.solver.stiffness, scene.time.dt);
    std::printf("\n");
    std::fflush(stdout);
    for (const auto& p : r.series) {
      char line[256];
      std::snprintf(line, sizeof line, "%s,%.6f,%.7f,%.7f,%.7f,%.7f,%.7f,%.7f,%.6f\n", solver.c_str(), p.t, p.a_sim, p.a_ode,
                    p.b_sim, p.b_ode, p.a_sim / p.a_ode - 1, p.b_sim / p.b_ode - 1, p.xy_moment);
      series += line;
    }
    char line[512];
    std::snprintf(line, sizeof line, "%s,%g,%ld,%ld,%.3f,%.2f,%.6f,%.7f,%.7f,%.7f,%.7f,%.6f,%.6f,%.3f,%d\n", solver.c_str(), r.h,
                  r.particles, r.steps, r.avg_iterations, r.wall_seconds, e.t, e.a_sim, e.a_ode, e.b_sim, e.b_ode, r.a_error,
                  r.b_error, bound, ok ? 1 : 0);
    summary += line;
  }
  write_file_atomic((dir / "elliptical_drop_axes.csv").string(), series);
  write_file_atomic((dir / "elliptical_drop.csv").string(), summary);
  // Top: a(t) and b(t), the ODE as lines and each solver's measured axes as points.
  // Bottom: their signed relative errors against the bound.
  std::ostringstream gp;
  gp << "set datafile missing \"NaN\"\n"
     << analysis::gnuplot_png_preamble("elliptical_drop.png", 1200, 1200)
     << "f = \"elliptical_drop_axes.csv\"\nset multiplot layout 2,1\n"
        "set title \"Elliptical drop (Monaghan 1994), A_0 = " << A0 << " 1/s: semi-axes from the second moments\"\n"
        "set xlabel \"t [s]\"\nset ylabel \"semi-axis [m]\"\nset key top left width 2\n"
        "plot f using 2:(strcol(1) eq " << analysis::gnuplot_quote(solvers.front())
     << " ? $6 : NaN) skip 1 with lines lc rgb \"black\" title \"b, exact\", "
        "f using 2:(strcol(1) eq " << analysis::gnuplot_quote(solvers.front())
     << " ? $4 : NaN) skip 1 with lines lc rgb \"black\" dt 2 title \"a, exact\"";
  auto style = [](const std::string& s) {
    return std::string(s == "iisph" ? " pt 6 ps 1.5 lc rgb \"#1f77b4\"" : " pt 4 ps 1.5 lc rgb \"#d62728\"");
  };
  auto label = [](const std::string& s) { return std::string(s == "iisph" ? "IISPH" : "WCSPH"); };
  for (const auto& s : solvers)
    gp << ", f using 2:(strcol(1) eq " << analysis::gnuplot_quote(s) << " ? $5 : NaN) skip 1 with points" << style(s)
       << " title " << analysis::gnuplot_quote("b, " + label(s)) << ", f using 2:(strcol(1) eq " << analysis::gnuplot_quote(s)
       << " ? $3 : NaN) skip 1 with points" << style(s) << " notitle";
  gp << "\nset title \"relative error of the semi-axes (a: dashed, b: solid)\"\nset ylabel \"error [%]\"\n"
        "set yrange [*<-1.5:1.5<*]\nset key bottom left width 2\n"
     << "plot " << 100 * bound << " with lines lc rgb \"black\" dt 3 title \"bound\", " << -100 * bound
     << " with lines lc rgb \"black\" dt 3 notitle";
  for (const auto& s : solvers) {
    gp << ", f using 2:(strcol(1) eq " << analysis::gnuplot_quote(s) << " ? 100*$8 : NaN) skip 1 with linespoints"
       << style(s) << " title " << analysis::gnuplot_quote(label(s)) << ", f using 2:(strcol(1) eq "
       << analysis::gnuplot_quote(s) << " ? 100*$7 : NaN) skip 1 with linespoints" << style(s) << " dt 2 notitle";
  }
  gp << "\nunset multiplot\n";
  report_figure(analysis::run_gnuplot((dir / "elliptical_drop.gp").string(), gp.str()), dir / "elliptical_drop.png");
  std::printf("wrote %s, %s\n", (dir / "elliptical_drop.csv").string().c_str(),
              (dir / "elliptical_drop_axes.csv").string().c_str());
  return failed ? 1 : 0;
}

}  // namespace

int run_validate(const ValidateOptions& o) {
  set_threads(o.threads);
  const fs::path dir = o.output_dir;
  make_directory(dir);
  if (o.what == "hydrostatic") return validate_hydrostatic(o, dir);
  if (o.what == "dam-break") return validate_dam_break(o, dir);
  if (o.what == "elliptical-drop") return validate_elliptical_drop(o, dir);
  throw view::FlagError("validate", o.what, "hydrostatic, dam-break, elliptical-drop");
}

}  // namespace sluice::app
