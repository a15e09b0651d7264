/// \file
/// A schedule of samples every 1/rate s of simulation time, for outputs taken after steps of
/// varying length: due at the first step that reaches a multiple of the period (within 1e-6 of
/// a period), so every writer of the same run samples at the same steps.
#pragma once

#include <cmath>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// When outputs are due (see the file's comment).
class SampleClock {
 public:
  /// rate: samples per simulated second (0: none).
  explicit SampleClock(Real rate = 0) : rate_(rate) {}
  /// True when a sample is due at time t (always at the first call); advances the schedule.
  /// force: take a sample now whatever the schedule says. A rate of 0 is never due.
  bool due(Real t, bool force = false) {
    if (!(rate_ > 0)) return false;
    if (!force && t * rate_ < next_ * rate_ - 1e-6) return false;
    next_ = (std::floor(t * rate_ + 1e-6) + 1) / rate_;
    return true;
  }
  /// The next call to due() takes a sample.
  void restart() { next_ = 0; }
  /// Samples per simulated second.
  Real rate() const { return rate_; }

 private:
  Real rate_ = 0;  ///< Hz of simulation time
  Real next_ = 0;  ///< s
};

}  // namespace mpm_sdem
