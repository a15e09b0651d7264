/// \file
/// The MPM world: definitions in, a step pipeline, state out. No ROS, YAML or OpenCV here.
#pragma once

#include <initializer_list>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/coupling/contact_set.hpp"
#include "mpm_sdem/core/coupling/coupling.hpp"
#include "mpm_sdem/core/fem/fem_bodies.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/boundary.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/profile.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/sph/sph.hpp"
#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world_command.hpp"

namespace mpm_sdem {

namespace detail {
struct SphState;
struct SphWorld;
}  // namespace detail

/// How the step is chosen (scene section `time`).
struct TimeStepDef {
  bool automatic = true;  ///< CFL bound, re-evaluated every step
  Real fixed = 0;         ///< s, when !automatic
  Real cfl = 0.3;         ///< kappa_1 of seed 000 eq. 51: dt = cfl * h / max(c_p + |v_p|)
  Real max = std::numeric_limits<Real>::infinity();  ///< s, upper bound on the automatic step
  /// kappa_2 of seed 000 eq. 51: dt <= 2 pi kappa_2 sqrt(m_min / k_n) for every spring contact,
  /// m_min the lightest mass on either side (an IMP spring acts on one light material point).
  Real contact_factor = 0.1;
};

/// The flume's side walls, parallel to the simulation plane, of a quasi-2D flow (Jop,
/// Forterre & Pouliquen 2005): a body force of 2 mu_w p / W per unit volume against the material's
/// velocity, p the points' pressure (none in tension). width 0: none (a plane-strain slice).
struct SidewallsDef {
  Real width = 0;     ///< W, the channel's width between the walls (m)
  Real friction = 0;  ///< mu_w, Coulomb coefficient of the material on the walls
};

/// The simulated box and what bounds it (scene section `domain`).
struct DomainDef {
  ///@{
  /// Corners (m); each extent an integer number of cells.
  Vec2 min{0, 0}, max{1, 1};
  ///@}
  ///@{
  /// The four sides' walls.
  WallDef left, right, bottom, top;
  ///@}
  SidewallsDef sidewalls;  ///< the flume's walls parallel to the plane; none by default
};

/// Everything a World is made from: what a scene file describes, in SI units.
struct WorldDef {
  DomainDef domain;                    ///< the box and its walls
  Real cell_size = 0.01;               ///< m
  SolverDef solver;                    ///< kernel, transfer, stress update, gravity, damping
  TimeStepDef time_step;               ///< how the step is chosen
  std::vector<MaterialDef> materials;  ///< named by the bodies
  std::vector<BodyDef> bodies;         ///< bodies of material points
  std::vector<BlockDef> blocks;        ///< rigid blocks at the start
  BlockContactDef block_contact;       ///< how blocks meet each other
  std::vector<FemBodyDef> fem_bodies;  ///< deformable bodies (seed 002), fixed for the world's life
  CouplingDef coupling;  ///< contact between material and blocks (scheme and its settings)
  SphDef sph;            ///< the SPH region or bodies (seed 001); none by default
};

/// Whether the domain's periodic sides are well posed (left and right together, at least five
/// cells across, material alone): "" or why not. Checked by the scene parser and by World.
Problem periodicProblem(const WorldDef& def);

/// Whether a world of this domain, cell and bodies fits in memory (limits::memoryProblem, with
/// the bodies' points counted on their bounding boxes): "" or why not. Checked before anything
/// is allocated, by the scene parser and by World.
Problem sizeProblem(const DomainDef& domain, Real cell_size, const std::vector<BodyDef>& bodies);

/// Which term set the time step.
/// kElement: the FEM bodies' elements (FemBodies::elementStep times kappa_1).
/// kViscous: a fluid's viscous diffusion (h^2 / (2 nu) times kappa_1).
/// kSph: the SPH particles' signal speed over the smoothing length (detail::sphSignalSpeed).
enum class StepLimit { kFixed, kCfl, kContact, kElement, kViscous, kSph, kMax };
/// The term's name as outputs print it ("cfl", "contact", ...).
const char* stepLimitName(StepLimit limit);

/// A stable step and the term that set it.
struct TimeStepChoice {
  Real dt = 0;                          ///< s
  StepLimit limit = StepLimit::kFixed;  ///< the term that set it
};

/// What a step did.
struct StepInfo {
  Real dt = 0;         ///< s, the step taken
  bool finite = true;  ///< false: a point's position or a block's state became NaN or infinite
  long clamped = 0;    ///< particles put back inside the domain this step
  /// The first moving block whose state is not finite (finite is then false) or whose centre of
  /// mass has left the domain, and how, naming it; empty when every block is sound and inside.
  std::string block_problem;
};

/// The simulation: material points on a background grid (MPM), with rigid blocks, FEM bodies and
/// SPH particles as a scene asks, advanced one step at a time through a pipeline of named, timed
/// stages (docs/architecture.md). Built from a WorldDef; changed between steps
/// only through its own calls, so that the coupling stays in step and every change is logged.
class World {
 public:
  /// Throws std::invalid_argument on a definition the scene layer should have refused.
  explicit World(const WorldDef& def);
  ~World();
  ///@{
  /// Movable, not copyable.
  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ///@}

  /// The stable time step for the current state (CFL term of seed 000 eq. 51), or the fixed one.
  TimeStepChoice chooseTimeStep();
  /// Advance by dt through the stage pipeline; returns what happened.
  StepInfo step(Real dt);
  /// Mirror the trajectory in time: negate velocities and affine matrices and the leapfrog
  /// staggering, so that stepping again retraces the motion (seed 001 sec. 5.1 test).
  void reverseVelocities();
  /// An external force carried by one material point (N per metre of thickness), acting at the
  /// point's position plus offset (m); held until set again, zero removes it. A traction on a
  /// surface (seed 001 sec. 5.2, a stress boundary condition) enters as each surface point's
  /// share, offset half a point spacing outwards so that it acts on the surface itself (the
  /// f^ext term of seed 000 eq. 13 as a boundary integral). Spread onto the grid with the
  /// internal force; scenes without loads do no work for them.
  void setPointLoad(int particle, const Vec2& force, const Vec2& offset = Vec2::Zero());

  /// Blocks added and removed while running (obstacles commanded from outside), named by their
  /// ids (Blocks::find gives a name's). placementProblem says why a block cannot be added where
  /// it is (empty when it can): its own values (blockProblem), its name taken, outside the domain
  /// (domainProblem), overlapping a block or, unless allow_overlap, the material. moving: the
  /// block being moved to def's pose (not compared with itself), or the null id. removeBlock,
  /// setBlockPose and setBlockVelocity throw std::invalid_argument on an id that names no block.
  Problem placementProblem(const BlockDef& def, bool allow_overlap, BlockId moving = {}) const;
  /// Adds a block (check it with placementProblem first); its id.
  BlockId addBlock(const BlockDef& def);
  /// Removes the block; the id names no block afterwards.
  void removeBlock(BlockId id);
  /// Moves the block's frame to origin and angle, and sets its frame's velocity and angular
  /// velocity (Blocks::setPose, setVelocity).
  void setBlockPose(BlockId id, const Vec2& origin, Real angle);
  /// Sets the block frame's velocity (m/s) and angular velocity (rad/s).
  void setBlockVelocity(BlockId id, const Vec2& origin_velocity, Real angular_velocity);
  /// An external load on a block for the next step only: a force (N/m, world frame) at a point
  /// (m, world frame) and a torque (N m/m). Moves dynamic blocks only; a caller that holds a
  /// load adds it before every step it acts in (the node's ~apply_obstacle_wrench).
  void addBlockLoad(BlockId id, const Vec2& force, const Vec2& point, Real torque);
  /// The acceleration of gravity (m/s^2) on the material, the blocks, the FEM bodies and the SPH
  /// region from the next step on (a bed tilted or spun while running). Throws
  /// std::invalid_argument past limits::kGravity (gravityProblem).
  void setGravity(const Vec2& gravity);
  /// Why setGravity would refuse gravity (empty when it would not).
  static Problem gravityProblem(const Vec2& gravity);
  /// Every change made by the six calls above (addBlock to setGravity) goes to log once it is
  /// made, numbered in order (world_command.hpp): what a run is re-simulated under. An empty log
  /// records nothing.
  void setCommandLog(CommandLog log) { command_log_ = std::move(log); }

  /// The definition the world was made from.
  const WorldDef& def() const { return def_; }
  /// Each material's parameters as the constitutive updates use them, in WorldDef::materials'
  /// order.
  const std::vector<MaterialParams>& materialParams() const { return params_; }
  /// The rigid blocks, or nullptr in a scene without any (no block or coupling work is done).
  /// Changed only through World (addBlock, removeBlock, setBlockPose, setBlockVelocity), which
  /// keeps the coupling in step.
  const Blocks* blocks() const { return blocks_.get(); }
  /// The deformable bodies, or nullptr in a scene without any.
  const FemBodies* femBodies() const { return fem_.get(); }
  /// The material-body coupling, or nullptr while there are no contact bodies.
  const Coupling* coupling() const { return coupling_.get(); }
  /// The coupling settings with their defaults resolved (r_p, V_d in metres).
  CouplingDef resolvedCoupling() const;
  ///@{
  /// The material points (structure of arrays); changing them between steps is allowed (tests,
  /// set-up), their number is not.
  const Particles& particles() const { return particles_; }
  Particles& particles() { return particles_; }
  ///@}
  /// The background grid of the last step.
  const Grid& grid() const { return grid_; }
  /// Memory held, in bytes: the particle columns with their tile bins, and the grid arrays.
  /// Nodes the last step cleared and updated (the tiles within reach of a particle).
  struct Memory {
    std::size_t particle_bytes = 0;  ///< the particle columns and their tile bins
    std::size_t grid_bytes = 0;      ///< the grid arrays
    std::size_t grid_nodes = 0;      ///< nodes of the whole domain
    std::size_t active_nodes = 0;    ///< nodes the last step cleared and updated
  };
  /// What the world holds now.
  Memory memory() const;
  /// Simulated time (s).
  Time time() const { return time_; }
  /// The time the material points' velocities are at: the leapfrog keeps them half a step
  /// behind the positions (seed 000 eq. 17).
  Time velocityTime() const { return time_ - velocity_lag_; }
  /// Steps taken since the start (a resumed run continues the count).
  long stepCount() const { return steps_; }
  /// Wall time per stage since the start or the last resetProfile().
  const Profile& profile() const { return profile_; }
  /// Starts the stages' timing afresh.
  void resetProfile() { profile_ = Profile(); }
  /// Whether the step shares its work among the OpenMP threads: SPH worlds, and worlds of at
  /// least SolverDef::parallel_min_points points; the others step on the calling thread alone.
  bool sharesWork() const;

 private:
  friend struct detail::CheckpointAccess;
  /// The automatic step (seed 000 eq. 51) with factors kappa_1 = cfl and kappa_2.
  TimeStepChoice stepBound(Real cfl, Real kappa2) const;
  /// The coupling springs' stable step (seed 000 eq. 51, second term): the step's bound, or the
  /// substep of subcycled springs.
  Real springStep(Real kappa2) const;
  void binParticles();
  /// f(first, end) for each run of consecutive nodes of the tiles (Tiles::nodeRuns), in parallel.
  template <class F>
  void forActiveNodes(const std::vector<int>& tiles, F&& f);
  void clearGrid();
  void particleToGrid(bool momentum, bool force);
  /// damp: local damping on the nodal force (internal, gravity and the coupling's forces).
  void gridVelocity(Real kick, bool after_force, bool damp = true);
  /// Local damping on the whole of a step's velocity change, for a coupling that changes the
  /// velocities after the update (its impulses are part of the force the damping must see).
  void dampVelocityChange(Real kick);
  /// USF: with side walls, the new pressure's wall load too (one pass over the points).
  void stressAndInternalForce(Real dt);
  /// The side walls' friction (SidewallsDef): what the points' pressure lets the walls resist on
  /// each node (after the stress; sidewallLoad for USL, stressAndInternalForce for USF), then
  /// that resistance on the nodes' velocities after the kick.
  void sidewallLoad();
  void sidewallFriction(Real kick);
  /// The wall load's nodes zeroed where points are (nullptr: no side walls), and 2 mu_w / W (1/m).
  Real* clearedSidewallLoad();
  Real sidewallCoefficient() const;
  /// Periodic in x: nodes i and i + cells_x are one node, so each gets the sum of both.
  void foldPeriodic(std::initializer_list<std::vector<Real>*> fields);
  bool periodicX() const { return def_.domain.left.type == WallType::kPeriodic; }
  void gridToParticle(Real dt, StepInfo& info);
  void constitutiveUpdate(Real dt);
  void applyWalls(std::vector<Real>& vx, std::vector<Real>& vy) const;
  void couplingStage(Real dt, Real kick, void (Coupling::*stage)(CouplingStep&));
  void stepBodies(Real dt);
  /// StepInfo::block_problem and, for a block's state, finite.
  void checkBlocks(StepInfo& info) const;
  void initCoupling();
  /// Whenever the blocks come or go: the set of every kind of contact body, and what the FEM
  /// bodies meet.
  void linkContactBodies();
  void spreadPointLoads();
  /// Seed 001's SPH particles: their checks and state; the parts of the world their stages
  /// (sph/sph_stages.hpp) read and change.
  void initSph();
  detail::SphWorld sphWorld();
  /// Everything solid the material meets: the rigid blocks, the FEM bodies, both (the set), or
  /// nullptr.
  ContactBodies* contactBodies() const {
    if (set_) return set_.get();
    if (blocks_) return blocks_.get();
    return fem_.get();
  }
  bool hasContactBodies() const { return contactBodies() && contactBodies()->shapeCount() > 0; }

  WorldDef def_;
  std::vector<MaterialParams> params_;
  Particles particles_;
  Grid grid_;
  Tiles tiles_;
  std::vector<Tiles::NodeRun> node_runs_;  ///< scratch of forActiveNodes
  /// Per node: the side walls' largest friction force (N/m), when the domain has side walls.
  std::vector<Real> sidewall_load_;
  Profile profile_;
  std::unique_ptr<Blocks> blocks_;
  std::unique_ptr<FemBodies> fem_;
  std::unique_ptr<ContactSet> set_;  ///< when there are blocks and FEM bodies
  std::unique_ptr<Coupling> coupling_;
  std::unique_ptr<detail::SphState> sph_;  ///< sph_step.hpp's; null without SPH
  /// For the contact term of the time step: the smallest mass per spring scale of a point
  /// (kg/m; impSpringScale) and the largest scale.
  Real lightest_point_ = 0;
  Real largest_spring_scale_ = 1;
  /// h^2 / (2 nu) of the most viscous fluid (s); infinite without one.
  Real viscous_dt_ = std::numeric_limits<Real>::infinity();
  struct PointLoad {
    int particle;
    Vec2 force;   ///< N/m
    Vec2 offset;  ///< m, from the point
    template <class Archive>
    void serialize(Archive& ar) {
      ar(particle, force, offset);
    }
  };
  std::vector<PointLoad> point_loads_;  ///< few and rarely used: a list, not a column
  /// setGravity without the log (a checkpoint's gravity).
  void applyGravity(const Vec2& gravity);
  Time time_ = 0;
  long steps_ = 0;
  CommandLog command_log_;
  long commands_ = 0;  ///< applied through the mutators: the next command's sequence number
  WorldCommand command(WorldCommand::Kind kind, BlockId id);
  /// Leapfrog bookkeeping (seed 000 eq. 17): positions live at time_, velocities at
  /// time_ - velocity_lag_, stresses at time_ - stress_lag_. Both start at 0, so the first kick
  /// is half a step and the first USF stress update is empty.
  Real velocity_lag_ = 0;
  Real stress_lag_ = 0;
};

}  // namespace mpm_sdem
