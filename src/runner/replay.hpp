// --replay-commands: the obstacle commands a node recorded (its bag's ~commands), applied to this
// run's world at their times, before the step from there, in their recorded order.
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::runner {

class CommandReplay {
 public:
  // Reads every mpm_sdem/RecordedCommand in the bag; those before start (a resumed run's time)
  // are in its checkpoint already. Throws std::runtime_error when the bag cannot be read.
  CommandReplay(const std::string& bag, Real start);
  // Applies the commands due at the world's time (recorded at or before it). One that cannot
  // be applied (its block missing in a changed scene) is skipped with a warning on stderr.
  // Returns true when blocks were added, removed or moved (as the node, the caller then
  // re-sends the static frames).
  bool applyDue(World& world);
  std::size_t count() const { return commands_.size(); }
  std::size_t applied() const { return applied_; }
  std::size_t skipped() const { return skipped_; }

 private:
  std::vector<WorldCommand> commands_;  // by sequence
  std::size_t next_ = 0, applied_ = 0, skipped_ = 0;
};

}  // namespace mpm_sdem::runner
