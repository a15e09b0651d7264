/// \file
/// What makes a block acceptable: the one set of rules behind the scene parser, Blocks, World and
/// the node's spawn, move and twist requests. Problems name the scene file's keys.
#pragma once

#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem {

/// Its own values: name, outline (core and rounding, or discs), pose, density (dynamic blocks),
/// friction, restitution, adhesion (penalty model only) and twist (see twistProblem).
Problem blockProblem(const BlockDef& def, BlockContactModel model);
/// Farthest reach of the rounded outline from the block frame's origin (m).
Real blockReach(const BlockDef& def);
/// A twist for this block (v of the point its velocity refers to, m/s; w, rad/s): none for a
/// static block, and no point faster than limits::kSpeed (|v| + |w| times the block's reach
/// from its frame origin), which would collapse the material's step (seed 000 eq. 51).
Problem twistProblem(const BlockDef& def, const Vec2& v, Real w);
/// The largest acceleration a load gives any point of the block, whatever its angle (m/s^2): a
/// force (N/m) at point (block frame, m) and a torque (N m/m) give |F| / M + (|r| |F| + |tau|) R /
/// I, r the point's and R the outline's farthest distance from the centre of mass. Infinite for
/// a block without mass (static, kinematic).
Real loadAcceleration(const BlockDef& def, const Vec2& force, const Vec2& point, Real torque);
/// A load held on a block: its loadAcceleration (m/s^2) and how long it still acts (s; infinite:
/// until cleared).
struct HeldLoad {
  Real acceleration = 0;  ///< m/s^2
  Real duration = 0;      ///< s
};
/// The loads held on one block at once, a new one with those held already: their accelerations
/// add up to at most limits::kLoadAcceleration, and the speed they can add, acceleration times
/// duration summed over the loads that end, at most limits::kSpeed (a load held until cleared
/// adds speed without end: the node stops the block when it leaves the domain).
Problem heldLoadsProblem(const std::vector<HeldLoad>& loads);
/// Where it is: a moving block lies inside the domain (the material's grid); a static one, a
/// boundary, may reach outside it but must touch it.
Problem domainProblem(const BlockDef& def, const Vec2& domain_min, const Vec2& domain_max);
/// Stops a moving block at the domain's walls for a step of h (s): a block whose outline box is
/// bounds, reaching reach (m, blockReach) from its frame origin, with that origin's velocity v
/// (m/s) and spin w (rad/s). The spin is dropped when what it sweeps in h (|w| h reach) would
/// carry the box across a side; each velocity component that would carry it across is cut to
/// what reaches the side (zero for a block already outside there). Returns whether it cut.
bool keepInsideDomain(const Box& bounds, Real reach, Real h, const Vec2& domain_min,
                      const Vec2& domain_max, Vec2& v, Real& w);
/// How deep two placed outlines (world-frame parts, placedParts) start inside each other when
/// that is more than 1% of the smaller rounding of the parts that meet, else 0: touching is fine
/// (stacked blocks); more would start the penalty springs loaded and throw the blocks apart.
Real startingOverlap(const std::vector<Spheropolygon>& a, const std::vector<Spheropolygon>& b);
/// Whether blocks a and b may start overlapping: when both are static. They never meet (Box2D
/// moves neither, and the couplings join blocks to material only), so a wall may be built of
/// overlapping parts. A moving block starts clear of every other: an overlap would be a spring
/// loaded at t = 0.
inline bool mayOverlap(const BlockDef& a, const BlockDef& b) {
  return a.type == BodyType::kStatic && b.type == BodyType::kStatic;
}
/// Whether a material point at p lies inside a placed outline (the contact springs would throw
/// it out).
bool insideOutline(const std::vector<Spheropolygon>& parts, const Vec2& p);

}  // namespace mpm_sdem
