#pragma once
// The progress line's estimate of the time left: the wall time per simulated second over
// the last few frames, not since the start. The first frames carry the set-up (renderer,
// first neighbour grid, a settling fluid) and made the first estimate 17 times the real
// time; before `min_frames` frames there is no estimate at all.
#include <deque>
#include <optional>
#include <utility>

namespace sluice::app {

class EtaEstimate {
 public:
  explicit EtaEstimate(int window = 10, int min_frames = 3) : window_(window), min_frames_(min_frames) {}

  // A frame reached after `wall` seconds at simulated time `t` (the run's start included).
  void add(double wall, double t) {
    samples_.emplace_back(wall, t);
    ++frames_;
    while (static_cast<int>(samples_.size()) > window_ + 1) samples_.pop_front();
  }

  // Wall seconds left until simulated time `end`; nullopt until more than min_frames
  // frames followed the first sample (the run's start).
  std::optional<double> seconds_left(double end) const {
    if (frames_ - 1 <= min_frames_ || samples_.size() < 2) return std::nullopt;
    const double dwall = samples_.back().first - samples_.front().first;
    const double dt = samples_.back().second - samples_.front().second;
    if (!(dt > 0)) return std::nullopt;
    const double left = end - samples_.back().second;
    return left > 0 ? dwall / dt * left : 0.0;
  }

 private:
  int window_, min_frames_;
  long frames_ = 0;
  std::deque<std::pair<double, double>> samples_;  // (wall [s], simulated [s])
};

}  // namespace sluice::app
