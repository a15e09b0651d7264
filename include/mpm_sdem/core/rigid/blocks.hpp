/// \file
/// Rigid blocks: spheropolygons and clusters of discs integrated by Box2D 2.4 (kept behind this
/// interface; no Box2D type appears here). Box2D is tuned for bodies of 0.1 to 10 units in single
/// precision, so the blocks live in Box2D scaled by length_scale (Box2D units per metre), chosen
/// so that the median block is one unit across; every quantity crossing this interface is SI.
///
/// Where things are: this class holds the blocks (rigid/blocks.cpp) and answers the contact
/// schemes as ContactBodies; rigid/box2d_bodies.cpp moves them; rigid/penalty_contacts.cpp is the
/// seed's block-block springs.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/coupling/contact_bodies.hpp"
#include "mpm_sdem/core/coupling/restitution.hpp"
#include "mpm_sdem/core/rigid/disc_cluster.hpp"
#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

namespace detail {
class Box2DBodies;
class PenaltyContacts;
}  // namespace detail

/// How a block moves: not at all, at the velocity it is given, or under the forces on it.
enum class BodyType { kStatic, kKinematic, kDynamic };

/// Block-block contact: the seed's spheropolygon vertex-edge springs (eq. 38-43) with forces
/// applied through Box2D, or Box2D's own contact solver on the core polygon grown by the rounding.
enum class BlockContactModel { kPenalty, kBox2D };

/// Velocity components of a dynamic block held at set values whatever acts on it, the others
/// free: a test rig's carriage and motor (a wheel towed at vx and turned at angular_velocity,
/// free to sink). A held component ignores the forces along it and, to the contact schemes, has
/// infinite mass (inverseMass, the trial velocity); the contact forces the block feels are still
/// reported (coupling(), blockContact()), so the rig's reaction is their negative.
/// Gravity acts within a substep on a held vy (Box2D adds it), an error of g h^2 per substep.
struct BlockDrive {
  ///@{
  /// Which components are held.
  bool hold_vx = false, hold_vy = false, hold_angular = false;
  ///@}
  Vec2 velocity{0, 0};        ///< of the centre of mass (m/s), the held components
  Real angular_velocity = 0;  ///< rad/s, when held
  /// Whether any component is held.
  bool any() const { return hold_vx || hold_vy || hold_angular; }
  template <class Archive>
  void serialize(Archive& ar) {
    ar(hold_vx, hold_vy, hold_angular, velocity, angular_velocity);
  }
};

/// One rigid block (scene section `blocks`, or a spawned obstacle): its outline, type, material
/// and initial motion.
struct BlockDef {
  std::string name;  ///< unique; a ROS name (limits::nameProblem)
  ///@{
  /// The outline, one of two kinds. A spheropolygon: a convex core polygon in the block frame
  /// (m; 1 vertex: a disk, 2: a capsule) swept by a disk of radius rounding (m, > 0). A rigid
  /// cluster of discs (seed 003 sec. 2.2): discs non-empty and core empty; the outline is their
  /// union and rounding is unused.
  std::vector<Vec2> core;
  Real rounding = 0;
  std::vector<Disc> discs;
  ///@}
  Vec2 position{0, 0};                 ///< block frame origin in the world (m)
  Real angle = 0;                      ///< rad, counter-clockwise
  Vec2 velocity{0, 0};                 ///< m/s, of the centre of mass
  Real angular_velocity = 0;           ///< rad/s
  BodyType type = BodyType::kDynamic;  ///< static, kinematic or dynamic
  Real density = 1000;                 ///< kg/m^3
  Real friction = 0.5;                 ///< Coulomb coefficient with blocks, walls and material
  Real restitution = 0.5;              ///< normal, in (0, 1]; a block pair takes the smaller
  /// Adhesion between blocks (Pa: N/m per metre of contact length), penalty model only; a block
  /// pair takes the larger (seed 003's wood: 30 Pa with wood, 60 Pa with the rigid boundary).
  Real adhesion = 0;
  BlockDrive drive;  ///< dynamic blocks only; nothing held by default
  /// Every field: a checkpoint carries the blocks added while running.
  template <class Archive>
  void serialize(Archive& ar) {
    ar(name, core, rounding, discs, position, angle, velocity, angular_velocity, type, density,
       friction, restitution, adhesion, drive);
  }
};

/// How blocks meet each other (scene section `block_contact`).
struct BlockContactDef {
  BlockContactModel model = BlockContactModel::kPenalty;  ///< springs or Box2D's solver
  Real normal_stiffness = 1e7;      ///< N/m per metre of thickness, penalty model
  Real tangential_stiffness = 5e6;  ///< N/m per metre
};

/// Where a block is: centre of mass, orientation and velocities, SI.
struct BlockState {
  Vec2 position{0, 0};        ///< centre of mass (m)
  Real angle = 0;             ///< rad, counter-clockwise
  Vec2 velocity{0, 0};        ///< of the centre of mass (m/s)
  Real angular_velocity = 0;  ///< rad/s
  template <class Archive>
  void serialize(Archive& ar) {
    ar(position, angle, velocity, angular_velocity);
  }
};

/// A handle on a block that stays valid while the block exists and names nothing once it is
/// removed, even when its slot is reused (Box2D v3's b2BodyId): the slot and the generation of
/// the slot's occupant. The default is the null id.
struct BlockId {
  int slot = -1;                 ///< the storage slot; -1: the null id
  std::uint32_t generation = 0;  ///< which occupant of the slot
  /// Whether this is the null id.
  bool isNull() const { return slot < 0; }
  template <class Archive>
  void serialize(Archive& ar) {
    ar(slot, generation);
  }
  ///@{
  /// Ids are equal when they name the same block (or are both null).
  bool operator==(const BlockId& o) const { return slot == o.slot && generation == o.generation; }
  bool operator!=(const BlockId& o) const { return !(*this == o); }
  ///@}
};

/// The rigid blocks: definitions, generational ids, state, Box2D bodies, their contacts with each
/// other, and their ContactBodies answers to the coupling.
class Blocks final : public ContactBodies, public InteriorLattice {
 public:
  /// length_hint (m): the typical block size, used for Box2D's length scale when defs is empty.
  /// Throws std::invalid_argument on a block whose outline or values are unacceptable.
  Blocks(const std::vector<BlockDef>& defs, const BlockContactDef& contact, const Vec2& gravity,
         Real length_hint = 0);
  ~Blocks() override;
  Blocks(const Blocks&) = delete;
  Blocks& operator=(const Blocks&) = delete;

  /// The blocks are listed 0..count()-1 in the order they were added (outputs list them so); a
  /// removal closes the gap. Hold an id, not a place in the list.
  int count() const { return static_cast<int>(defs_.size()); }
  /// The id of the block at place i.
  BlockId id(int i) const { return ids_[i]; }
  /// The block's place in the list now, or -1 when the id names no block.
  int indexOf(BlockId id) const;
  /// Throws like the constructor.
  BlockId add(const BlockDef& def);
  /// Throws std::invalid_argument when the id names no block.
  void remove(BlockId id);
  /// The block with this name, or the null id.
  BlockId find(const std::string& name) const;

  /// Block i's definition as added (its pose and velocity those it started with).
  const BlockDef& def(int i) const { return defs_[i]; }
  /// Block i's mass, centroid (own frame) and inertia.
  const MassProperties& massProperties(int i) const { return bodies_[i].mass; }
  /// Where block i is now and how it moves.
  const BlockState& state(int i) const { return bodies_[i].state; }
  /// Origin of block i's own frame (the frame its outline is given in), world frame (m).
  Vec2 origin(int i) const;
  /// Velocity of block i's frame origin (m/s): what setVelocity sets.
  Vec2 originVelocity(int i) const;
  /// Moves the block's frame to origin and angle (a teleport: no force, velocities kept).
  void setPose(BlockId id, const Vec2& origin, Real angle);
  /// Sets the velocity of the block frame's origin (m/s) and its angular velocity (rad/s). A
  /// kinematic block keeps them until told otherwise; a dynamic one starts from them.
  void setVelocity(BlockId id, const Vec2& origin_velocity, Real angular_velocity);
  /// Box2D's length unit in metres (its solver is tuned for bodies of about one unit).
  Real lengthScale() const { return scale_; }
  ///@{
  /// Forces for the next step, world frame (N/m), applied at a point (m), and torques (N m/m);
  /// cleared by step(). A dynamic block's trial velocity (beginCoupling) includes what was
  /// added before the exchange with the material: an external load acts on it too.
  void addForce(int i, const Vec2& force, const Vec2& point);
  void addTorque(int i, Real torque);
  ///@}
  /// Both for the next step on the block of that id; throws like remove().
  void addLoad(BlockId id, const Vec2& force, const Vec2& point, Real torque);
  /// The acceleration of gravity (m/s^2) on every block from the next step on.
  void setGravity(const Vec2& gravity);
  ///@{
  /// The block that contact shape s belongs to (a spheropolygon is one shape; a cluster one per
  /// disc), and block i's shapes: firstShape(i) .. firstShape(i) + shapesOf(i) - 1.
  int owner(int s) const { return shapes_[s].block; }
  int firstShape(int i) const { return bodies_[i].first_shape; }
  int shapesOf(int i) const { return bodies_[i].shape_count; }
  ///@}
  /// Block i's convex parts in its own frame (counter-clockwise cores).
  const std::vector<Spheropolygon>& parts(int i) const { return parts_[i]; }
  /// Block i's parts where they are now (world frame).
  std::vector<Spheropolygon> currentParts(int i) const;
  /// Box around block i's outline (m).
  Box blockBounds(int i) const;
  /// The blocks that are not static, in list order (places, valid until blocks change).
  const std::vector<int>& movingBlocks() const { return moving_; }
  /// Changes whenever blocks are added or removed or one is moved by setPose: what was derived
  /// from where the blocks are (the block springs' broad phase) is stale.
  std::uint64_t layoutVersion() const { return layout_version_; }

  /// ContactBodies: core vertices in the world frame, refreshed after every step.
  int shapeCount() const override { return static_cast<int>(shapes_.size()); }
  int bodyOf(int s) const override { return owner(s); }
  std::uint64_t bodyKey(int s) const override;
  /// Names shape s while it exists (a part of a block): for the block-block springs' history.
  std::uint64_t shapeKey(int s) const;
  const Vec2* coreVertices(int s) const override {
    return world_vertices_.data() + shapes_[s].first_vertex;
  }
  int coreVertexCount(int s) const override { return shapes_[s].vertex_count; }
  Real rounding(int s) const override { return shapes_[s].rounding; }
  CoreDistance closest(int s, const Vec2& x) const override {
    return closestOnCore(coreVertices(s), coreVertexCount(s), x);
  }
  Box bounds(int s) const override;
  Real friction(int s) const override { return defs_[owner(s)].friction; }
  /// From the block's restitution (fixed at construction).
  Real dampingRatio(int s) const override { return bodies_[owner(s)].zeta; }
  bool movable(int s) const override { return bodies_[owner(s)].type == BodyType::kDynamic; }
  Real mass(int s) const override;
  Vec2 velocityAt(int s, const Vec2& x) const override;
  Mat2 inverseMass(int s, const Vec2& x) const override;
  /// Shape s's block's inverse mass along x and y and inverse inertia (1/kg, 1/kg, 1/(kg m^2)),
  /// zero along what does not yield (a static or kinematic block, a held drive component).
  Eigen::Matrix<Real, 3, 1> inverseMasses(int s) const;
  /// Lightest dynamic block (kg/m), infinite when there is none.
  Real lightestMass() const override;
  Real maxDampingRatio() const override { return max_zeta_; }
  BodyPose pose(int s) const override;
  Real movedSince(int s, const BodyPose& then) const override;
  InteriorLattice* interiorLattice() override { return this; }
  void interiorPoints(int s, Real spacing, std::vector<Vec2>& points, Real& mass_each) override;
  /// Clears coupling() and sets the trial velocities (a dynamic block falls for dt).
  void beginCoupling(Real dt) override;
  Vec2 trialVelocityAt(int s, const Vec2& x) const override;
  /// A force from the material: added for the next step and to coupling() (one contact).
  void applyForce(int s, const Vec2& force, const Vec2& x) override;
  void applyImpulse(int s, const Vec2& impulse, const Vec2& x, Real dt) override;
  /// Stable step of the block-block penalty springs (penalty_contacts.cpp); infinite when no
  /// spring can form.
  Real stableStep(Real kappa2) const override;
  /// Advance by dt in substeps no longer than max_substep: in each, block-block contact forces
  /// (penalty model) and one Box2D step. The forces added before the call (the material's) act
  /// unchanged through all substeps. Returns the number of substeps.
  int step(Real dt, Real max_substep = std::numeric_limits<Real>::infinity()) override;
  void pushForce(int s, const Vec2& force, const Vec2& x) override;
  void recordForce(int s, const Vec2& force, const Vec2& x) override;
  int substep(Real h, Real max_substep, Real share) override;

  /// A load on one block in the last step (for outputs): what the material did to it
  /// (coupling), or what the other blocks did (blockContact).
  struct Load {
    Vec2 force{0, 0};  ///< N/m
    Real torque = 0;   ///< N m/m about the centre of mass
    int contacts = 0;  ///< contacts that carried it in the last step (substep)
    template <class Archive>
    void serialize(Archive& ar) {
      ar(force, torque, contacts);
    }
  };
  /// What the material did to each block in the last step (the step's mean force).
  const std::vector<Load>& coupling() const { return coupling_; }
  /// The contact forces of the other blocks on block i, averaged over the last step's substeps,
  /// with either contact model (the penalty springs, or Box2D's contact impulses over each
  /// substep); contacts: the springs or Box2D manifold points of the last substep. With
  /// coupling()[i], the load a kinematic block such as a loading plate or a blade carries.
  const Load& blockContact(int i) const { return block_contact_[i]; }
  ///@{
  /// For the block-block contact models, during step(): a contact force between blocks a and b
  /// (force on a, -force on b) at a point (m). addContactForce applies it for the substep
  /// (penalty springs); recordContactForce only notes what Box2D's solver applied.
  void addContactForce(int a, int b, const Vec2& force_on_a, const Vec2& point);
  void recordContactForce(int a, int b, const Vec2& force_on_a, const Vec2& point);
  ///@}

 private:
  friend struct detail::CheckpointAccess;
  void checkDef(const BlockDef& def) const;  ///< throws std::invalid_argument
  int checkedIndex(BlockId id) const;        ///< throws std::invalid_argument
  void layoutShapes();
  void refresh();       ///< state and world vertices from Box2D (box2d_bodies.cpp)
  void refresh(int i);  ///< block i's alone
  void holdDrives();    ///< sets the held velocity components of driven blocks in Box2D
  /// step() and substep(): dt in substeps with the forces given so far; the loads of the step
  /// are cleared when it ends. share: dt over the whole step (1 for step()), for the records.
  int advance(Real dt, Real max_substep, bool ends_step, Real share);

  /// What every step reads and writes, one entry per block (hot); the definitions, names
  /// included, stay in defs_ (cold).
  struct Body {
    BlockState state;
    MassProperties mass;
    BodyType type = BodyType::kDynamic;
    BlockDrive drive;
    Real zeta = 0;  ///< damping ratio of its spring contacts
    /// Pose and twist of a kinematic block in double precision (centre of mass, world frame).
    Vec2 kinematic_centre{0, 0};
    Real kinematic_angle = 0;
    Vec2 kinematic_velocity{0, 0};
    Real kinematic_angular_velocity = 0;
    Vec2 force{0, 0};  ///< for the next (sub)step
    Real torque = 0;
    Vec2 held_force{0, 0};  ///< the material's, held through the substeps
    Real held_torque = 0;
    /// The external loads of the step under way (beginCoupling moves them here from force), for
    /// every substep of a multi-rate step; each step sets them afresh, so they are not in a
    /// checkpoint.
    Vec2 load_force{0, 0};
    Real load_torque = 0;
    Vec2 trial_v{0, 0};  ///< during the exchange with the material (beginCoupling)
    Real trial_w = 0;
    int first_shape = 0, shape_count = 0;
    /// What changes while running (the rest follows from the block's definition).
    template <class Archive>
    void serialize(Archive& ar) {
      ar(state, drive, kinematic_centre, kinematic_angle, kinematic_velocity,
         kinematic_angular_velocity, force, torque, held_force, held_torque, trial_v, trial_w);
    }
  };
  /// A driven block's trial velocity keeps its held components (beginCoupling, applyImpulse).
  static void holdTrial(Body& b);
  /// A contact shape: a convex rounded part of one block.
  struct Shape {
    int block = 0;  ///< place in the list
    int part = 0;   ///< which part of its block
    int first_vertex = 0, vertex_count = 0;
    Real rounding = 0;
  };
  /// A block's interior lattice (interiorPoints): offsets from the centre of mass at angle0,
  /// world axes, grouped by the part they fall in first (part k's from begin[k] to begin[k+1]),
  /// laid on first use.
  struct Lattice {
    std::vector<Vec2> offset;
    std::vector<int> begin;
    Real angle0 = 0, spacing = 0, mass = 0;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(offset, begin, angle0, spacing, mass);
    }
  };

  std::unique_ptr<detail::Box2DBodies> b2_;
  std::unique_ptr<detail::PenaltyContacts> penalty_;
  std::vector<BlockDef> defs_;                     ///< cold
  std::vector<BlockId> ids_;                       ///< the id of each listed block
  std::vector<std::vector<Spheropolygon>> parts_;  ///< each block's parts, block frame
  std::vector<Lattice> lattices_;
  std::vector<Body> bodies_;  ///< hot
  std::vector<Shape> shapes_;
  std::vector<Vec2> world_vertices_;  ///< the shapes' core vertices, world frame
  std::vector<Load> coupling_;        ///< records for outputs
  std::vector<Load> block_contact_;   ///< from the other blocks, last step
  /// The blocks that move (not static), in list order: a substep touches only these, so that a
  /// thousand static obstacles cost nothing per step (layoutShapes keeps it).
  std::vector<int> moving_;
  /// Slot table: the place of the block in each slot (-1 free), its generation, free slots.
  std::vector<int> slot_place_;
  std::vector<std::uint32_t> slot_generation_;
  std::vector<int> free_slots_;
  Real max_zeta_ = 0;
  std::uint64_t layout_version_ = 0;
  Real substep_share_ = 1;  ///< one substep's share of the (material) step under way
  Vec2 gravity_{0, 0};
  BlockContactDef contact_;
  Real scale_ = 1;
};

///@{
/// A block's convex parts in its own frame (one for a spheropolygon, one per disc of a cluster,
/// counter-clockwise), and placed at its pose (m, world frame).
std::vector<Spheropolygon> blockParts(const BlockDef& def);
std::vector<Spheropolygon> placedParts(const BlockDef& def);
///@}
/// Mass, centroid (block frame) and inertia of the block's outline at its density: the
/// spheropolygon's, or the union of its discs.
MassProperties blockMass(const BlockDef& def);

/// Smallest gap between two rounded outlines given by their world-frame cores and roundings
/// (negative: they overlap), from the vertex-edge distances both ways.
Real roundedGap(const Vec2* a, int na, Real rounding_a, const Vec2* b, int nb, Real rounding_b);

}  // namespace mpm_sdem
