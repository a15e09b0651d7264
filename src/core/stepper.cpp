#include "mpm_sdem/core/stepper.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem {

Real stepTowards(Real dt, Time end_time, Time time) {
  const Time remaining = end_time - time;
  return static_cast<Real>(remaining < 1.5 * dt && remaining > dt ? 0.5 * remaining
                                                                  : std::min<Time>(dt, remaining));
}

bool reachedEnd(Time time, Time end_time) {
  return time >= end_time - 1e-9 * std::abs(end_time);
}

StepInfo stepStable(World& world, Time end_time) {
  return world.step(stepTowards(world.chooseTimeStep().dt, end_time, world.time()));
}

StepInfo runUntil(World& world, Time end_time) {
  StepInfo info;
  while (!reachedEnd(world.time(), end_time) && info.finite) info = stepStable(world, end_time);
  return info;
}

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
  out.dt = stepTowards(out.stable.dt, end_time, world_.time());
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
