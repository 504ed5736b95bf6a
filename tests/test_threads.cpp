// The program's OpenMP wait policy (src/app/wait_policy.h): set by the program itself,
// unless the user has set one, and recorded in summary.json.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <thread>
#include <vector>

#include "app/thread_governor.h"
#include "core/parallel.h"
#include "test_process.h"

namespace sluice {
namespace {

using test::CaseDir;

using test::kTinyScene;

// Sets or unsets an environment variable for the scope, and restores it.
class ScopedEnv {
 public:
  ScopedEnv(const char* name, const char* value) : name_(name) {
    if (const char* old = std::getenv(name)) old_ = old;
    value ? setenv(name, value, 1) : unsetenv(name);
  }
  ~ScopedEnv() { old_ ? setenv(name_, old_->c_str(), 1) : unsetenv(name_); }
  ScopedEnv(const ScopedEnv&) = delete;
  ScopedEnv& operator=(const ScopedEnv&) = delete;

 private:
  const char* name_;
  std::optional<std::string> old_;
};

// for_each_chunk (src/core/parallel.h) runs every chunk exactly once, with any number of
// threads, fewer threads than shares (inside another parallel region), or none.
TEST(Threads, EveryChunkRunsOnce) {
  const int before = omp_get_max_threads();
  for (const int threads : {1, 2, 3, 5})
    for (const Index chunks : {0, 1, 2, 7, 100})
      for (const bool parallel : {false, true})
        for (const bool nested : {false, true}) {
          omp_set_num_threads(threads);
          std::vector<std::atomic<int>> runs(static_cast<size_t>(chunks));
          auto run = [&] { for_each_chunk(chunks, parallel, [&](Index c) { ++runs[static_cast<size_t>(c)]; }); };
          if (nested) {
#pragma omp parallel num_threads(2)
#pragma omp single
            run();
          } else {
            run();
          }
          for (Index c = 0; c < chunks; ++c)
            EXPECT_EQ(runs[static_cast<size_t>(c)].load(), 1)
                << "chunk " << c << " of " << chunks << ", " << threads << " threads, parallel " << parallel
                << ", nested " << nested;
        }
  omp_set_num_threads(before);
}

// A thread that falls behind on its own share (here: it takes 3 ms a chunk, the other
// 0.1 ms, as if the host had descheduled it) has part of its share taken by the other:
// without that, it would run all 20 chunks of its share.
TEST(Threads, ChunksOfASlowThreadMove) {
  const int before = omp_get_max_threads();
  omp_set_num_threads(2);
  constexpr Index kChunks = 40;
  std::vector<int> ran_by(kChunks, -1);
  for_each_chunk(kChunks, true, [&](Index c) {
    ran_by[static_cast<size_t>(c)] = omp_get_thread_num();
    std::this_thread::sleep_for(std::chrono::microseconds(omp_get_thread_num() == 0 ? 3000 : 100));
  });
  omp_set_num_threads(before);
  const int by_0 = static_cast<int>(std::count(ran_by.begin(), ran_by.end(), 0));
  if (by_0 == 0 || by_0 == kChunks) GTEST_SKIP() << "OpenMP ran this region on one thread";
  EXPECT_LT(by_0, kChunks / 2) << "thread 1 took none of thread 0's share";
}

std::string recorded_wait_policy() {
  CaseDir dir;
  test::write_text(dir.work() / "tiny.json", kTinyScene);
  const test::Result r = test::run_sluice(dir, {"simulate", "tiny.json", "-o", "out", "-q"});
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(test::read_text(dir.work() / "out" / "summary.json")).value("thread_wait", "");
}

TEST(Threads, ProgramSetsItsWaitPolicy) {
  ScopedEnv spin("GOMP_SPINCOUNT", nullptr), policy("OMP_WAIT_POLICY", nullptr);
  EXPECT_EQ(recorded_wait_policy(), "GOMP_SPINCOUNT=1000");
}

TEST(Threads, UsersWaitPolicyIsKept) {
  {
    ScopedEnv spin("GOMP_SPINCOUNT", nullptr), policy("OMP_WAIT_POLICY", "passive");
    EXPECT_EQ(recorded_wait_policy(), "OMP_WAIT_POLICY=passive");
  }
  ScopedEnv spin("GOMP_SPINCOUNT", "50000"), policy("OMP_WAIT_POLICY", nullptr);
  EXPECT_EQ(recorded_wait_policy(), "GOMP_SPINCOUNT=50000");
}

// Steps fed to the governor with a made-up cost per thread count: it keeps the count that
// is faster and follows when the machine changes.
struct FakeMachine {
  double seconds_on_1, seconds_on_2;
  int run(app::ThreadGovernor& g, int steps) {
    int on_1 = 0;
    for (int k = 0; k < steps; ++k) {
      g.before_step();
      on_1 += g.threads() == 1;
      g.after_step(g.threads() == 1 ? seconds_on_1 : seconds_on_2, 3);
    }
    return on_1;
  }
};

TEST(Threads, GovernorKeepsTheFasterCount) {
  const int saved = omp_get_max_threads();
  app::ThreadGovernor g(2, false);
  FakeMachine idle{1.0, 0.6};
  EXPECT_LT(idle.run(g, 2000), 100);  // probes only, fewer as nothing changes
  EXPECT_EQ(g.threads(), 2);
  FakeMachine busy{1.0, 1.5};  // another program took a core
  EXPECT_GT(busy.run(g, 2000), 1900);
  EXPECT_EQ(g.threads(), 1);
  EXPECT_EQ(g.switches(), 1);
  EXPECT_GT(idle.run(g, 2000), 0);  // back to 2 threads once 1 is slower than 2 again
  EXPECT_EQ(g.threads(), 2);
  omp_set_num_threads(saved);
}

TEST(Threads, GovernorLeavesAFixedCountAlone) {
  app::ThreadGovernor g(2, /*fixed=*/true);
  FakeMachine busy{1.0, 1.5};
  busy.run(g, 500);
  EXPECT_FALSE(g.active());
  EXPECT_EQ(g.threads(), 0);
}

}  // namespace
}  // namespace sluice
