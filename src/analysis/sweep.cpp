#include "analysis/sweep.h"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>

#include "io/csv.h"
#include "solver/simulation.h"

namespace sluice::analysis {

using io::csv_quote;
using io::InputError;
using io::join;
using io::parse_csv_line;
using io::split;

namespace {

const char* kHeader =
    "scene,set,solver,particles,threads,stable,message,steps,simulated_s,wall_s,s_per_simulated_s,avg_iterations,"
    "avg_density_error_percent,max_density_error_percent,ms_neighbors,ms_nonpressure,ms_pressure,ms_integrate,"
    "ms_total,ms_moving_boundaries,pareto,avg_dt_s,min_dt_s,avg_dt_of_dt_max_percent,label";
// The header before the step-size and label columns: such files are still read (--collect).
const char* kHeader21 =
    "scene,set,solver,particles,threads,stable,message,steps,simulated_s,wall_s,s_per_simulated_s,avg_iterations,"
    "avg_density_error_percent,max_density_error_percent,ms_neighbors,ms_nonpressure,ms_pressure,ms_integrate,"
    "ms_total,ms_moving_boundaries,pareto";

// The values of "V1,V2,...", split at the commas outside brackets, braces and quotes:
// solver.gravity=[0,-9.81],[0,-5] is two values, each a JSON array.
std::vector<std::string> split_values(const std::string& text) {
  std::vector<std::string> values(1);
  int depth = 0;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted) {
      if (c == '\\' && i + 1 < text.size()) {
        values.back() += text.substr(i++, 2);  // an escaped quote does not end the string
        continue;
      }
      if (c == '"') quoted = false;
    } else if (c == '"') {
      quoted = true;
    } else if (c == '[' || c == '{') {
      ++depth;
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    } else if (c == ',' && depth == 0) {
      values.emplace_back();
      continue;
    }
    values.back() += c;
  }
  return values;
}

}  // namespace

std::string SweepRun::label() const {
  std::vector<std::string> values;
  for (const std::string& kv : set)
    values.push_back(kv == "time.dt=null" ? "adaptive dt" : kv.substr(kv.find('=') + 1));
  return join(values, ", ");
}

SweepAxis parse_sweep(const std::string& text) {
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0 || eq + 1 == text.size())
    throw SceneError("--sweep " + text + ": expected KEY=V1,V2,... (KEY as for --set, e.g. solver.type=iisph,wcsph)");
  SweepAxis a;
  a.key = text.substr(0, eq);
  a.values = split_values(text.substr(eq + 1));
  for (const auto& v : a.values)
    if (v.empty()) throw SceneError("--sweep " + text + ": an empty value; values are separated by single commas");
  return a;
}

std::vector<std::vector<std::string>> sweep_combinations(const std::vector<SweepAxis>& axes) {
  std::vector<std::vector<std::string>> combos{{}};
  for (const SweepAxis& a : axes) {
    std::vector<std::vector<std::string>> next;
    for (const auto& c : combos)
      for (const auto& v : a.values) {
        auto n = c;
        n.push_back(a.key + "=" + v);
        next.push_back(std::move(n));
      }
    combos = std::move(next);
  }
  return combos;
}

SweepRun run_sweep_point(const Scene& scene, const std::vector<std::string>& set,
                         const std::function<void(const StepStats&)>& on_step, bool brute_force) {
  SweepRun r;
  r.scene = scene.name;
  r.set = set;
  r.solver = to_string(scene.solver.type);
  r.particles = static_cast<long>(scene.fluid_x.size());
  r.threads = omp_get_max_threads();
  double iterations = 0, error = 0, dt_sum = 0;
  const double dt_max = scene.time.dt > 0 ? scene.time.dt : scene.time.dt_max;
  r.min_dt = HUGE_VAL;
  const auto t0 = std::chrono::steady_clock::now();
  std::unique_ptr<Simulation> sim;
  try {
    // Inside: a settle (time.settle) can go unstable too, and is recorded as the run's.
    sim = std::make_unique<Simulation>(scene);
    sim->set_brute_force_neighbors(brute_force);
    while (!sim->finished()) {
      const StepStats st = sim->step();
      if (on_step) on_step(st);
      ++r.steps;
      iterations += st.iterations;
      error += st.density_error_percent;
      dt_sum += st.dt;
      r.min_dt = std::min(r.min_dt, st.dt);
      r.max_density_error = std::max(r.max_density_error, st.density_error_percent);
      const double ms[6] = {st.ms(Phase::Neighbors),
                            st.ms(Phase::NonPressure),
                            st.ms(Phase::Pressure),
                            st.ms(Phase::Integrate),
                            st.ms_total,
                            st.ms(Phase::Boundary)};
      for (int k = 0; k < 6; ++k) r.ms_phase[k] += ms[k];
    }
  } catch (const SimulationUnstable& e) {
    r.stable = false;
    r.message = e.what();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.simulated = sim ? sim->time() : 0.0;
  const double ns = r.steps > 0 ? static_cast<double>(r.steps) : 1.0;
  r.avg_iterations = iterations / ns;
  r.avg_density_error = error / ns;
  for (double& ms : r.ms_phase) ms /= ns;
  r.avg_dt = dt_sum / ns;
  if (r.steps == 0) r.min_dt = 0;
  r.dt_of_max_percent = dt_max > 0 ? 100.0 * r.avg_dt / dt_max : 0;
  return r;
}

void mark_pareto_front(std::vector<SweepRun>& runs) {
  for (SweepRun& a : runs) {
    a.pareto = a.stable;
    if (!a.stable) continue;
    const double ta = a.seconds_per_simulated_second(), ea = a.avg_density_error;
    for (const SweepRun& b : runs) {
      if (&a == &b || !b.stable) continue;
      const double tb = b.seconds_per_simulated_second(), eb = b.avg_density_error;
      if (tb <= ta && eb <= ea && (tb < ta || eb < ea)) {
        a.pareto = false;
        break;
      }
    }
  }
}

std::string sweep_csv(const std::vector<SweepRun>& runs) {
  std::string text = std::string(kHeader) + "\n";
  for (const SweepRun& r : runs) {
    char nums[640];
    std::snprintf(nums, sizeof nums, "%ld,%.6g,%.6g,%.6g,%.4f,%.6f,%.6f,%.5f,%.5f,%.5f,%.5f,%.5f,%.5f,%d", r.steps,
                  r.simulated, r.wall_seconds, r.seconds_per_simulated_second(), r.avg_iterations, r.avg_density_error,
                  r.max_density_error, r.ms_phase[0], r.ms_phase[1], r.ms_phase[2], r.ms_phase[3], r.ms_phase[4],
                  r.ms_phase[5], r.pareto ? 1 : 0);
    char dts[128];
    std::snprintf(dts, sizeof dts, "%.6g,%.6g,%.2f", r.avg_dt, r.min_dt, r.dt_of_max_percent);
    text += csv_quote(r.scene) + "," + csv_quote(join(r.set, ";")) + "," + r.solver + "," +
            std::to_string(r.particles) + "," + std::to_string(r.threads) + "," + (r.stable ? "1" : "0") + "," +
            csv_quote(r.message) + "," + nums + "," + dts + "," + csv_quote(r.label()) + "\n";
  }
  return text;
}

std::vector<SweepRun> read_sweep_csv(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot open file");
  std::string line;
  if (!std::getline(in, line) || (line != kHeader && line != kHeader21))
    throw InputError(path + ": line 1: not a sluice bench CSV (expected the header " + std::string(kHeader) + ")");
  const std::size_t fields = line == kHeader ? 25 : 21;
  std::vector<SweepRun> runs;
  for (long n = 2; std::getline(in, line); ++n) {
    if (line.empty()) continue;
    const auto f = parse_csv_line(line);
    if (f.size() != fields)
      throw InputError(path + ": line " + std::to_string(n) + ": expected " + std::to_string(fields) +
                       " fields, found " + std::to_string(f.size()));
    try {
      SweepRun r;
      r.scene = f[0];
      if (!f[1].empty()) r.set = split(f[1], ';');  // overrides may hold spaces, never ';'
      r.solver = f[2];
      r.particles = std::stol(f[3]);
      r.threads = std::stoi(f[4]);
      r.stable = f[5] == "1";
      r.message = f[6];
      r.steps = std::stol(f[7]);
      r.simulated = std::stod(f[8]);
      r.wall_seconds = std::stod(f[9]);
      r.avg_iterations = std::stod(f[11]);
      r.avg_density_error = std::stod(f[12]);
      r.max_density_error = std::stod(f[13]);
      for (int k = 0; k < 6; ++k) r.ms_phase[k] = std::stod(f[14 + k]);
      if (fields == 25) {
        r.avg_dt = std::stod(f[21]);
        r.min_dt = std::stod(f[22]);
        r.dt_of_max_percent = std::stod(f[23]);
      }
      runs.push_back(r);
    } catch (const std::logic_error&) {
      throw InputError(path + ": line " + std::to_string(n) + ": a field that should be a number is not");
    }
  }
  return runs;
}

std::string sweep_plot_script(const std::vector<SweepRun>& runs, const std::string& title) {
  struct Solver {
    const char* name;
    const char* title;
    const char* style;
  };
  // IISPH blue, WCSPH red, as in every figure of the project.
  const Solver solvers[] = {{"iisph", "IISPH", "pt 7 ps 1.6 lc rgb \"#1f77b4\""},
                            {"wcsph", "WCSPH", "pt 5 ps 1.6 lc rgb \"#d62728\""}};
  auto drawable = [](const SweepRun& r) {
    return r.stable && r.seconds_per_simulated_second() > 0 && r.avg_density_error > 0;
  };
  auto point = [](const SweepRun& r) {
    char buf[96];
    std::snprintf(buf, sizeof buf, "%.6g %.6g ", r.seconds_per_simulated_second(), r.avg_density_error);
    std::string label = r.label();
    for (char& c : label) c = c == '"' ? '\'' : c;
    return buf + std::string("\"") + label + "\"\n";
  };
  std::string data, plot;
  auto add = [&](const std::string& part) { plot += (plot.empty() ? "plot " : ", \\\n     ") + part; };
  for (const Solver& sv : solvers) {
    std::string block;
    for (const SweepRun& r : runs)
      if (r.solver == sv.name && drawable(r)) block += point(r);
    if (block.empty()) continue;
    data += "$" + std::string(sv.name) + " << EOD\n" + block + "EOD\n";
    add("$" + std::string(sv.name) + " using 1:2 with points " + sv.style + " title \"" + sv.title + "\"");
    add("$" + std::string(sv.name) +
        " using 1:2:3 with labels offset char 0.8,0.8 left font \",13\" noenhanced notitle");
  }
  std::vector<const SweepRun*> front;
  for (const SweepRun& r : runs)
    if (r.pareto && drawable(r)) front.push_back(&r);
  std::sort(front.begin(), front.end(), [](const SweepRun* a, const SweepRun* b) {
    return a->seconds_per_simulated_second() < b->seconds_per_simulated_second();
  });
  if (front.size() > 1) {
    data += "$pareto << EOD\n";
    for (const SweepRun* r : front) data += point(*r);
    data += "EOD\n";
    add("$pareto using 1:2 with lines lc rgb \"black\" dt 2 title \"Pareto front\"");
  }
  if (plot.empty()) plot = "set label 1 \"no stable run to draw\" at graph 0.5, 0.5 center\nplot NaN notitle";
  // Inline rows are space-separated with quoted labels (the preamble reads CSV).
  return "set datafile separator whitespace\n" + data + "set title \"" + title + "\" noenhanced\n" +
         "set logscale xy\nset xlabel \"wall time per simulated second [s]\"\n"
         "set ylabel \"average density error [%]\"\nset key outside top center horizontal box opaque\n"
         "set offsets graph 0.05, graph 0.15, graph 0.1, graph 0.05\n" +
         plot + "\n";
}

std::string sweep_markdown(const std::vector<SweepRun>& runs) {
  std::string md =
      "| run | overrides | solver | particles | stable | s / sim s | steps | avg dt [s] | % of dt_max | iterations | "
      "avg err % | max err % | neighb ms | nonpres ms | pressure ms | integr ms | Pareto |\n"
      "|---:|---|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|:---:|\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SweepRun& r = runs[i];
    char line[640];
    std::snprintf(line, sizeof line,
                  "| %zu | `%s` | %s | %ld | %s | %.3f | %ld | %.3g | %.0f | %.2f | %.4f | %.4f | %.3f | %.3f | %.3f | "
                  "%.3f | %s |\n",
                  i + 1, join(r.set, " ").c_str(), r.solver.c_str(), r.particles,
                  r.stable ? "yes" : ("no, t = " + std::to_string(r.simulated)).c_str(),
                  r.seconds_per_simulated_second(), r.steps, r.avg_dt, r.dt_of_max_percent, r.avg_iterations,
                  r.avg_density_error, r.max_density_error, r.ms_phase[0], r.ms_phase[1], r.ms_phase[2], r.ms_phase[3],
                  r.pareto ? "**yes**" : "");
    md += line;
  }
  return md;
}

}  // namespace sluice::analysis
