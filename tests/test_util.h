#pragma once
// Shared helpers of the kernel, neighbour and physics tests: scenes from inline JSON,
// particle state ordered by id, and a bitwise hash of that state.
#include <omp.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "solver/simulation.h"

namespace sluice::test {

// A scene from JSON text (format of docs/scene_format.md); throws SceneError.
inline Scene scene_from_json(const std::string& text, const std::vector<std::string>& overrides = {}) {
  return parse_scene(text, "inline.json", overrides);
}

// Fluid state copied into the scene's initial particle order (fluid().id), so runs
// with different reorderings or thread counts compare particle by particle.
struct OrderedState {
  std::vector<Vec2> x, v;
  std::vector<double> p, rho;
};

inline OrderedState ordered_state(const Simulation& sim) {
  const FluidParticles& f = sim.fluid();
  OrderedState s;
  const size_t n = static_cast<size_t>(f.size());
  s.x.resize(n);
  s.v.resize(n);
  s.p.resize(n);
  s.rho.resize(n);
  for (size_t k = 0; k < n; ++k) {
    const size_t i = static_cast<size_t>(f.id[k]);
    s.x[i] = f.x[k];
    s.v[i] = f.v[k];
    s.p[i] = f.p[k];
    s.rho[i] = f.rho[k];
  }
  return s;
}

// FNV-1a over the bits of positions, velocities and pressures in id order.
inline std::uint64_t state_hash(const Simulation& sim) {
  const OrderedState s = ordered_state(sim);
  std::uint64_t h = 1469598103934665603ULL;
  auto mix = [&](double d) {
    std::uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    for (int b = 0; b < 8; ++b) {
      h ^= (bits >> (8 * b)) & 0xffu;
      h *= 1099511628211ULL;
    }
  };
  for (size_t i = 0; i < s.x.size(); ++i) {
    mix(s.x[i].x());
    mix(s.x[i].y());
    mix(s.v[i].x());
    mix(s.v[i].y());
    mix(s.p[i]);
  }
  return h;
}

// A run to its end: the average solver iterations per step and the largest realized
// compression (Eq. 15 at a step's start) [%].
struct RunAverages {
  double iterations = 0, largest_compression = 0;
};
inline RunAverages run_to_end(Simulation& sim) {
  RunAverages r;
  long steps = 0;
  while (!sim.finished()) {
    const StepStats st = sim.step();
    r.iterations += st.iterations;
    r.largest_compression = std::max(r.largest_compression, st.density_error_percent);
    ++steps;
  }
  if (steps > 0) r.iterations /= static_cast<double>(steps);
  return r;
}

// Restores the OpenMP thread count when leaving a scope.
class ThreadCount {
 public:
  explicit ThreadCount(int n) : saved_(omp_get_max_threads()) { omp_set_num_threads(n); }
  ~ThreadCount() { omp_set_num_threads(saved_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int saved_;
};

}  // namespace sluice::test
