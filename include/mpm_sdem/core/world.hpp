/// \file
/// The world: the MPM solver, the contact bodies (blocks, FEM bodies), their coupling and the
/// SPH region composed; definitions in, the step as the seed's sequence of stages, state out.
/// No ROS, YAML or OpenCV here.
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
#include "mpm_sdem/core/mpm/mpm_solver.hpp"
#include "mpm_sdem/core/mpm/point_loads.hpp"
#include "mpm_sdem/core/profile.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/sph/sph.hpp"
#include "mpm_sdem/core/time_step.hpp"
#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world_command.hpp"

namespace mpm_sdem {

namespace detail {
struct SphState;
struct SphWorld;
}  // namespace detail

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
/// cells across): "" or why not. Checked by the scene parser and by World; what they may not
/// meet is in the exclusions' table (exclusions.hpp).
Problem periodicProblem(const WorldDef& def);

/// What a step did.
struct StepInfo {
  Real dt = 0;         ///< s, the step taken
  bool finite = true;  ///< false: a point's position or a block's state became NaN or infinite
  long clamped = 0;    ///< particles put back inside the domain this step
  /// The first moving block whose state is not finite (finite is then false) or whose centre of
  /// mass has left the domain, and how, naming it; empty when every block is sound and inside.
  std::string block_problem;
};

/// The simulation: material points on a background grid (MpmSolver), with rigid blocks, FEM
/// bodies and SPH particles as a scene asks, advanced one step at a time through named, timed
/// stages, each subsystem at its own rate (docs/architecture.md, The step). Built from a
/// WorldDef, which composes the step: the stages this world needs, in order (step_stages.hpp),
/// composed again only when its makeup changes. Changed between steps only through its own calls
/// (world_changes.cpp), so that the coupling stays in step and every change is logged.
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
  /// Advance by dt through the composed stages; returns what happened.
  StepInfo step(Real dt);
  /// The stages a step runs, in order (composeStep of this world's makeup).
  const std::vector<Stage>& stages() const { return stages_; }
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
  const std::vector<MaterialParams>& materialParams() const { return mpm_.params(); }
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
  const Particles& particles() const { return mpm_.particles(); }
  Particles& particles() { return mpm_.particles(); }
  ///@}
  /// The background grid of the last step.
  const Grid& grid() const { return mpm_.grid(); }
  /// Which points sleep (SolverDef::sleep).
  const Sleep& sleep() const { return mpm_.sleep(); }
  /// The nodes' largest over-fill now, max(0, v_i - V_i) / h^2 (VolumeFit).
  Real largestOverfill() { return mpm_.largestOverfill(); }
  /// What the last step's volume fit found (SolverDef::volume_fit).
  const VolumeFit::Result& lastVolumeFit() const { return mpm_.lastFit(); }
  /// Memory held, in bytes: the particle columns with their tile bins, and the grid arrays.
  using Memory = MpmSolver::Memory;
  /// What the world holds now.
  Memory memory() const { return mpm_.memory(); }
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
  void resetProfile();
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
  /// What this world is made of now, as the step's stages go.
  StepMakeup makeup() const;
  /// The step's stages from the makeup (stages_), and the profile's list of stages with them.
  /// Called on construction and whenever the makeup may change (bodies or point loads come or
  /// go, a checkpoint restored).
  void compose();
  /// What a stage reads beyond the world: the step, the kick's span, what the step found.
  struct StepScratch {
    Real dt;
    Real kick;
    StepInfo& info;
  };
  /// One stage of the step (a switch over Stage: no virtual call, no allocation).
  void runStage(Stage stage, StepScratch& s);
  /// The blocks and point loads keep the tiles near them awake (SolverDef::sleep).
  void keepBlocksAwake();
  /// The step's velocity change after a coupling's correction: damped (SolverDef::damping) as
  /// a whole, and the walls again (a correction may push into one).
  void correctedWalls(Real kick);
  void couplingStage(Real dt, Real kick, void (Coupling::*stage)(CouplingStep&));
  void stepBodies(Real dt);
  /// StepInfo::block_problem and, for a block's state, finite.
  void checkBlocks(StepInfo& info) const;
  void initCoupling();
  /// Whenever the blocks come or go: the set of every kind of contact body, and what the FEM
  /// bodies meet.
  void linkContactBodies();
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
  MpmSolver mpm_;  ///< the material points, the grid, the walls and the transfers
  std::unique_ptr<Blocks> blocks_;
  std::unique_ptr<FemBodies> fem_;
  std::unique_ptr<ContactSet> set_;  ///< when there are blocks and FEM bodies
  std::unique_ptr<Coupling> coupling_;
  std::unique_ptr<detail::SphState> sph_;  ///< sph_step.hpp's; null without SPH
  /// For the contact term of the time step: the smallest mass per spring scale of a point
  /// (kg/m; impSpringScale) and the largest scale.
  Real lightest_point_ = 0;
  Real largest_spring_scale_ = 1;
  PointLoads point_loads_;  ///< setPointLoad's
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
  std::vector<Stage> stages_;  ///< compose()'s
  bool damped_kick_ = true;    ///< the kick damps (no coupling's correction follows to do it)
  Profile profile_;
};

}  // namespace mpm_sdem
