// Box2D's side of the `block_contact: box2d` model: unit conversion, the shapes that stand for
// the blocks' rounded outlines, and the scene's rule for friction and restitution. Internal
// header of the core library.
#pragma once

#include <box2d/box2d.h>

#include <algorithm>
#include <string>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem::detail {

// SI (m) to Box2D units and back; s is Box2D units per metre.
inline b2Vec2 toB2(const Vec2& v, Real s) {
  return b2Vec2(static_cast<float>(v.x() * s), static_cast<float>(v.y() * s));
}
inline Vec2 fromB2(const b2Vec2& v, Real s) {
  return Vec2(v.x / s, v.y / s);
}

// How far each Box2D shape reaches past its block's rounded outline (m). Box2D's contact
// solver leaves two shapes at rest overlapping by anything from 0 (an approach is stopped as
// soon as they touch) to b2_linearSlop (its position solver corrects only deeper overlaps, so
// a harder landing ends there), in Box2D units (1/scale m). A quarter slop each makes the rounded
// outlines touch in the middle of that band, half a slop off at worst.
inline Real box2dReach(Real scale) {
  return 0.25 * b2_linearSlop / scale;
}

// The Box2D polygon of a block's rounded part (counter-clockwise core, 2 or more vertices): Box2D
// puts a skin of b2_polygonRadius around it, so the core is grown by g = a + reach - skin, inward
// when the rounding is below 1.75 slops. Throws when the core cannot shrink that far: an edge would
// turn round or come below a slop long (Box2D would weld its ends), or a segment's rectangle would
// have no width.
std::vector<b2Vec2> box2dPolygon(const Spheropolygon& part, const std::string& block_name,
                                 Real scale);

// The scene's combination rule (scene_reference.md): a contact takes the smaller friction and
// the smaller restitution of its two blocks, not Box2D's sqrt(mu1 mu2) and max(e1, e2). Box2D
// mixes them once when a contact is created; PreSolve runs before every solve of a touching
// contact, the time-of-impact ones included.
class SmallerOfTwo : public b2ContactListener {
 public:
  void PreSolve(b2Contact* contact, const b2Manifold*) override {
    const b2Fixture* a = contact->GetFixtureA();
    const b2Fixture* b = contact->GetFixtureB();
    contact->SetFriction(std::min(a->GetFriction(), b->GetFriction()));
    contact->SetRestitution(std::min(a->GetRestitution(), b->GetRestitution()));
  }
};

}  // namespace mpm_sdem::detail
