/// \file
/// What a coupling scheme may ask of the solid bodies the material touches, and all it may do to
/// them. The material meets contact shapes: convex rounded outlines, each a core (a list of
/// vertices: a convex polygon, two for a capsule, one for a disk) swept by a disk of radius
/// rounding(s) (seed 000 sec. 3). A shape belongs to a body and moves with it: a spheropolygon
/// block is one shape, a cluster of discs (seed 003) one shape per disc, an FEM body (next) one
/// per boundary segment. Its motion can be read and pushed at any point. Rigid blocks implement
/// it (Blocks); a new kind of body implements it too, and every scheme works with it unchanged.
/// Everything is SI, per metre of thickness, world frame.
///
/// A step, as World drives it: beginCoupling (the material's record cleared, trial velocities
/// set), the scheme's stages (forces or impulses from the material), then step (the bodies move
/// with them). Shapes are numbered 0..shapeCount()-1, a body's shapes one after another; the
/// numbers hold between changes to the set of bodies (an add or a removal renumbers them), a
/// body key for as long as the body exists.
#pragma once

#include <cstdint>
#include <limits>
#include <vector>

#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// An axis-aligned box (m).
struct Box {
  ///@{
  /// Corners (m).
  Vec2 min{0, 0}, max{0, 0};
  ///@}
};

/// Bodies with an area of their own, sampled by points for the grid-based multi-velocity scheme
/// (seed 002 eq. 23): rigid blocks (Blocks).
class InteriorLattice {
 public:
  virtual ~InteriorLattice() = default;
  /// Points filling shape s's rounded outline on a lattice of the given spacing (m), where they
  /// are now, and the mass of each (kg/m): the body's mass shared equally by all its points,
  /// each point given to one of the body's shapes where they overlap. The lattice is laid once
  /// and moves with the body.
  virtual void interiorPoints(int s, Real spacing, std::vector<Vec2>& points, Real& mass_each) = 0;
};

/// Where a shape was, for telling how far it has moved since (the contact search's Verlet list):
/// a rigid body's centre of mass and angle, or a deformable segment's two ends.
struct BodyPose {
  Vec2 position{0, 0};  ///< centre of mass, or a segment's first end (m)
  Real angle = 0;       ///< rad
  Vec2 other{0, 0};     ///< a segment's second end (m)
  template <class Archive>
  void serialize(Archive& ar) {
    ar(position, angle, other);
  }
};

/// The mass a contact between a point of mass m and a body of mass M moves, m M / (m + M); m
/// alone against a body that does not move (M infinite). Sizes the dashpots (seed 000 eq. 42).
inline Real reducedMass(Real m, Real M) {
  return M < std::numeric_limits<Real>::infinity() ? m * M / (m + M) : m;
}

/// Every kind of solid the material meets, as the coupling schemes see it: shapes with outlines,
/// their bodies' motion and mass at a point, and the forces and impulses the material gives them.
class ContactBodies {
 public:
  virtual ~ContactBodies() = default;
  /// How many shapes there are now; shapes are numbered 0..shapeCount()-1, afresh when a body
  /// comes or goes.
  virtual int shapeCount() const = 0;
  ///@{
  /// The body shape s belongs to: its number now (bodies too are numbered afresh on a change),
  /// and a key that names it while it exists and is never that of a removed body (for carrying a
  /// contact's history across a renumbering). Where a body's shapes overlap (a cluster of discs)
  /// its outline is their union: a point meets the body at the deepest of them.
  virtual int bodyOf(int s) const = 0;
  virtual std::uint64_t bodyKey(int s) const = 0;
  ///@}

  ///@{
  /// The outline: core vertices (counter-clockwise) and the sweeping radius (m).
  virtual const Vec2* coreVertices(int s) const = 0;
  virtual int coreVertexCount(int s) const = 0;
  virtual Real rounding(int s) const = 0;
  ///@}
  /// Closest point of the core to x; the rounded surface lies rounding(s) further along normal.
  virtual CoreDistance closest(int s, const Vec2& x) const = 0;
  /// Box around the rounded outline.
  virtual Box bounds(int s) const = 0;
  ///@{
  /// Coulomb friction with the material, and the damping ratio of spring contacts (from the
  /// body's restitution, eq. 42).
  virtual Real friction(int s) const = 0;
  virtual Real dampingRatio(int s) const = 0;
  ///@}

  ///@{
  /// The motion of the shape's body at the start of the step. movable: forces change it (a
  /// dynamic block; a static or kinematic one keeps its own). mass: what a contact's dashpot acts
  /// against, infinite when not movable. inverseMass: velocity change at x per unit impulse at x
  /// (zero when not movable): 1/M + r_perp r_perp^T / I for a rigid block.
  virtual bool movable(int s) const = 0;
  virtual Real mass(int s) const = 0;
  virtual Vec2 velocityAt(int s, const Vec2& x) const = 0;
  virtual Mat2 inverseMass(int s, const Vec2& x) const = 0;
  ///@}
  ///@{
  /// The lightest movable body's mass (infinite when none) and the largest damping ratio, for
  /// the contact term of the time step (seed 000 eq. 51).
  virtual Real lightestMass() const = 0;
  virtual Real maxDampingRatio() const = 0;
  ///@}

  ///@{
  /// For a Verlet list: the pose of the shape's body now, and a bound on how far any point of the
  /// shape's rounded outline has moved since an earlier pose.
  virtual BodyPose pose(int s) const = 0;
  virtual Real movedSince(int s, const BodyPose& then) const = 0;
  ///@}
  /// The bodies' interior lattice (InteriorLattice), or null when they have none: FEM bodies'
  /// segments enclose no area of their own, and the scheme that needs it (multi_velocity)
  /// cannot meet them (couplingSchemes()).
  virtual InteriorLattice* interiorLattice() { return nullptr; }

  ///@{
  /// The exchange with the material in a step of dt. beginCoupling clears what the material did
  /// and sets each body's trial velocity: its free motion over dt (gravity), which impulses then
  /// change one by one, so that many contacts on one body share its momentum (Gauss-Seidel).
  /// Forces and impulses on a shape act on its body.
  virtual void beginCoupling(Real dt) = 0;
  virtual Vec2 trialVelocityAt(int s, const Vec2& x) const = 0;
  ///@}
  /// A force from the material (N/m) at x for the coming step.
  virtual void applyForce(int s, const Vec2& force, const Vec2& x) = 0;
  /// An impulse from the material (N s/m) at x: changes the trial velocity now and acts as the
  /// force impulse / dt over the step.
  virtual void applyImpulse(int s, const Vec2& impulse, const Vec2& x, Real dt) = 0;

  ///@{
  /// The bodies' own motion: the largest stable step of their mutual contacts (infinite when
  /// none), and a step of dt in substeps no longer than max_substep (returns their number).
  virtual Real stableStep(Real kappa2) const = 0;
  virtual int step(Real dt, Real max_substep) = 0;
  ///@}

  ///@{
  /// Multi-rate coupling (ContactIntegration::kSubcycled): the material's step is cut into
  /// substeps and the springs' forces change in each. pushForce acts on the body for the coming
  /// substep only and is not recorded; recordForce only records (the step's mean, for outputs);
  /// applyForce is both. substep advances by h like step, with the forces pushed since the last
  /// substep and the external loads given before the material's step (they act in every
  /// substep of it); share: h over the material's step, for the bodies' own records.
  virtual void pushForce(int s, const Vec2& force, const Vec2& x) = 0;
  virtual void recordForce(int s, const Vec2& force, const Vec2& x) = 0;
  virtual int substep(Real h, Real max_substep, Real share) = 0;
  ///@}
};

}  // namespace mpm_sdem
