// The commands a run applied to its world (a node's requests, held loads and velocity
// commands), as its bag recorded them on ~commands: for mpm_sdem_run --replay-commands and for
// a resume that catches up from a checkpoint (sim/catch_up.hpp).
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "mpm_sdem/core/world_command.hpp"

namespace mpm_sdem {

// The bag's commands applied at times in [from, to] s, ordered by sequence. Throws
// std::runtime_error when the bag cannot be read.
std::vector<WorldCommand> readRecordedCommands(const std::string& bag, Real from,
                                               Real to = std::numeric_limits<Real>::infinity());

}  // namespace mpm_sdem
