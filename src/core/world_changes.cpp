// World's changes between steps: blocks added, removed, moved and loaded, and gravity; each
// logged as a command (world_command.hpp) so that a replay makes the same changes.
#include <cmath>
#include <stdexcept>
#include <string>

#include "mpm_sdem/core/exclusions.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

Problem World::placementProblem(const BlockDef& d, bool allow_overlap, BlockId moving) const {
  if (Problem own = blockProblem(d, def_.block_contact.model); !own.empty()) return own;
  // The world with blocks must be one a scene could give (a periodic one could not).
  std::vector<bool> with_blocks = featuresOf(def_);
  with_blocks[static_cast<std::size_t>(Feature::kBlocks)] = true;
  if (Problem p = combinationProblem(with_blocks); !p.empty()) return p;
  if (!coupling_ && !schemeTraits(def_.coupling.scheme).takes_later_blocks && steps_ > 0)
    return {"", std::string("the ") + couplingSchemeName(def_.coupling.scheme) +
                    " coupling builds its wall from the material's initial outline: give the "
                    "scene a block from the start, or use another coupling scheme"};
  if (moving.isNull() && blocks_ && !blocks_->find(d.name).isNull())
    return {"name", "a block named '" + d.name + "' exists"};
  if (Problem where = domainProblem(d, def_.domain.min, def_.domain.max); !where.empty())
    return where;
  if (allow_overlap) return {};
  const std::vector<Spheropolygon> parts = placedParts(d);
  if (blocks_) {
    for (int i = 0; i < blocks_->count(); ++i) {
      if (blocks_->id(i) == moving || mayOverlap(d, blocks_->def(i))) continue;
      if (const Real depth = startingOverlap(parts, blocks_->currentParts(i)); depth > 0)
        return {"position", "it overlaps block '" + blocks_->def(i).name + "' by " +
                                std::to_string(depth) + " m"};
    }
  }
  const Particles& P = mpm_.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (insideOutline(parts, Vec2(P.x[p], P.y[p])))
      return {"position", "it overlaps the material (point " + std::to_string(p) + " is inside)"};
  }
  return {};
}

BlockId World::addBlock(const BlockDef& d) {
  if (!blocks_)
    blocks_ = std::make_unique<Blocks>(std::vector<BlockDef>{}, def_.block_contact,
                                       def_.solver.gravity, std::sqrt(blockMass(d).area));
  const BlockId id = blocks_->add(d);
  linkContactBodies();
  if (!coupling_) initCoupling();
  coupling_->bodiesChanged();
  compose();
  if (command_log_) {
    WorldCommand c = command(WorldCommand::Kind::kAddBlock, id);
    c.def = blocks_->def(blocks_->indexOf(id));
    command_log_(c);
  }
  return id;
}

void World::removeBlock(BlockId id) {
  if (!blocks_) throw std::invalid_argument("removeBlock: the world has no blocks");
  const WorldCommand c = command_log_ && blocks_->indexOf(id) >= 0
                             ? command(WorldCommand::Kind::kRemoveBlock, id)
                             : WorldCommand();
  blocks_->remove(id);
  linkContactBodies();
  coupling_->bodiesChanged();
  compose();
  if (command_log_) command_log_(c);
}

WorldCommand World::command(WorldCommand::Kind kind, BlockId id) {
  WorldCommand c;
  c.kind = kind;
  c.time = time_;
  c.step = steps_;
  c.sequence = commands_++;
  if (!id.isNull()) c.block = blocks_->def(blocks_->indexOf(id)).name;
  return c;
}

void World::setBlockPose(BlockId id, const Vec2& origin, Real angle) {
  blocks_->setPose(id, origin, angle);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetPose, id);
  c.point = origin;
  c.scalar = angle;
  command_log_(c);
}

void World::setBlockVelocity(BlockId id, const Vec2& origin_velocity, Real angular_velocity) {
  blocks_->setVelocity(id, origin_velocity, angular_velocity);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetVelocity, id);
  c.vector = origin_velocity;
  c.scalar = angular_velocity;
  command_log_(c);
}

void World::addBlockLoad(BlockId id, const Vec2& force, const Vec2& point, Real torque) {
  if (!blocks_) throw std::invalid_argument("addBlockLoad: this world has no blocks");
  blocks_->addLoad(id, force, point, torque);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kAddLoad, id);
  c.vector = force;
  c.point = point;
  c.scalar = torque;
  command_log_(c);
}

Problem World::gravityProblem(const Vec2& g) {
  if (!std::isfinite(g.x()) || !std::isfinite(g.y())) return {"gravity", "must be finite"};
  if (const Problem p = limits::rangeProblem(g.norm(), limits::kGravity); !p.empty())
    return {"gravity", "its magnitude " + p.message};
  return {};
}

void World::applyGravity(const Vec2& g) {
  def_.solver.gravity = g;
  mpm_.setGravity(g);
  if (blocks_) blocks_->setGravity(g);
  if (fem_) fem_->setGravity(g);
}

void World::setGravity(const Vec2& g) {
  if (const Problem p = gravityProblem(g); !p.empty()) throw std::invalid_argument(p.text());
  applyGravity(g);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetGravity, BlockId());
  c.vector = g;
  command_log_(c);
}

std::string applyCommand(World& world, const WorldCommand& c) {
  if (c.kind == WorldCommand::Kind::kSetGravity) {
    if (const Problem p = World::gravityProblem(c.vector); !p.empty())
      return "cannot set gravity: " + p.message;
    world.setGravity(c.vector);
    return "";
  }
  if (c.kind == WorldCommand::Kind::kAddBlock) {
    if (Problem p = world.placementProblem(c.def, true); !p.empty())
      return "cannot add block '" + c.def.name + "': " + p.text();
    world.addBlock(c.def);
    return "";
  }
  const BlockId id = world.blocks() ? world.blocks()->find(c.block) : BlockId();
  if (id.isNull()) return "no block named '" + c.block + "'";
  switch (c.kind) {
    case WorldCommand::Kind::kAddBlock:
    case WorldCommand::Kind::kSetGravity:
      break;
    case WorldCommand::Kind::kRemoveBlock:
      world.removeBlock(id);
      break;
    case WorldCommand::Kind::kSetPose:
      world.setBlockPose(id, c.point, c.scalar);
      break;
    case WorldCommand::Kind::kSetVelocity:
      world.setBlockVelocity(id, c.vector, c.scalar);
      break;
    case WorldCommand::Kind::kAddLoad:
      world.addBlockLoad(id, c.vector, c.point, c.scalar);
      break;
  }
  return "";
}

}  // namespace mpm_sdem
