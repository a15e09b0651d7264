// Warnings throttled in wall time, the first at once. rosconsole's ROS_*_THROTTLE count ROS time,
// which under /use_sim_time is the simulation's: it starts at 0, so the first warning waited
// until the simulated time passed the period (5 s of simulated time were 100 s of wall time on
// the blade scene), and it races ahead or stands still with the simulation.
#pragma once

#include <ros/console.h>

#include <atomic>
#include <chrono>
#include <limits>

namespace mpm_sdem::node {

// True on the first call, then at most once per period (s of wall time); thread-safe.
class WallThrottle {
 public:
  explicit WallThrottle(double period_s)
      : period_(
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s))) {}
  bool ready() {
    const Clock::rep now = Clock::now().time_since_epoch().count();
    Clock::rep last = last_.load(std::memory_order_relaxed);
    if (last != kNever && now - last < period_.count()) return false;
    return last_.compare_exchange_strong(last, now, std::memory_order_relaxed);
  }

 private:
  using Clock = std::chrono::steady_clock;
  static constexpr Clock::rep kNever = std::numeric_limits<Clock::rep>::min();
  Clock::duration period_;
  std::atomic<Clock::rep> last_{kNever};
};

}  // namespace mpm_sdem::node

// ROS_WARN_THROTTLE in wall time, the first at once (one throttle per call site).
#define MPM_SDEM_WARN_THROTTLE(period, ...)                                \
  do {                                                                     \
    static ::mpm_sdem::node::WallThrottle mpm_sdem_throttle_site_(period); \
    if (mpm_sdem_throttle_site_.ready()) ROS_WARN(__VA_ARGS__);            \
  } while (false)
