#include "mpm_sdem/core/step_guard.hpp"

#include <cstdio>

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem {

std::string StepGuard::problem(const TimeStepChoice& dt) {
  char text[256];
  if (!(dt.dt >= limits::kMinTimeStep)) {
    std::snprintf(text, sizeof text,
                  "the stable step collapsed to %.3g s (%s term), below %.0e s: time would "
                  "stand still",
                  dt.dt, stepLimitName(dt.limit), limits::kMinTimeStep);
    return text;
  }
  if (reference_ == 0) reference_ = dt.dt;
  if (dt.dt < fraction_ * reference_) {
    std::snprintf(text, sizeof text,
                  "the stable step fell to %.3g s (%s term), below %g of the first step "
                  "(%.3g s; limits.step_collapse): the run has likely blown up",
                  dt.dt, stepLimitName(dt.limit), fraction_, reference_);
    return text;
  }
  return "";
}

}  // namespace mpm_sdem
