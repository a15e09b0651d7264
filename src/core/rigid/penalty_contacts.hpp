// The seed's block-block contact (seed 000 eq. 38-43): linear springs between the vertices of
// one rounded outline and the edges of the other, dashpots sized for the asked restitution,
// Coulomb-capped tangential springs with a history, and adhesion (seed 003 sec. 4.3). Works on
// contact shapes, so a cluster of discs meets other blocks disc by disc. Internal header.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"

namespace mpm_sdem::detail {

class PenaltyContacts {
 public:
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

  BlockContactDef def_;
  std::vector<std::pair<Key, Vec2>> history_, next_history_;  // sorted by key
  std::vector<Spring> springs_;                               // one pair's, reused
  std::vector<Box> boxes_;                                    // per block, reused
};

}  // namespace mpm_sdem::detail
