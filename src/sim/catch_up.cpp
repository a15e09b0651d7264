#include "mpm_sdem/sim/catch_up.hpp"

#include <chrono>
#include <cmath>

#include "mpm_sdem/core/stepper.hpp"

namespace mpm_sdem {

CatchUp catchUp(World& world, Time until, Time end_time, Real step_collapse,
                const std::vector<WorldCommand>& commands) {
  const auto wall = std::chrono::steady_clock::now();
  CatchUp out;
  std::size_t next = 0;
  while (next < commands.size() && commands[next].time < world.time()) ++next;
  // A step that would end past `until` by less than this is one that lands on it (the sum of
  // the steps rounds).
  const Time slack = 1e-12 * (1 + std::abs(until));
  Stepper stepper(world, step_collapse);
  while (!reachedEnd(world.time(), end_time)) {
    // Where the runner and the node apply them: before the step is chosen. A step chosen
    // without the commands due now decides whether to stop: those at the time reached stay for
    // the resumed run (only a spawned or removed block changes the step; then it is chosen
    // again).
    PlannedStep step = stepper.plan(end_time);
    if (world.time() + step.dt > until + slack) break;
    bool layout = false;
    for (; next < commands.size() && commands[next].time <= world.time(); ++next) {
      const WorldCommand& c = commands[next];
      if (!applyCommand(world, c).empty()) {
        ++out.skipped;
        continue;
      }
      ++out.applied;
      layout = layout || c.kind == WorldCommand::Kind::kAddBlock ||
               c.kind == WorldCommand::Kind::kRemoveBlock;
    }
    if (layout) step = stepper.plan(end_time);
    if (!step.problem.empty()) {
      out.problem = step.problem;
      break;
    }
    stepper.take(step, out.problem);
    ++out.steps;
    if (!out.problem.empty()) break;
  }
  out.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count();
  return out;
}

}  // namespace mpm_sdem
