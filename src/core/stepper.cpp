#include "mpm_sdem/core/stepper.hpp"

#include <cstdio>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"

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
                  "the stable step fell to %.3g s (%s term), below %g of the reference step "
                  "(%.3g s: the run's first, or the first after its blocks changed; "
                  "limits.step_collapse): the run has likely blown up",
                  dt.dt, stepLimitName(dt.limit), fraction_, reference_);
    return text;
  }
  return "";
}

PlannedStep Stepper::plan(Time end_time) {
  PlannedStep out;
  out.stable = world_.chooseTimeStep();
  const std::uint64_t layout = world_.blocks() ? world_.blocks()->layoutVersion() : 0;
  if (layout != layout_) {
    layout_ = layout;
    guard_.rebase();
  }
  out.problem = guard_.problem(out.stable);
  out.dt = end_time < std::numeric_limits<Time>::infinity()
               ? stepTowards(out.stable.dt, end_time, world_.time())
               : out.stable.dt;
  return out;
}

StepInfo Stepper::take(const PlannedStep& step, std::string& problem) {
  const StepInfo info = world_.step(step.dt);
  problem.clear();
  if (!info.finite) {
    char text[64];
    std::snprintf(text, sizeof text, "the state became non-finite (dt = %.3g s", step.dt);
    problem = text + (info.block_problem.empty() ? ")" : "; " + info.block_problem + ")");
  }
  return info;
}

}  // namespace mpm_sdem
