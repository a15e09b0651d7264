/// \file
/// Several kinds of contact bodies as one (the rigid blocks and the FEM bodies): their shapes one
/// kind after another, every question passed to the kind that owns the shape. World hands the
/// schemes a kind directly when the scene has one only, so a set costs nothing then.
#pragma once

#include <vector>

#include "mpm_sdem/core/coupling/contact_bodies.hpp"

namespace mpm_sdem {

/// Several ContactBodies (the blocks and the FEM bodies) answered as one, their shapes numbered
/// one after the other.
class ContactSet final : public ContactBodies {
 public:
  /// The members are not owned and must outlive the set; their bodies' keys must differ (the
  /// blocks' use 44 bits, the FEM bodies' have bit 62 set). Call refresh() when a member's shapes
  /// change in number.
  explicit ContactSet(std::vector<ContactBodies*> members);
  /// Takes the members' shapes afresh (after a member's bodies came or went).
  void refresh();

  int shapeCount() const override { return first_.back(); }
  int bodyOf(int s) const override;
  std::uint64_t bodyKey(int s) const override { return at(s).bodyKey(local(s)); }
  const Vec2* coreVertices(int s) const override { return at(s).coreVertices(local(s)); }
  int coreVertexCount(int s) const override { return at(s).coreVertexCount(local(s)); }
  Real rounding(int s) const override { return at(s).rounding(local(s)); }
  CoreDistance closest(int s, const Vec2& x) const override { return at(s).closest(local(s), x); }
  Box bounds(int s) const override { return at(s).bounds(local(s)); }
  Real friction(int s) const override { return at(s).friction(local(s)); }
  Real dampingRatio(int s) const override { return at(s).dampingRatio(local(s)); }
  bool movable(int s) const override { return at(s).movable(local(s)); }
  Real mass(int s) const override { return at(s).mass(local(s)); }
  Vec2 velocityAt(int s, const Vec2& x) const override { return at(s).velocityAt(local(s), x); }
  Mat2 inverseMass(int s, const Vec2& x) const override { return at(s).inverseMass(local(s), x); }
  Real lightestMass() const override;
  Real maxDampingRatio() const override;
  BodyPose pose(int s) const override { return at(s).pose(local(s)); }
  Real movedSince(int s, const BodyPose& then) const override {
    return at(s).movedSince(local(s), then);
  }
  void beginCoupling(Real dt) override;
  Vec2 trialVelocityAt(int s, const Vec2& x) const override {
    return at(s).trialVelocityAt(local(s), x);
  }
  void applyForce(int s, const Vec2& force, const Vec2& x) override {
    at(s).applyForce(local(s), force, x);
  }
  void applyImpulse(int s, const Vec2& impulse, const Vec2& x, Real dt) override {
    at(s).applyImpulse(local(s), impulse, x, dt);
  }
  Real stableStep(Real kappa2) const override;
  int step(Real dt, Real max_substep) override;
  void pushForce(int s, const Vec2& force, const Vec2& x) override {
    at(s).pushForce(local(s), force, x);
  }
  void recordForce(int s, const Vec2& force, const Vec2& x) override {
    at(s).recordForce(local(s), force, x);
  }
  int substep(Real h, Real max_substep, Real share) override;

 private:
  int member(int s) const {
    int m = 0;
    while (s >= first_[m + 1]) ++m;
    return m;
  }
  ContactBodies& at(int s) const { return *members_[member(s)]; }
  int local(int s) const { return s - first_[member(s)]; }

  std::vector<ContactBodies*> members_;
  std::vector<int> first_;       ///< members' first shapes, then the total
  std::vector<int> first_body_;  ///< members' first body numbers
};

}  // namespace mpm_sdem
