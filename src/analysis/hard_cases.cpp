#include "analysis/hard_cases.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "scene/scene.h"
#include "solver/leak_check.h"
#include "solver/simulation.h"

namespace sluice::analysis {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& file, const std::string& path, const std::string& what) {
  throw SceneError(file + ": " + path + ": " + what);
}

std::vector<std::string> strings(const json& j, const std::string& file, const std::string& path) {
  if (!j.is_array()) fail(file, path, "expected an array of overrides \"path=value\", got " + j.dump());
  std::vector<std::string> out;
  for (std::size_t i = 0; i < j.size(); ++i) {
    if (!j[i].is_string())
      fail(file, path + "/" + std::to_string(i), "expected a string \"path=value\", got " + j[i].dump());
    out.push_back(j[i].get<std::string>());
  }
  return out;
}

std::vector<SolverType> solvers(const json& j, const std::string& file, const std::string& path) {
  std::vector<SolverType> out;
  for (const json& s : j) {
    if (s == "iisph")
      out.push_back(SolverType::IISPH);
    else if (s == "wcsph")
      out.push_back(SolverType::WCSPH);
    else
      fail(file, path, "invalid solver " + s.dump() + "; must be iisph or wcsph");
  }
  return out;
}

Vec2 centre_of_mass(const Simulation& sim) {
  Vec2 c = Vec2::Zero();
  for (const Vec2& x : sim.fluid().x) c += x;
  return c / static_cast<double>(std::max<Index>(1, sim.fluid().size()));
}

}  // namespace

bool HardCase::expects_stop(SolverType s) const {
  return std::find(expect_stop.begin(), expect_stop.end(), s) != expect_stop.end();
}

const char* outcome_name(Outcome o) {
  switch (o) {
    case Outcome::Held:
      return "held";
    case Outcome::ExpectedStop:
      return "expected_stop";
    case Outcome::Failed:
      break;
  }
  return "failed";
}

std::vector<HardCase> load_suite(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open file");
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw SceneError(path + ": not valid JSON: " + e.what());
  }
  if (!root.is_object() || !root.contains("cases") || !root["cases"].is_array())
    fail(path, "/cases", "missing; the suite is {\"cases\": [ ... ]}");
  std::vector<HardCase> cases;
  const json& list = root["cases"];
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string at = "/cases/" + std::to_string(i);
    const json& j = list[i];
    if (!j.is_object()) fail(path, at, "expected an object, got " + j.dump());
    HardCase c;
    for (const auto& [key, v] : j.items()) {
      const std::string kp = at + "/" + key;
      if (key == "name" && v.is_string())
        c.name = v.get<std::string>();
      else if (key == "scene" && v.is_string())
        c.scene = v.get<std::string>();
      else if (key == "what" && v.is_string())
        c.what = v.get<std::string>();
      else if (key == "set")
        c.set = strings(v, path, kp);
      else if (key == "short")
        c.short_set = strings(v, path, kp);
      else if (key == "iisph")
        c.iisph_set = strings(v, path, kp);
      else if (key == "wcsph")
        c.wcsph_set = strings(v, path, kp);
      else if (key == "resting" && v.is_boolean())
        c.resting = v.get<bool>();
      else if (key == "known_limit" && v.is_boolean())
        c.known_limit = v.get<bool>();
      else if (key == "max_density_error_iisph" && v.is_number() && v.get<double>() > 0)
        c.max_density_error_iisph = v.get<double>();
      else if (key == "max_density_error_wcsph" && v.is_number() && v.get<double>() > 0)
        c.max_density_error_wcsph = v.get<double>();
      else if (key == "why" && v.is_string())
        c.why = v.get<std::string>();
      else if (key == "solvers" && v.is_array())
        c.solvers = solvers(v, path, kp);
      else if (key == "expect_stop" && v.is_array())
        c.expect_stop = solvers(v, path, kp);
      else {
        fail(path, kp,
             "unknown key or wrong type " + v.dump() +
                 "; allowed: name, scene, what, why (strings), set, short, iisph, wcsph (arrays of \"path=value\"), "
                 "solvers, expect_stop ([\"iisph\", \"wcsph\"]), resting, known_limit (bool), "
                 "max_density_error_iisph, max_density_error_wcsph (numbers > 0, percent)");
      }
    }
    if (c.name.empty() || c.scene.empty()) fail(path, at, "needs \"name\" and \"scene\"");
    for (SolverType s : c.expect_stop)
      if (std::find(c.solvers.begin(), c.solvers.end(), s) == c.solvers.end())
        fail(path, at + "/expect_stop", "lists a solver the case does not run");
    if (!c.expect_stop.empty() && c.why.empty())
      fail(path, at, "\"expect_stop\" needs \"why\": the reason the stop is expected");
    cases.push_back(std::move(c));
  }
  return cases;
}

CaseResult run_case(const HardCase& c, const std::string& suite_dir, SolverType solver, bool quick) {
  const bool iisph = solver == SolverType::IISPH;
  CaseResult r;
  r.name = c.name;
  r.solver = iisph ? "iisph" : "wcsph";
  r.known_limit = c.known_limit;
  const std::string failed = c.known_limit ? "FAILED (known limit): " : "FAILED: ";
  r.bound = iisph ? c.max_density_error_iisph : c.max_density_error_wcsph;
  std::vector<std::string> set = c.set;
  set.push_back(std::string("solver.type=") + r.solver);
  // The short version's overrides come before the solver's own, so a solver-specific
  // step or stiffness holds in both versions.
  if (quick) set.insert(set.end(), c.short_set.begin(), c.short_set.end());
  for (const auto& s : iisph ? c.iisph_set : c.wcsph_set) set.push_back(s);
  // WCSPH: the detector stops the run at the bound instead of letting it compress on.
  if (!iisph) set.push_back("stability.max_error_percent=" + std::to_string(r.bound));
  // Both: a single particle through a wall stops the run (the criterion is "none").
  set.push_back("stability.max_leaked_percent=0");
  Scene scene;
  try {
    scene = load_scene((std::filesystem::path(suite_dir) / c.scene).string(), set);
  } catch (const SceneError& e) {
    r.outcome = failed + "scene error: " + e.what();
    return r;
  }
  r.tolerance = scene.solver.tolerance_percent;

  const auto t0 = std::chrono::steady_clock::now();
  bool stopped = false;
  std::string detector;  // the detector's message when it stopped the run
  // The scene's settling phase (time.settle) runs in the constructor and may be stopped.
  std::optional<Simulation> built;
  try {
    built.emplace(scene);
  } catch (const SimulationUnstable& e) {
    r.result = Outcome::Failed;
    r.outcome = failed + "stopped by the detector while settling: " + e.what();
    return r;
  }
  Simulation& sim = *built;
  const Vec2 com0 = centre_of_mass(sim);
  double sum_err = 0, sum_iter = 0;
  try {
    while (!sim.finished()) {
      const StepStats st = sim.step();
      ++r.steps;
      sum_err += st.avg_error_percent;
      sum_iter += st.iterations;
      r.max_density_error = std::max(r.max_density_error, st.density_error_percent);
      // Leaks at every frame time (cheap next to a step, and a particle through a wall
      // stays there): the solid-side test of every object at its pose.
      if (st.frame >= 0) r.leaks += count_fluid_in_solids(scene, sim.fluid().x, sim.time());
      if (c.resting && st.frame >= 0) {
        const double ke = st.kinetic_energy;
        r.ke_peak = std::max(r.ke_peak, ke);
        r.ke_end = ke;
      }
    }
  } catch (const SimulationUnstable& e) {
    stopped = true;
    detector = e.what();
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.simulated = sim.time();
  const double ns = static_cast<double>(std::max<long>(1, r.steps));
  r.avg_error = sum_err / ns;
  r.avg_iterations = sum_iter / ns;
  if (c.resting) r.drift = (centre_of_mass(sim) - com0).norm();

  // The detector stopping a run is a failure unless the case declares it for this
  // solver; a declared stop that does not come means the suite is stale.
  std::ostringstream why;
  if (!stopped) {
    if (r.leaks > 0) why << r.leaks << " fluid particles through a wall; ";
    if (iisph && r.avg_error > 1.02 * r.tolerance) why << "average error " << r.avg_error << " % above the tolerance; ";
    if (r.max_density_error > r.bound)
      why << "density error " << r.max_density_error << " % above " << r.bound << " %; ";
    if (c.resting && !(r.ke_end <= 0.5 * r.ke_peak))
      why << "kinetic energy not decaying (end " << r.ke_end << ", peak " << r.ke_peak << "); ";
    if (c.resting && r.drift > scene.spacing) why << "centre of mass drifted " << r.drift << " m; ";
  }
  std::string problems = why.str();
  if (!problems.empty()) problems.resize(problems.size() - 2);
  const bool expected = c.expects_stop(solver);
  if (stopped && expected) {
    r.result = Outcome::ExpectedStop;
    r.outcome = "expected stop: " + detector;
  } else if (stopped) {
    r.result = Outcome::Failed;
    r.outcome = failed + "stopped by the detector: " + detector;
  } else if (expected) {
    r.result = Outcome::Failed;
    r.outcome = failed + (problems.empty() ? "expected to stop but held: update the suite"
                                           : "expected to stop but ran to the end: " + problems);
  } else if (!problems.empty()) {
    r.result = Outcome::Failed;
    r.outcome = failed + problems;
  } else {
    r.result = Outcome::Held;
    r.outcome = c.known_limit ? "held (a known limit: its full run fails, see its \"what\")" : "held";
  }
  return r;
}

}  // namespace sluice::analysis
