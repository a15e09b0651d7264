/// \file
/// Material-body coupling: one interface, five schemes picked per scene. Every scheme works on
/// ContactBodies alone (whatever kind of solid) and gives the same outputs: forces or impulses on
/// the bodies (ContactBodies::applyForce, applyImpulse), forces or momentum on the grid, and a
/// count of active contacts. World calls the stages in this order each step:
///   [bodies.beginCoupling] -> beforeStep -> [P2G, internal force] -> addGridForces
///   -> [velocity update] -> correctGridVelocity -> [G2P] -> afterMaterialStep -> [bodies.step]
/// A scheme that subcycles its springs (subcycles()) moves the bodies itself, in substeps inside
/// correctGridVelocity, and World skips [bodies.step].
#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/coupling/contact_bodies.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/sph/sph.hpp"
#include "mpm_sdem/core/step_stages.hpp"
#include "mpm_sdem/core/types.hpp"

namespace cereal {
class BinaryOutputArchive;
class BinaryInputArchive;
}  // namespace cereal

namespace mpm_sdem {

/// How the material meets the solid bodies (scene key coupling.scheme).
enum class CouplingScheme {
  kImp,              ///< seed 000 sec. 4: DEM springs between blocks and identified material points
  kImpGrid,          ///< seed 000 sec. 5.4 "MPM-GRID": the same springs, force put on the grid
                     ///< nodes around the contact point instead of on the material point
  kMultiVelocity,    ///< seed 002 sec. 2.4: the block's own velocity field on the grid, nodal
                     ///< stick/slip contact (eq. 22-32)
  kParticleSurface,  ///< seed 002 sec. 3: particle-to-surface contact, no penalty stiffness
                     ///< (eq. 42-54 with the block's effective mass at the contact point)
  kPartitioned,      ///< seed 003 Algorithm 1: blocks meet a wall of segments through boundary
                     ///< particles; the wall forces go to the MPM side as point loads
};

/// What a scheme is: stated once per scheme (coupling.cpp) and asked by the scene parser, World,
/// the runner and the checkpoint. What it cannot meet is the exclusions' table's
/// (exclusions.hpp).
struct SchemeTraits {
  CouplingScheme scheme;  ///< the scheme this row describes
  const char* name;       ///< as a scene names it (coupling.scheme)
  /// Its contacts are springs (normal_stiffness, tangential_stiffness), which bound the step
  /// (seed 000 eq. 51, second term) unless they are subcycled.
  bool springs;
  /// A block may be added after the first step: not when its wall is built from the material's
  /// initial outline (partitioned).
  bool takes_later_blocks;
};
/// Every scheme, in the order a scene's choices list them.
const std::vector<SchemeTraits>& couplingSchemes();
/// Scheme s's row.
const SchemeTraits& schemeTraits(CouplingScheme s);
/// Scheme s's name as a scene writes it.
inline const char* couplingSchemeName(CouplingScheme s) {
  return schemeTraits(s).name;
}

/// What the IMP spring constants are given for.
enum class SpringBasis {
  kPerPoint,   ///< seed 000: one spring k per IMP (N/m per metre of thickness); a face's
               ///< stiffness grows with the number of points along it
  kPerLength,  ///< k per metre of contact length (Pa): each IMP's spring is k times its point
               ///< spacing, so a face is as stiff at every resolution
};

/// How an IMP's normal spring-dashpot acts over a step.
enum class ContactIntegration {
  kExplicit,   ///< seed 000 sec. 4.2: the force at the start of the step, held over it; the
               ///< springs bound the step (eq. 51, second term)
  kExact,      ///< the impulse of the spring-dashpot over the step in closed form for the point
               ///< and block as a free pair (clippedSpringImpulse), starting within the step if
               ///< they meet; the normal springs no longer bound the step, the tangential do
  kSubcycled,  ///< multi-rate: the material's step is set by the material alone, and the
               ///< springs and the bodies take substeps within it, each substep's forces from
               ///< the positions and velocities at its start (imp_coupling.hpp)
};

/// The material-body coupling of a scene (section `coupling`): the scheme and its settings.
struct CouplingDef {
  CouplingScheme scheme = CouplingScheme::kImp;  ///< which scheme
  /// Spring schemes (kImp, kImpGrid, kPartitioned).
  Real normal_stiffness = 1e6;      ///< k_n of one contact (N/m per metre of thickness)
  Real tangential_stiffness = 5e5;  ///< k_t (N/m per metre)
  SpringBasis stiffness_per = SpringBasis::kPerPoint;                     ///< kImp and kImpGrid
  ContactIntegration normal_integration = ContactIntegration::kExplicit;  ///< kImp and kImpGrid
  Real contact_radius = 0;   ///< r_p (m); 0: h / sqrt(points per cell), inside eq. 45
  Real verlet_distance = 0;  ///< V_d (m); 0: half a cell
  /// kMultiVelocity: the block's points per cell side (its nodal mass and normal, eq. 23).
  int block_points_per_cell = 2;
  /// kPartitioned: how far inside each body's initial outline the boundary particles start (m);
  /// 0: a third of the point spacing (seed 003, the wooden-block case).
  Real boundary_inset = 0;
};

/// What a stage may read and change.
struct CouplingStep {
  Particles& particles;   ///< the material
  Grid& grid;             ///< the background grid of the step
  const Tiles& tiles;     ///< the points binned by tiles
  ContactBodies& bodies;  ///< every solid the material meets
  KernelType kernel;      ///< the grid's shape functions
  Vec2 gravity;           ///< m/s^2
  Real dt;                ///< s, the step
  Real kick;              ///< s, the grid velocity update's span (dt, half of it on the first step)
  ///@{
  /// Subcycling schemes: the longest stable substep of the material-body springs (eq. 51,
  /// second term) and of the bodies' own contacts (ContactBodies::stableStep), s.
  Real contact_substep = std::numeric_limits<Real>::infinity();
  Real body_substep = std::numeric_limits<Real>::infinity();
  ///@}
  ///@{
  /// The SPH particles' accelerations (m/s^2, indexed by particle; seed 001), or null in a world
  /// without them. An SPH particle is moved by its own acceleration, not by the grid: a contact
  /// force on it is added here, and an impulse changes its velocity (Particles::vx, vy) at once.
  Real* sph_ax = nullptr;
  Real* sph_ay = nullptr;
  bool isSph(int p) const { return sph_ax && particles.kind[p] == kSphParticle; }
  ///@}
};

/// A material-body coupling scheme: the stages World calls in its step (see the file's comment),
/// what it gave the material, and its state for checkpoints.
class Coupling {
 public:
  virtual ~Coupling() = default;
  /// Contact forces from the state at the start of the step (spring schemes).
  virtual void beforeStep(CouplingStep&) {}
  /// Nodal forces, added to the internal forces before the velocity update.
  virtual void addGridForces(CouplingStep&) {}
  /// Momentum exchange on the updated (trial) grid velocities (penalty-free schemes).
  virtual void correctGridVelocity(CouplingStep&) {}
  /// After the points moved.
  virtual void afterMaterialStep(CouplingStep&) {}
  /// The stages it fills: World's step holds only these (step_stages.hpp).
  virtual CouplingHooks hooks() const = 0;
  /// True when contacts are springs, which bound the time step (seed 000 eq. 51, second term).
  bool hasSprings() const { return schemeTraits(def_.scheme).springs; }
  /// True when correctGridVelocity changes nodal velocities (the walls are then applied again).
  virtual bool correctsVelocities() const { return false; }
  /// True when the springs take substeps inside the material's step (they do not bound it) and
  /// the scheme steps the bodies in them.
  virtual bool subcycles() const { return false; }
  /// A body was added or removed: the shapes are numbered afresh (rebuild what is indexed by
  /// them; shape keys still name the ones that stayed).
  virtual void bodiesChanged() {}
  /// Its settings as the runner's banner states them (with the defaults resolved, units).
  virtual std::string settings() const = 0;
  ///@{
  /// The state it carries from step to step beyond the base's (scratch is rebuilt), written and
  /// read by the checkpoint in this order (src/core/state_archive.hpp); none by default.
  virtual void saveState(cereal::BinaryOutputArchive&) {}
  virtual void loadState(cereal::BinaryInputArchive&) {}
  ///@}

  /// The material's inertia over its mass (SolverDef::inertia_scale): a point's springs and
  /// dashpots move s m.
  void setInertiaScale(Real s) { inertia_scale_ = s; }
  /// Which scheme this is.
  CouplingScheme scheme() const { return def_.scheme; }
  /// Settings with defaults resolved (r_p, V_d, inset in metres).
  const CouplingDef& def() const { return def_; }
  /// Contacts that acted in the last step.
  long activeContacts() const { return active_; }
  /// Sum of what the last step gave the material (N/m): impulses are divided by dt.
  Vec2 forceOnMaterial() const { return on_material_; }

 protected:
  friend struct detail::CheckpointAccess;
  Real inertia_scale_ = 1;  ///< SolverDef::inertia_scale
  /// def with its defaults resolved.
  explicit Coupling(const CouplingDef& def) : def_(def) {}
  CouplingDef def_;         ///< the settings, defaults resolved
  long active_ = 0;         ///< contacts that acted in the last step
  Vec2 on_material_{0, 0};  ///< what the last step gave the material (N/m)
};

/// def must have its defaults resolved (World does it from the cell size and points per cell).
std::unique_ptr<Coupling> makeCoupling(const CouplingDef& def, const Vec2& domain_min,
                                       const Vec2& domain_max, Real cell_size,
                                       const std::vector<BodyDef>& bodies);

}  // namespace mpm_sdem
