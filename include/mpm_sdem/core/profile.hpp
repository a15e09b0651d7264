/// \file
/// Wall-clock time spent in each named stage of the step (Box2D's b2Profile, accumulated).
#pragma once

#include <chrono>

namespace mpm_sdem {

/// The named stages of a step, as profiles and outputs name them.
enum class Stage : int {
  kTimeStep,      ///< stable time step (CFL and contact terms)
  kContact,       ///< IMP search and forces, and their spreading onto the grid
  kSort,          ///< particles binned by grid tile (Tiles)
  kClearGrid,     ///< zeroing the nodes the last step used
  kP2G,           ///< particle to grid: mass and momentum (USF), or with the internal force (USL)
  kGridUpdate,    ///< nodal velocities, kick and walls
  kG2P,           ///< grid to particle: velocity, affine matrix, position
  kConstitutive,  ///< stress update of USL
  kVolumeFit,     ///< the flowing points moved down the nodes' over-fill (VolumeFit)
  kStress,        ///< USF: velocity gradient, stress update and internal force in one sweep
  kBodies,        ///< solid bodies: blocks' springs and Box2D, FEM bodies' elements and step
  kSph,   ///< SPH particles (seed 001): kinds and band, velocity gradient, stress, forces, move
  kCount  ///< how many stages
};

/// The stage's name in outputs ("p2g", "contact", ...).
const char* stageName(Stage stage);

/// Wall time spent in each stage of the step (s) and the steps counted.
struct Profile {
  double seconds[static_cast<int>(Stage::kCount)] = {};  ///< per stage
  long steps = 0;                                        ///< steps timed
  /// All stages together (s).
  double total() const;
};

/// Adds the wall time from its construction to its destruction to one stage of a Profile.
class StageTimer {
 public:
  /// Starts timing stage into profile.
  StageTimer(Profile& profile, Stage stage)
      : slot_(profile.seconds[static_cast<int>(stage)]), start_(Clock::now()) {}
  ~StageTimer() { slot_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  using Clock = std::chrono::steady_clock;
  double& slot_;
  Clock::time_point start_;
};

}  // namespace mpm_sdem
