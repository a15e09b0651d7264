// Rigid blocks: spheropolygons integrated by Box2D 2.4 (kept behind this interface; no Box2D type
// appears here). Box2D is tuned for bodies of 0.1 to 10 units in single precision, so the blocks
// live in Box2D scaled by length_scale (Box2D units per metre), chosen so that the median block is
// one unit across; every quantity crossing this interface is SI.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/restitution.hpp"
#include "mpm_sdem/core/spheropolygon.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

enum class BodyType { kStatic, kKinematic, kDynamic };

// Block-block contact: the seed's spheropolygon vertex-edge springs (eq. 38-43) with forces
// applied through Box2D, or Box2D's own contact solver on the core polygon grown by the rounding.
enum class BlockContactModel { kPenalty, kBox2D };

struct BlockDef {
  std::string name;
  std::vector<Vec2> core;     // convex core polygon in the block frame (m); 1 vertex: disk
  Real rounding = 0;          // sweeping disk radius a (m), > 0
  Vec2 position{0, 0};        // block frame origin in the world (m)
  Real angle = 0;             // rad, counter-clockwise
  Vec2 velocity{0, 0};        // m/s, of the centre of mass
  Real angular_velocity = 0;  // rad/s
  BodyType type = BodyType::kDynamic;
  Real density = 1000;     // kg/m^3
  Real friction = 0.5;     // Coulomb coefficient with blocks, walls and material
  Real restitution = 0.5;  // normal, in (0, 1]; a block pair takes the smaller
  // Adhesion between blocks (Pa: N/m per metre of contact length), penalty model only; a block
  // pair takes the larger (seed 003's wood: 30 Pa with wood, 60 Pa with the rigid boundary).
  Real adhesion = 0;
};

struct BlockContactDef {
  BlockContactModel model = BlockContactModel::kPenalty;
  Real normal_stiffness = 1e7;      // N/m per metre of thickness, penalty model
  Real tangential_stiffness = 5e6;  // N/m per metre
};

// Where a block is: centre of mass, orientation and velocities, SI.
struct BlockState {
  Vec2 position{0, 0};
  Real angle = 0;
  Vec2 velocity{0, 0};
  Real angular_velocity = 0;
};

class Blocks {
 public:
  // length_hint (m): the typical block size, used for Box2D's length scale when defs is empty.
  // Throws std::invalid_argument on a block whose core or rounding is unacceptable.
  Blocks(const std::vector<BlockDef>& defs, const BlockContactDef& contact, const Vec2& gravity,
         Real length_hint = 0);
  ~Blocks();
  Blocks(const Blocks&) = delete;
  Blocks& operator=(const Blocks&) = delete;

  int count() const { return static_cast<int>(defs_.size()); }
  // Adds a block at the end (its index is the returned count - 1). Throws like the constructor.
  int add(const BlockDef& def);
  // Removes block i; the blocks after it move down one index.
  void remove(int i);
  // Index of the block with this name, or -1.
  int find(const std::string& name) const;
  const BlockDef& def(int i) const { return defs_[i]; }
  const MassProperties& massProperties(int i) const { return mass_[i]; }
  const BlockState& state(int i) const { return state_[i]; }
  // Core vertices in the world frame, refreshed after every step.
  const Vec2* vertices(int i) const { return &world_vertices_[i * kMaxBlockVertices]; }
  int vertexCount(int i) const { return static_cast<int>(defs_[i].core.size()); }
  Vec2 velocityAt(int i, const Vec2& point) const;
  // Origin of block i's own frame (the frame its core is given in), world frame (m).
  Vec2 origin(int i) const;
  // Moves block i's frame to origin and angle (a teleport: no force, velocities kept).
  void setPose(int i, const Vec2& origin, Real angle);
  // Sets the velocity of block i's frame origin (m/s) and its angular velocity (rad/s). A
  // kinematic block keeps them until told otherwise; a dynamic one starts from them.
  void setVelocity(int i, const Vec2& origin_velocity, Real angular_velocity);
  Real lengthScale() const { return scale_; }
  // Lightest dynamic block (kg/m), infinite when there is none.
  Real lightestDynamicMass() const;
  // Damping ratio of block i's spring contacts, from its restitution (fixed at construction).
  Real dampingRatio(int i) const { return zeta_[i]; }
  Real maxDampingRatio() const { return max_zeta_; }

  // Forces for the next step, world frame (N/m), applied at a point (m); cleared by step().
  void addForce(int i, const Vec2& force, const Vec2& point);
  // A force from the material: added for the next step and to coupling()[i] (one contact).
  void addMaterialForce(int i, const Vec2& force, const Vec2& point);
  void clearCoupling();
  // Stable step of the block-block penalty springs (contactTimeStep for four springs, eq. 39,
  // between two of the blocks with the smallest effective mass at a contact point, rotation
  // included); infinite when no spring can form.
  Real stableStep(Real kappa2) const;
  // Advance by dt in substeps no longer than max_substep: in each, block-block contact forces
  // (penalty model) and one Box2D step. The forces added before the call (the material's) act
  // unchanged through all substeps. Returns the number of substeps.
  int step(Real dt, Real max_substep = std::numeric_limits<Real>::infinity());

  // What the material did to each block in the last step (for outputs).
  struct Coupling {
    Vec2 force{0, 0};  // N/m
    Real torque = 0;   // N m/m about the centre of mass
    int contacts = 0;
  };
  std::vector<Coupling>& coupling() { return coupling_; }
  const std::vector<Coupling>& coupling() const { return coupling_; }
  // The force of the other blocks' springs on block i, averaged over the last step's substeps
  // (N/m; penalty model only, zero with Box2D's contacts). With coupling()[i].force, the load a
  // kinematic block such as a loading plate carries.
  const Vec2& blockContactForce(int i) const { return block_force_[i]; }

 private:
  void checkDef(const BlockDef& def) const;  // throws std::invalid_argument
  void penaltyContacts(Real dt);
  void refresh();

  // An overlapping vertex-edge pair of the penalty model (seed 000 eq. 38-41).
  struct Spring {
    Vec2 point;   // contact point, eq. 41 (m)
    Vec2 normal;  // from the edge's block towards the vertex's
    Real xi;      // overlap (m)
    int vertex;   // index of the vertex in its block
    int side;     // 0: a vertex of the lower-index block
  };

  struct Box2D;
  std::unique_ptr<Box2D> b2_;
  std::vector<BlockDef> defs_;
  std::vector<MassProperties> mass_;
  std::vector<Real> zeta_;
  Real max_zeta_ = 0;
  std::vector<BlockState> state_;
  // The pose and twist of kinematic blocks in double precision (centre of mass, world frame).
  struct Kinematic {
    Vec2 centre;
    Real angle;
    Vec2 velocity;
    Real angular_velocity;
  };
  std::vector<Kinematic> kinematic_;
  std::vector<Vec2> world_vertices_;
  std::vector<Vec2> force_;
  std::vector<Vec2> block_force_;  // mean penalty force from the other blocks, last step
  std::vector<Real> torque_;
  std::vector<Vec2> held_force_;  // the material's forces, held through the substeps
  std::vector<Real> held_torque_;
  std::vector<Coupling> coupling_;
  BlockContactDef contact_;
  Real scale_ = 1;
  // Tangential spring history of the penalty contacts, by (block i, block j, vertex, side).
  std::vector<std::pair<unsigned long long, Vec2>> history_, next_history_;
  std::vector<Spring> springs_;  // one block pair's, reused
};

// The core vertices of a block definition at its pose (m, world frame).
std::vector<Vec2> placedCore(const BlockDef& def);
// Smallest gap between two rounded outlines given by their world-frame cores and roundings
// (negative: they overlap), from the vertex-edge distances both ways.
Real roundedGap(const Vec2* a, int na, Real rounding_a, const Vec2* b, int nb, Real rounding_b);

}  // namespace mpm_sdem
