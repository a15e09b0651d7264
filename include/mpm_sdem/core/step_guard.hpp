// The stop for a run whose stable step has collapsed. An unstable run does not always raise its
// total energy past limits.energy_growth (gravity's part dominates a settling flow): the
// partitioned blow-up of 2026-11-28 drove one point at 4,000 m/s^2 and cut the CFL step from
// 31 us to 2 ns while the total stayed below the limit. No accepted input shortens a step by
// anything near a thousand times in a sane run (the fastest command, 1e3 m/s, takes a sand's
// CFL step down by 30-100 times), so a step far below the first one is a symptom of a blow-up.
// The runner and the node ask it before every step.
#pragma once

#include <string>

#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

class StepGuard {
 public:
  // collapse_fraction: the stop lies at this fraction of the reference step (scene key
  // limits.step_collapse).
  explicit StepGuard(Real collapse_fraction) : fraction_(collapse_fraction) {}
  // The next step checked becomes the reference: a run's start, its resumption, and in the
  // node a request that changed the world (a spawned light obstacle may shorten the step).
  void rebase() { reference_ = 0; }
  // Empty when the chosen step may be taken; otherwise what is wrong, one clause without a
  // full stop, for the caller to place in its message. Below limits::kMinTimeStep always.
  std::string problem(const TimeStepChoice& dt);
  Real reference() const { return reference_; }

 private:
  Real fraction_;
  Real reference_ = 0;  // s; 0 until the first step after a rebase
};

}  // namespace mpm_sdem
