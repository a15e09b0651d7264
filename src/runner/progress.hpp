// Progress on the terminal: a rewritten line on a tty, a plain line every few seconds otherwise.
#pragma once

#include <chrono>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::runner {

class Progress {
 public:
  Progress(Real end_time, bool enabled);
  void update(long step, Real sim_time, Real dt, long particles);
  void finish(long step, Real sim_time, long particles);

 private:
  void print(long step, Real sim_time, Real dt, long particles, bool final);
  using Clock = std::chrono::steady_clock;
  Real end_time_;
  bool enabled_, tty_;
  Clock::time_point start_, last_;
};

}  // namespace mpm_sdem::runner
