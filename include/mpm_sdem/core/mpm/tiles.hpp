/// \file
/// Particles binned by square tiles of grid cells. The bins serve two purposes:
/// - race-free parallel P2G: tiles are coloured like a 2x2 checkerboard; a particle writes only to
///   nodes within one node of its tile, so two tiles of one colour never write the same node and
///   can be processed by different threads. The result does not depend on the thread count:
///   every node sums its contributions colour by colour and, inside a tile, in particle order.
/// - a sparse grid: only node tiles next to an occupied tile are cleared and updated, so empty
///   domain costs nothing per step (the node arrays stay dense in memory).
#pragma once

#include <array>
#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"

namespace mpm_sdem {

/// The particles binned by tiles of kSize x kSize cells (see the file's comment).
struct Tiles {
  /// Cells per tile side. A particle in cell c touches nodes c-1 .. c+2 with every kernel (3 or 4
  /// nodes), so tiles two apart must not share a node: needs kSize >= 3. Small tiles give two
  /// threads enough tiles of each colour to share in small scenes.
  static constexpr int kSize = 3;

  ///@{
  /// tiles per axis; tile (a, b) holds nodes a*kSize ...
  int nx = 0, ny = 0;
  ///@}
  std::vector<int> start;  ///< per tile, its first entry in order (size tiles+1)
  std::vector<int> order;  ///< particle indices grouped by tile, ascending in a tile
  ///@{
  /// With SPH particles (binByKind), tile t's entries order[start[t], start[t+1]) hold its
  /// material points up to mpm_end[t], then its SPH particles; the grid sums (P2G) take
  /// order[start[t], grid_end[t]): the material points and the SPH particles of the transition
  /// band (seed 001 sec. 4). Without SPH both are start[t+1].
  std::vector<int> mpm_end, grid_end;
  ///@}
  std::array<std::vector<int>, 4> colour;  ///< occupied tiles of each colour, ascending
  std::vector<int> active;                 ///< node tiles within reach of a particle, ascending
  std::vector<int> previous;               ///< active tiles of the previous binning
  std::vector<int> retired;                ///< tiles in previous but no longer active
  /// Periodic in x (WallType::kPeriodic): a row of tiles any point reaches is active whole, so
  /// that both copies of a node on the periodic sides are.
  bool periodic_x = false;

  /// Sizes the tiles for the grid.
  void init(const Grid& g);
  /// Bytes of the per-particle arrays (sort keys and order).
  std::size_t particleBytes() const { return (key_.capacity() + order.capacity()) * sizeof(int); }
  /// Bin the awake particles (Particles::asleep 0; with asleep, the sleeping ones instead) by
  /// the cell they are in (stable counting sort, O(N + tiles)), every one taking part in the grid
  /// sums; then activate(). The others follow the last tile in order, outside every tile. Given
  /// the awake points' runs (Sleep::runs), only those are read and binned, and order holds them
  /// alone.
  void bin(const Particles& P, const Grid& g, bool asleep = false,
           const std::vector<PointRun>* awake = nullptr);
  /// Bin the awake particles again in the same step (after some fell asleep or woke): the
  /// previous step's active tiles stay previous, so that clearing the grid still finds them.
  void rebin(const Particles& P, const Grid& g, const std::vector<PointRun>* awake);
  /// Bin by tile and, within a tile, by Particles::kind (material points first). grid_end is
  /// mpm_end: the caller adds the SPH particles of the band, then calls activate().
  void binByKind(const Particles& P, const Grid& g);
  /// The colour lists and active node tiles from the tiles' grid entries [start, grid_end).
  void activate();
  /// The nodes of a list of tiles (ascending, as active, previous and retired are) as runs of
  /// consecutive nodes [first, end): tiles next to each other in a row of tiles share one run per
  /// row of nodes, so the node sweeps run long vectorisable loops instead of three nodes at a time.
  struct NodeRun {
    ///@{
    /// Node indices of the run [first, end).
    int first, end;
    ///@}
  };
  /// The runs of the tiles' nodes, into runs.
  void nodeRuns(const Grid& g, const std::vector<int>& tiles, std::vector<NodeRun>& runs) const;

 private:
  friend struct detail::CheckpointAccess;
  /// The last binning: the next step's contact search and time step read it before binning anew.
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(start, order, mpm_end, grid_end, colour, active, previous, retired);
  }
  void sort(const Particles& P, const Grid& g, bool by_kind, bool asleep,
            const std::vector<PointRun>* awake);

  std::vector<int> key_;              ///< per particle, its tile (times 2, plus its kind)
  std::vector<int> counts_;           ///< per thread and tile: count, then write position
  std::vector<unsigned char> reach_;  ///< per tile, 1 if within reach of a particle
};

}  // namespace mpm_sdem
