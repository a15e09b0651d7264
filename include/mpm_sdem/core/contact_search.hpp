// Global and local search for material point - block pairs (seed 002 sec. 3.1, seed 000 sec.
// 4.1): the points are bucket-sorted by cell, each block scans the cells under its outline grown
// by a reach, and the pairs are kept until a point or block moves half the Verlet distance.
#pragma once

#include <vector>

#include "mpm_sdem/core/blocks.hpp"
#include "mpm_sdem/core/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

struct ContactPair {
  int particle = 0;
  int block = 0;
  Vec2 history{0, 0};  // accumulated tangential sliding (m), spring schemes
  Vec2 force{0, 0};    // on the particle (N/m) in the last step; zero when not touching
  Vec2 point{0, 0};    // contact point (m) in the last step
};

class ContactSearch {
 public:
  // reach (m): how far outside a block's rounded outline a point becomes a pair, on top of the
  // Verlet distance.
  void init(const Vec2& domain_min, const Vec2& domain_max, Real cell_size, Real reach,
            Real verlet_distance);
  // Rebuilds the pairs when anything moved more than half the Verlet distance. Pairs come
  // sorted by (block, particle); a pair that survives a rebuild keeps its history.
  void update(const Particles& P, const Blocks& B);
  void invalidate() { built_ = false; }
  // Block b was removed: drop its pairs and shift the later block indices down.
  void removeBlock(int b);

  std::vector<ContactPair>& pairs() { return pairs_; }
  const std::vector<ContactPair>& pairs() const { return pairs_; }
  long rebuilds() const { return rebuilds_; }

 private:
  bool needsRebuild(const Particles& P, const Blocks& B) const;
  void rebuild(const Particles& P, const Blocks& B);

  Vec2 lo_{0, 0};
  Real bucket_ = 1, reach_ = 0, verlet_ = 0;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_, cell_items_, cell_of_;
  std::vector<Real> x_built_, y_built_;
  std::vector<BlockState> blocks_built_;
  std::vector<ContactPair> pairs_, previous_;
  long rebuilds_ = 0;
  bool built_ = false;
};

}  // namespace mpm_sdem
