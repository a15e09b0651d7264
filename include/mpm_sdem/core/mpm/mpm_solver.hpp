/// \file
/// The MPM solver (seed 000 sec. 2): material points on a background grid, the domain's walls and
/// periodic sides, and the transfers between them, as the stages World composes its step of
/// (step_stages.hpp) and times. It knows nothing of blocks, FEM bodies or SPH: those act on its
/// grid between its stages.
#pragma once

#include <cstddef>
#include <initializer_list>
#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/boundary.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/mpm/sleep.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/mpm/volume_fit.hpp"
#include "mpm_sdem/core/mpm/volumetric_average.hpp"
#include "mpm_sdem/core/time_step.hpp"

namespace mpm_sdem {

/// Whether a world of this domain, cell and bodies fits in memory (limits::memoryProblem, with
/// the bodies' points counted on their bounding boxes): "" or why not. Checked before anything
/// is allocated, by the scene parser and by MpmSolver.
Problem sizeProblem(const DomainDef& domain, Real cell_size, const std::vector<BodyDef>& bodies);

/// Particles and grid with the stages of an MPM step. A stage does its work unasked: whether it
/// runs at all is World's choice, made once (composeStep).
class MpmSolver {
 public:
  /// Fills the bodies with points, in tile order. Throws std::invalid_argument on a definition
  /// the scene layer should have refused (a domain not a whole number of cells, a body naming no
  /// material, a world too large).
  MpmSolver(const DomainDef& domain, Real cell_size, const SolverDef& solver,
            const std::vector<MaterialDef>& materials, const std::vector<BodyDef>& bodies);

  ///@{
  /// The material points (structure of arrays), the grid of the last step and the points' tiles.
  const Particles& particles() const { return particles_; }
  Particles& particles() { return particles_; }
  const Grid& grid() const { return grid_; }
  Grid& grid() { return grid_; }
  const Tiles& tiles() const { return tiles_; }
  Tiles& tiles() { return tiles_; }
  ///@}
  ///@{
  /// Which points sleep (SolverDef::sleep).
  const Sleep& sleep() const { return sleep_; }
  Sleep& sleep() { return sleep_; }
  ///@}
  /// Each material's parameters as the constitutive updates use them.
  const std::vector<MaterialParams>& params() const { return params_; }
  /// The solver's choices (gravity as last set).
  const SolverDef& def() const { return def_; }
  /// The box and its walls.
  const DomainDef& domain() const { return domain_; }
  /// Gravity on the material from the next step on (m/s^2).
  void setGravity(const Vec2& gravity) { def_.gravity = gravity; }
  /// Whether the left and right sides are one (WallType::kPeriodic).
  bool periodicX() const { return domain_.left.type == WallType::kPeriodic; }
  /// Whether the domain has the flume's side walls (SidewallsDef).
  bool hasSidewalls() const { return domain_.sidewalls.width > 0; }
  /// Whether the volume fit runs: SolverDef::volume_fit, and some material flows.
  bool fits() const { return fits_; }

  /// Memory held, in bytes, and the nodes the last step cleared and updated.
  struct Memory {
    std::size_t particle_bytes = 0;  ///< the particle columns and their tile bins
    std::size_t grid_bytes = 0;      ///< the grid arrays
    std::size_t grid_nodes = 0;      ///< nodes of the whole domain
    std::size_t active_nodes = 0;    ///< nodes the last step cleared and updated
  };
  /// What the solver holds now.
  Memory memory() const;

  /// The material's stable step (seed 000 eq. 51, first term, and explicit viscous diffusion):
  /// kappa_1 = cfl, or longest (StepLimit::kMax) when that is shorter.
  TimeStepChoice materialStep(Real cfl, Real longest) const;

  /// @name Stages, in the order of a step
  ///@{
  /// The awake points binned by grid tile.
  void bin();
  /// With sleeping material: which tiles sleep in this step of dt (Sleep::update; the blocks'
  /// boxes given to sleep().keepAwake first), the awake points binned again on a change.
  void updateSleep(Real dt);
  /// Zeroes the nodes the last step used.
  void clearGrid();
  /// P2G: mass and momentum (with APIC's affine part), and with force the internal force (USL).
  void particleToGrid(bool momentum, bool force);
  /// With sleeping material: the sleepers' mass on the nodes the awake points use.
  void addSleepersMass();
  ///@{
  /// Periodic in x (periodicX()): nodes i and i + cells_x are one node, so each gets the sum of
  /// both; the mass and momentum, and the forces with the side walls' load.
  void foldMomentum() { foldPeriodic({&grid_.mass, &grid_.mom_x, &grid_.mom_y}); }
  void foldForces() { foldPeriodic({&grid_.force_x, &grid_.force_y, &sidewall_load_}); }
  ///@}
  /// The nodes' mass and momentum times SolverDef::inertia_scale != 1 (their velocity unchanged):
  /// from here on the grid's mass is the inertial one; gravity keeps the true weight.
  void scaleInertia();
  /// The nodal velocities: without after_force, v0 = p / m (eq. 20); with it, the kick by the
  /// nodal force and gravity (eq. 11, 17), with local damping unless !damp. Walls applied.
  void gridVelocity(Real kick, bool after_force, bool damp = true);
  /// Local damping on the whole of a step's velocity change, for a coupling that changes the
  /// velocities after the update (its impulses are part of the force the damping must see).
  void dampVelocityChange(Real kick);
  /// The domain's walls on the nodes' velocities (vel_x, vel_y).
  void applyWalls() { applyWalls(grid_.vel_x, grid_.vel_y); }
  /// Each point's L_p from the pre-kick velocity, its divergence averaged over the nodes
  /// (SolverDef::volumetric_average; stressAndInternalForce then takes L_p as it is).
  void averageVolumetricRate();
  /// USF: velocity gradient, stress update and internal force in one sweep, with the side walls'
  /// load from the new pressure.
  void stressAndInternalForce(Real dt);
  /// With sleeping material: the sleepers' internal force on the awake nodes (USF).
  void addSleepersForce();
  /// USL: the side walls' load from the points' pressure (after P2G).
  void sidewallLoad();
  /// The side walls' friction on the nodes' velocities after the kick (with side walls).
  void sidewallFriction(Real kick);
  /// G2P: velocity, affine matrix and position (eq. 26-31); material_points: only those tiles'
  /// points (with SPH), or nullptr for all (the awake ones with sleeping material, whose tiles
  /// the step's moving nodes then mark, noteMovingNodes). Counts points put back inside the
  /// domain, and clears finite on a NaN.
  void gridToParticle(Real dt, const Tiles* material_points, long& clamped, bool& finite);
  /// With sleeping material: the sleeping tiles the step's moving nodes reach
  /// (Sleep::noteMovingNodes).
  void noteMovingNodes();
  /// USL: the stress update after G2P.
  void constitutiveUpdate(Real dt);
  /// When fits(): the flowing materials' shearing points moved down the nodes' over-fill
  /// (VolumeFit::fit), once the step's positions and volumes are final.
  void fitVolumes(Real dt);
  ///@}

  /// The nodes' over-fill now: the largest max(0, v_i - V_i) / h^2 (VolumeFit::measure).
  Real largestOverfill();
  /// What the last step's fit found (zero without SolverDef::volume_fit).
  const VolumeFit::Result& lastFit() const { return last_fit_; }

  /// Negates the points' velocities and affine matrices (World::reverseVelocities).
  void reverseVelocities();

 private:
  /// f(first, end) for each run of consecutive nodes of the tiles (Tiles::nodeRuns), in parallel.
  template <class F>
  void forActiveNodes(const std::vector<int>& tiles, F&& f);
  void applyWalls(std::vector<Real>& vx, std::vector<Real>& vy) const;
  void foldPeriodic(std::initializer_list<std::vector<Real>*> fields);
  /// The wall load's nodes zeroed where points are (nullptr: no side walls).
  Real* clearedSidewallLoad();
  /// 2 mu_w / W (1/m).
  Real sidewallCoefficient() const;

  DomainDef domain_;
  SolverDef def_;
  std::vector<MaterialParams> params_;
  Particles particles_;
  Grid grid_;
  Tiles tiles_;
  Sleep sleep_;
  VolumeFit volume_fit_;
  VolumetricAverage volumetric_average_;  ///< solver.volumetric_average
  std::vector<char> flows_;               ///< per material: MaterialTraits::flows
  bool fits_ = false;                     ///< SolverDef::volume_fit, and some material flows
  VolumeFit::Result last_fit_;
  ///@{
  /// The sleepers' fastest wave speed (m/s), as of Sleep::generation (materialStep's cache).
  mutable long sleepers_generation_ = -1;
  mutable Real sleepers_speed_ = 0;
  ///@}
  std::vector<Tiles::NodeRun> node_runs_;  ///< scratch of forActiveNodes
  /// Per node: the side walls' largest friction force (N/m), when the domain has side walls.
  std::vector<Real> sidewall_load_;
  /// h^2 / (2 nu) of the most viscous fluid (s); infinite without one.
  Real viscous_dt_;
};

}  // namespace mpm_sdem
