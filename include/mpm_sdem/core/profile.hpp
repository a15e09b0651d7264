// Wall-clock time spent in each named stage of the step (Box2D's b2Profile, accumulated).
#pragma once

#include <chrono>

namespace mpm_sdem {

enum class Stage : int {
  kTimeStep,      // stable time step (CFL and contact terms)
  kContact,       // IMP search and forces, and their spreading onto the grid
  kSort,          // particles binned by grid tile (Tiles)
  kClearGrid,     // zeroing the nodes the last step used
  kP2G,           // particle to grid: mass and momentum (USF), or with the internal force (USL)
  kGridUpdate,    // nodal velocities, kick and walls
  kG2P,           // grid to particle: velocity, affine matrix, position
  kConstitutive,  // stress update of USL
  kStress,        // USF: velocity gradient, stress update and internal force in one sweep
  kBodies,        // solid bodies: blocks' springs and Box2D, FEM bodies' elements and step
  kSph,  // SPH particles (seed 001): kinds and band, velocity gradient, stress, forces, move
  kCount
};

const char* stageName(Stage stage);

struct Profile {
  double seconds[static_cast<int>(Stage::kCount)] = {};
  long steps = 0;
  double total() const;
};

class StageTimer {
 public:
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
