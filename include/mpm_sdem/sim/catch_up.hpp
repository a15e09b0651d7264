/// \file
/// A run resumed from a checkpoint before the time it was asked to resume at (BAG\@TIME: a
/// bag keeps one checkpoint per simulated second by default) is brought up to that time as the
/// run that recorded it took it: the same steps, landed on the same end time, under the commands it
/// recorded, each applied when due. Runs are bit-identical whatever the threads, so the state
/// reached is the recorded run's state at that step, and a run resumed there continues it to
/// the bit. The cost is the simulation of the gap (at most the checkpoints' spacing).
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/core/world_command.hpp"

namespace mpm_sdem {

/// What catchUp did.
struct CatchUp {
  long steps = 0;           ///< steps taken
  std::size_t applied = 0;  ///< recorded commands applied
  std::size_t skipped = 0;  ///< recorded commands that could not be applied (a changed scene)
  std::string problem;      ///< not empty: a step failed (one clause); the world is unsound
  double wall_seconds = 0;  ///< s of wall time it took
};

/// Steps world, just restored from a checkpoint, to the last step that ends at or before
/// `until` (s), as the run that wrote the checkpoint took them: the stable step landed on
/// end_time (stepTowards), checked by a StepGuard of step_collapse (limits.step_collapse), and
/// before each step the commands recorded at or before the world's time applied (commands:
/// ordered by sequence; those before the world's time are in the checkpoint and skipped). The
/// commands due at the time reached are left for the resumed run, as a checkpoint leaves them.
CatchUp catchUp(World& world, Time until, Time end_time, Real step_collapse,
                const std::vector<WorldCommand>& commands);

}  // namespace mpm_sdem
