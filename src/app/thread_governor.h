#pragma once
// The thread count of a run whose user did not fix one (no --threads, no
// OMP_NUM_THREADS), chosen between steps by measuring. On a machine whose cores are busy
// with other work, one thread can beat two: every parallel loop ends in a barrier that
// waits for the thread the other work has descheduled (docs/performance.md, "Threads").
// The bits of a run do not depend on the thread count, so only its speed does.
#include <omp.h>

#include <algorithm>
#include <cstdlib>
#include <vector>

namespace sluice::app {

class ThreadGovernor {
 public:
  // max_threads <= 1, or fixed = true: the governor leaves the count alone.
  ThreadGovernor(int max_threads, bool fixed)
      : max_(max_threads), best_(max_threads), active_(!fixed && max_threads > 1) {}

  // Around Simulation::step(): before_step() sets the count for the step, after_step()
  // takes its wall time and pressure iterations (a step's work is about proportional to
  // iterations + 2, which makes steps of one window comparable).
  void before_step() {
    if (!active_) return;
    const int want = probing_ ? other() : best_;
    if (want != current_) {
      omp_set_num_threads(want);
      current_ = want;
    }
  }
  void after_step(double seconds, int iterations) {
    if (!active_) return;
    const double s = seconds / (std::max(iterations, 0) + 2.0);
    ++steps_at_[current_ == 1 ? 0 : 1];
    if (probing_) {
      trial_.push_back(s);
      if (trial_.size() < kTrial) return;
      probing_ = false;
      if (median(trial_) < 0.95 * median(recent_)) {  // the other count is faster: keep it
        best_ = other_of(best_);
        ++switches_;
        interval_ = kFirstInterval;
      } else {
        interval_ = std::min(2 * interval_, kMaxInterval);  // probe less often while nothing changes
      }
      recent_.clear();
      trial_.clear();
      since_probe_ = 0;
      return;
    }
    recent_.push_back(s);
    if (recent_.size() > kTrial) recent_.erase(recent_.begin());
    ++since_probe_;
    // Probe when due, or at once when the steps got much slower (another program started).
    const bool slower = recent_.size() == kTrial && reference_ > 0 && median(recent_) > 1.3 * reference_;
    if (recent_.size() == kTrial && (since_probe_ >= interval_ || slower)) {
      reference_ = median(recent_);
      probing_ = true;
      if (slower) interval_ = kFirstInterval;
    } else if (recent_.size() == kTrial && reference_ == 0) {
      reference_ = median(recent_);
    }
  }

  bool active() const { return active_; }
  int threads() const { return current_; }  // of the last step (0 before the first)
  int switches() const { return switches_; }
  long steps_on_one() const { return steps_at_[0]; }
  long steps_on_max() const { return steps_at_[1]; }

 private:
  static constexpr std::size_t kTrial = 8;    // steps per comparison
  static constexpr long kFirstInterval = 32;  // steps between probes, doubled up to kMaxInterval
  static constexpr long kMaxInterval = 2048;

  int other_of(int t) const { return t == 1 ? max_ : 1; }
  int other() const { return other_of(best_); }
  static double median(std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  }

  int max_, best_, current_ = 0;
  bool active_, probing_ = false;
  std::vector<double> recent_, trial_;
  double reference_ = 0;
  long since_probe_ = 0, interval_ = kFirstInterval;
  long steps_at_[2] = {0, 0};
  int switches_ = 0;
};

}  // namespace sluice::app
