// The blocks' bodies in Box2D: creation with the mass of the rounded outline, forces in, one
// step, poses out, all in SI across this class (Box2D units inside). Internal header.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem::detail {

// Box2D units per metre for these blocks: the median block one unit across (length_hint when
// there is none); finer with Box2D's own contacts (see the definition).
Real box2dLengthScale(const std::vector<BlockDef>& defs, BlockContactModel model, Real length_hint);

// Box2D's bodies of the listed blocks, in the same order.
class Box2DBodies {
 public:
  Box2DBodies(const Vec2& gravity, Real scale, BlockContactModel model);
  ~Box2DBodies();
  // Box2D's own numbers for a body (Box2D units, single precision): what a checkpoint keeps, so
  // that a rebuilt body is the same to the bit.
  struct Raw {
    float x = 0, y = 0, angle = 0, vx = 0, vy = 0, angular_velocity = 0;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(x, y, angle, vx, vy, angular_velocity);
    }
  };
  // Appends the body of a block (with a fixture per part when Box2D does the contacts), where
  // def puts it or, given at, where at does. Throws std::invalid_argument, before anything is
  // created, when Box2D cannot take the outline.
  void add(const BlockDef& def, const std::vector<Spheropolygon>& parts, const MassProperties& mass,
           const Raw* at = nullptr);
  Raw raw(int i) const;
  void remove(int i);
  // Centre of mass (the Box2D body's origin) and angle, velocity of the centre of mass and
  // angular velocity.
  Vec2 centre(int i) const;
  Real angle(int i) const;
  Vec2 velocity(int i) const;
  Real angularVelocity(int i) const;
  void setTransform(int i, const Vec2& centre, Real angle);
  void setVelocity(int i, const Vec2& velocity, Real angular_velocity);
  // A force at the centre of mass (N/m) and a torque (N m/m) for the next step (dynamic bodies).
  void applyForce(int i, const Vec2& force, Real torque);
  void step(Real h);
  // The acceleration of gravity (m/s^2) from the next step on.
  void setGravity(const Vec2& gravity);
  // After step(h): each touching contact's mean force over the step, to blocks'
  // recordContactForce (the bodies' places in the list are the blocks').
  void reportContacts(Real h, Blocks& blocks) const;

 private:
  struct World;
  std::unique_ptr<World> w_;
  Real scale_;
  BlockContactModel model_;
};

}  // namespace mpm_sdem::detail
