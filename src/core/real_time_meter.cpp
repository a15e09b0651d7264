#include "mpm_sdem/core/real_time_meter.hpp"

namespace mpm_sdem {

double RealTimeMeter::runningSeconds(Clock::time_point now) const {
  return banked_ + (running_ ? std::chrono::duration<double>(now - since_).count() : 0.0);
}

void RealTimeMeter::setRunning(bool running, Clock::time_point now) {
  if (running == running_) return;
  banked_ = runningSeconds(now);
  running_ = running;
  since_ = now;
}

void RealTimeMeter::sample(Real sim_time, Clock::time_point now) {
  const double wall = runningSeconds(now);
  samples_.emplace_back(wall, sim_time);
  // Keep one sample at or before the window's start, so that the window is always full.
  while (samples_.size() > 2 && samples_[1].first <= wall - kWindow) samples_.pop_front();
}

double RealTimeMeter::factor() const {
  if (samples_.size() < 2) return 0;
  const double wall = samples_.back().first - samples_.front().first;
  return wall > 0 ? (samples_.back().second - samples_.front().second) / wall : 0;
}

void RealTimeMeter::clear() {
  samples_.clear();
}

}  // namespace mpm_sdem
