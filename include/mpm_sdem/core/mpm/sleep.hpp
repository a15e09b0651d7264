/// \file
/// Sleeping material (SleepDef): points at rest, away from every block, skip the step and keep
/// their share of the grid, as Box2D's islands sleep. The unit is the tile of Tiles (kSize^2
/// cells): a tile's points sleep and wake together. Between steps, update() decides which tiles
/// sleep from the points' speeds, the nodes' speeds of the last step and the blocks' boxes; the
/// step then bins only the awake points (Tiles::bin), adds the sleepers' share to the nodes the
/// awake points use (addMass, addForce) and moves only the awake points (runs()).
#pragma once

#include <cstdint>
#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Which tiles sleep, and the sleepers' share of the grid (see the file's comment).
class Sleep {
 public:
  /// Sized for the grid and its tiles; every point awake.
  void init(const SleepDef& def, const Grid& g, const Tiles& t);
  /// Whether points may sleep (SleepDef::on).
  bool on() const { return def_.on(); }
  /// Whether any point sleeps now.
  bool any() const { return sleeping_points_ > 0; }
  /// Points asleep now.
  long sleepingPoints() const { return sleeping_points_; }
  /// Counts the rebuilds: it changes whenever the sleeping points do.
  long generation() const { return generation_; }
  /// Sleeping tiles that a moving node has reached: they wake at the next update().
  long wakingTiles() const {
    long n = 0;
    for (std::size_t t = 0; t < asleep_.size(); ++t) n += asleep_[t] && moved_[t];
    return n;
  }

  /// Keeps the tiles that overlap the box [lo, hi] grown by the margin awake (a block's box);
  /// until the next update().
  void keepAwake(const Vec2& lo, const Vec2& hi);
  /// After a step's grid update (G2P read it): which sleeping tiles a node their points read
  /// moved faster than SleepDef::speed in (for the next update()).
  void noteMovingNodes(const Grid& G);
  /// At the start of a step of dt (s), with T the awake points binned where they are: wakes the
  /// sleeping tiles a fast node (noteMovingNodes), an entering point or a block reaches, and puts
  /// to sleep the awake tiles whose points have all been slower than SleepDef::speed for
  /// SleepDef::time and that no block reaches (their points at rest: v = 0, B = 0, L = 0). Rebuilds
  /// the share and the runs when a tile changed, and then returns true: the awake points must be
  /// binned again (Tiles::rebin).
  bool update(Particles& P, const Tiles& T, KernelType kernel, Real dt);
  /// The sleepers' share rebuilt from the points (after a checkpoint is read).
  void rebuild(const Particles& P, KernelType kernel);

  ///@{
  /// The sleepers' mass (after P2G) and internal force (after the stress sweep) added to the
  /// nodes [first, end).
  void addMass(Grid& G, int first, int end) const;
  void addForce(Grid& G, int first, int end) const;
  ///@}
  /// The awake points as runs of at most kRun points in storage order (any() only).
  const std::vector<PointRun>& runs() const { return runs_; }
  /// Points per run: a multiple of every SIMD width, small enough to share among threads.
  static constexpr long kRun = 256;

 private:
  friend struct detail::CheckpointAccess;
  /// What outlives a step: the tiles' states, quiet times and moving nodes (the points' flags
  /// are a column of Particles; the share and the runs are rebuilt from them).
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(asleep_, quiet_, moved_);
  }

  SleepDef def_;
  int nx_ = 0, ny_ = 0;               ///< tiles per axis (Tiles::nx, ny)
  Real margin_ = 0;                   ///< m
  std::vector<std::uint8_t> asleep_;  ///< per tile, 1 while its points sleep
  std::vector<Real> quiet_;           ///< per tile, how long its points have been slow (s)
  std::vector<std::uint8_t> moved_;   ///< per sleeping tile, 1 if a node it reads moved fast
  enum Change : std::uint8_t { kStays, kSleeps, kWakes };
  std::vector<std::uint8_t> change_;  ///< per tile, update()'s decision (Change)
  std::vector<std::uint8_t> near_;    ///< per tile, 1 if keepAwake() reached it
  long sleeping_points_ = 0;
  long generation_ = 0;
  Tiles sleepers_;  ///< the sleeping points by tile (Tiles::bin with asleep)
  Grid share_;      ///< their mass, (zero) momentum and internal force on the nodes
  std::vector<PointRun> runs_;
};

}  // namespace mpm_sdem
