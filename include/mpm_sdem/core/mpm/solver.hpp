/// \file
/// The MPM solver's choices (seed 000 sec. 2): kernel, velocity transfer, stress update order,
/// gravity and local damping; part of WorldDef, read by the point sweeps.
#pragma once

#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Grid-to-particle velocity transfer (seed 000 eq. 26-31). kAsflip: APIC's affine matrix with
/// FLIP's velocity increment (Fei et al. 2021's ASFLIP, its blend at 1 and the points moved by
/// the grid's velocity): no share of the velocity is lost per transfer.
enum class TransferScheme { kPic, kFlip, kApic, kAsflip };
/// Whether the points carry APIC's affine matrix B to and from the grid.
constexpr bool carriesAffine(TransferScheme t) {
  return t == TransferScheme::kApic || t == TransferScheme::kAsflip;
}
/// Update stress first (seed 000 sec. 2.2) or last.
enum class StressUpdate { kUsf, kUsl };

/// Sand at rest costs nothing (docs/method.md, Sleeping material): the points of a tile of
/// Tiles::kSize^2 cells that have all stayed slower than speed for time, away from every block,
/// skip the step, with their velocity set to zero and their share of the grid (mass and the
/// internal force of their stress) kept. A tile wakes, with all its points, when a node its
/// points read moves faster than speed, when an awake point enters it, or when a block comes
/// within margin of it. USF and material points only (not with SPH, FEM bodies, side walls,
/// periodic sides or point loads).
struct SleepDef {
  Real speed = 0;    ///< m/s: the speed below which points may sleep; 0: never
  Real time = 0.05;  ///< s: how long a tile's points stay slower than speed before they sleep
  Real margin = 0;   ///< m: how near a block keeps a tile awake; 0: two tiles (6 cells)
  /// Whether points may sleep.
  bool on() const { return speed > 0; }
};

/// The solver's choices (scene section `solver`).
struct SolverDef {
  KernelType kernel = KernelType::kQuadraticBSpline;  ///< the grid's shape functions
  TransferScheme transfer = TransferScheme::kApic;    ///< how velocities go back to the points
  Real pic_fraction = 0.01;  ///< alpha of eq. 28 (1 = PIC, 0 = FLIP); kFlip only
  /// kAsflip only: the time over which a point's departure from the grid's velocity field decays
  /// (s), blended by exp(-dt / time) per step so that the loss does not depend on the step and
  /// momentum stays exact (one factor for every point). 0: never (pure ASFLIP). A granular
  /// deposit needs it: nothing else takes the agitation of points that carry no stress.
  Real asflip_relaxation_time = 0;
  StressUpdate stress_update =
      StressUpdate::kUsf;  ///< stress before (USF) or after (USL) the grid update
  Vec2 gravity{0, -9.81};  ///< m/s^2
  /// Local non-viscous (Cundall) damping factor in [0, 1): each nodal force component is reduced
  /// by damping * |F| against the node's velocity. It removes kinetic energy without changing
  /// the static equilibrium; for settling quasi-static states only (0 = off).
  Real damping = 0;
  /// Inertia scaling for quasi-static scenes (dimensionless, >= 1): the material's density in
  /// the momentum balance is s rho, while its weight (rho g) and its stress keep the true
  /// density. Static equilibria are unchanged; the wave speed falls by sqrt(s), so the CFL step
  /// grows by sqrt(s); every acceleration of the material falls by s (free fall at g / s), and
  /// the world is the unscaled one with every speed sqrt(s) times larger: admissible where the
  /// answer at sqrt(s) times the tool's speed is the answer at its speed (docs/method.md,
  /// Quasi-static scenes). Not with FEM bodies or SPH particles, whose inertia it would leave
  /// true. 1: off.
  Real inertia_scale = 1;
  SleepDef sleep;  ///< sleeping material (off by default)
  /// Volume-consistent points (VolumeFit, docs/method.md): after each step the shearing points of
  /// the flowing materials (granular, fluid) move down the nodes' over-fill, so that their
  /// volumes keep tiling the space they share. Off: the points go where the grid carries them.
  bool volume_fit = false;
  /// The velocity's divergence averaged over the nodes before each stress update (USF), against
  /// volumetric locking (VolumetricAverage, issue 90). Off: each point's own divergence.
  bool volumetric_average = false;
  /// A world of fewer awake material points and no SPH steps on the calling thread alone:
  /// below this, starting and ending a step's ~24 parallel regions (3.5 us each on two cores
  /// here) costs more than sharing its work saves (docs/performance.md). Speed only: the results
  /// are bit-identical on any number of threads (test_threads). 0: always share.
  long parallel_min_points = 2000;
};

}  // namespace mpm_sdem
