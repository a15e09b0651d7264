/// \file
/// The real-time factor (simulated seconds per wall-clock second) over a sliding window of running
/// wall time: paused time is not counted, and a window of a few seconds smooths the step-to-step
/// swing of a paced run. One meter feeds the node's ~stats, its bag and its log.
#pragma once

#include <chrono>
#include <deque>
#include <utility>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Simulated seconds per wall-clock second over a sliding window (see the file's comment).
class RealTimeMeter {
 public:
  using Clock = std::chrono::steady_clock;  ///< wall time, never set back
  static constexpr double kWindow = 2.0;    ///< s of running wall time

  /// Running or not from now on; paused wall time is left out of every factor.
  void setRunning(bool running, Clock::time_point now = Clock::now());
  /// The simulated time reached now (after a step).
  void sample(Real sim_time, Clock::time_point now = Clock::now());
  /// Over the last kWindow s of running time (or all of it, when shorter); 0 before two samples.
  double factor() const;
  /// Forget the samples (after a reset: simulated time starts again).
  void clear();

 private:
  double runningSeconds(Clock::time_point now) const;
  bool running_ = false;
  Clock::time_point since_{};
  double banked_ = 0;                            ///< running seconds before since_
  std::deque<std::pair<double, Real>> samples_;  ///< (running wall s, simulated s)
};

}  // namespace mpm_sdem
