#include "replay.hpp"

#include <cstdio>

#include "mpm_sdem/ros/recorded_commands.hpp"

namespace mpm_sdem::runner {

CommandReplay::CommandReplay(const std::string& path, Real start)
    : commands_(readRecordedCommands(path, start)) {}

bool CommandReplay::applyDue(World& world) {
  bool changed = false;
  for (; next_ < commands_.size() && commands_[next_].time <= world.time(); ++next_) {
    const WorldCommand& c = commands_[next_];
    const std::string problem = applyCommand(world, c);
    if (problem.empty()) {
      ++applied_;
      changed = changed || c.kind == WorldCommand::Kind::kAddBlock ||
                c.kind == WorldCommand::Kind::kRemoveBlock ||
                c.kind == WorldCommand::Kind::kSetPose;
      continue;
    }
    if (skipped_++ < 10)
      std::fprintf(stderr, "\nwarning: command %ld (t = %.6g s) not applied: %s\n", c.sequence,
                   c.time, problem.c_str());
  }
  return changed;
}

}  // namespace mpm_sdem::runner
