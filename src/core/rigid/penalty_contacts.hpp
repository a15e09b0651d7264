// The seed's block-block contact (seed 000 eq. 38-43): linear springs between the vertices of
// one rounded outline and the edges of the other, dashpots sized for the asked restitution,
// Coulomb-capped tangential springs with a history, and adhesion (seed 003 sec. 4.3). Works on
// contact shapes, so a cluster of discs meets other blocks disc by disc. Internal header.
#pragma once

#include <box2d/b2_dynamic_tree.h>

#include <Eigen/Eigenvalues>

#include <cstdint>
#include <memory>
#include <utility>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem::detail {

class PenaltyContacts {
 public:
  using Rates = Eigen::Matrix<Real, 6, 1>;
  // A pair's springs: a face meets a face with four; more means the outlines passed through.
  static constexpr int kMaxSprings = 16;
  using Matrix = Eigen::Matrix<Real, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxSprings, kMaxSprings>;
  using Vector = Eigen::Matrix<Real, Eigen::Dynamic, 1, 0, kMaxSprings, 1>;

  explicit PenaltyContacts(const BlockContactDef& def) : def_(def) {}
  // Adds the springs' forces on every block (Blocks::addContactForce) for a substep of h.
  void apply(Blocks& blocks, Real h);
  // The largest stable substep (contactTimeStep, eq. 39), infinite when no spring can form.
  Real stableStep(const Blocks& blocks, Real kappa2) const;

 private:
  // An overlapping vertex-edge pair (seed 000 eq. 38-41).
  struct Spring {
    Vec2 point;   // contact point, eq. 41 (m)
    Vec2 normal;  // from the edge's shape towards the vertex's
    Real xi;      // overlap (m)
    int vertex;   // index of the vertex in its shape
    int side;     // 0: a vertex of the first shape of the pair
    // Its normal rate (the vertex's side moving away) as a row acting on the two blocks'
    // velocities (v_x, v_y, w of the first shape's block, then the second's).
    Rates rate;
    Real push;  // N/m, before the cap at zero (pairPush)
  };
  // A tangential spring's name across steps and removals: the two shapes' keys, the vertex and
  // the side.
  struct Key {
    std::uint64_t first, second;
    int vertex, side;
    bool operator<(const Key& o) const;
    bool operator==(const Key& o) const;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(first, second, vertex, side);
    }
  };
  friend struct detail::CheckpointAccess;
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(history_);  // the tangential springs' stretch
  }
  void pair(Blocks& blocks, int p, int q, Real h);
  // The springs' rates and pushes (N/m, may be negative) for a substep h, each mode of the pair
  // stepped exactly.
  void pairPush(const Blocks& blocks, int p, int q, Real gamma, Real h);
  // The broad phase: block pairs whose boxes overlap, at least one of them dynamic, into
  // pairs_ in the order (i < j) of the list, as a loop over all pairs would give them.
  void findPairs(const Blocks& blocks);
  void placeBoxes(const Blocks& blocks);

  BlockContactDef def_;
  std::vector<std::pair<Key, Vec2>> history_, next_history_;  // sorted by key
  std::vector<Spring> springs_;                               // one pair's, reused
  Eigen::SelfAdjointEigenSolver<Matrix> modes_;               // of their A (pairPush)
  // Broad phase: every block's box (m) and its proxy in a Box2D dynamic tree, in Box2D units
  // (whose fattening, 0.1 unit, suits the blocks' sizes). A static block's is placed when the
  // blocks change (Blocks::layoutVersion) and stays; the others move each substep.
  std::vector<Box> boxes_;
  std::vector<std::int32_t> proxies_;
  std::vector<int> dynamic_;  // the dynamic blocks, which ask the tree for their neighbours
  std::unique_ptr<b2DynamicTree> tree_;
  std::uint64_t placed_version_ = 0;
  std::vector<std::pair<int, int>> pairs_;
};

}  // namespace mpm_sdem::detail
