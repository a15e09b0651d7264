/// \file
/// Changes made to a world from outside between two steps (a node's obstacle requests, held
/// loads, velocity commands, gravity set at run time), as World's mutators received them. A world
/// reports each one it applies to a log (World::setCommandLog); applyCommand applies a recorded one
/// again. A run re-simulated under its recorded commands, from the same scene, is the same run to
/// the bit; from a changed scene, it shows what the change does under the same commands.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

class World;

/// One change made to a world from outside between two steps, as it was applied.
struct WorldCommand {
  /// What the command did.
  enum class Kind : std::uint8_t {
    kAddBlock = 0,     ///< def
    kRemoveBlock = 1,  ///< block
    kSetPose = 2,      ///< block's frame origin at point (m), angle scalar (rad)
    kSetVelocity = 3,  ///< block's frame origin moving at vector (m/s), scalar (rad/s)
    kAddLoad = 4,      ///< vector: force (N/m, world frame) at point (m), scalar: torque (N m/m)
    kSetGravity = 5,   ///< vector: the acceleration of gravity (m/s^2); block: ""
  };
  Kind kind = Kind::kAddBlock;  ///< which change
  Real time = 0;                ///< s: the world's time when applied, before the step from there
  long step = 0;                ///< the world's step count then
  long sequence = 0;            ///< its place among the world's commands (0, 1, ...)
  std::string block;            ///< the block's name (kAddBlock: def.name)
  Vec2 vector{0, 0};            ///< see kind
  Vec2 point{0, 0};             ///< see kind
  Real scalar = 0;              ///< see kind
  BlockDef def;                 ///< kAddBlock
};

/// Receives each command a world applies (World::setCommandLog).
using CommandLog = std::function<void(const WorldCommand&)>;

/// Applies a recorded command to world at its current time, the block found by name. Returns ""
/// or why it could not be applied (no block of that name, or a block it may not add), leaving
/// the world unchanged then.
std::string applyCommand(World& world, const WorldCommand& command);

}  // namespace mpm_sdem
