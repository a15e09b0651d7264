// What makes a block acceptable: the one set of rules behind the scene parser, Blocks, World and
// the node's spawn, move and twist requests. Problems name the scene file's keys.
#pragma once

#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem {

// Its own values: name, outline (core and rounding, or discs), pose, density (dynamic blocks),
// friction, restitution, adhesion (penalty model only) and twist (see twistProblem).
Problem blockProblem(const BlockDef& def, BlockContactModel model);
// Farthest reach of the rounded outline from the block frame's origin (m).
Real blockReach(const BlockDef& def);
// A twist for this block (v of the point its velocity refers to, m/s; w, rad/s): none for a
// static block, and no point faster than limits::kSpeed (|v| + |w| times the block's reach
// from its frame origin), which would collapse the material's step (seed 000 eq. 51).
Problem twistProblem(const BlockDef& def, const Vec2& v, Real w);
// Where it is: a moving block lies inside the domain (the material's grid); a static one, a
// boundary, may reach outside it but must touch it.
Problem domainProblem(const BlockDef& def, const Vec2& domain_min, const Vec2& domain_max);
// How deep two placed outlines (world-frame parts, placedParts) start inside each other when
// that is more than 1% of the smaller rounding of the parts that meet, else 0: touching is fine
// (stacked blocks); more would start the penalty springs loaded and throw the blocks apart.
Real startingOverlap(const std::vector<Spheropolygon>& a, const std::vector<Spheropolygon>& b);
// Whether a material point at p lies inside a placed outline (the contact springs would throw
// it out).
bool insideOutline(const std::vector<Spheropolygon>& parts, const Vec2& p);

}  // namespace mpm_sdem
