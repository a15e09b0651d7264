// Identified material points (seed 000 sec. 4): material points within the Verlet distance of a
// block are candidates; those whose contact disk of radius r_p overlaps the block's rounded
// outline exchange a DEM contact force with it (eq. 44-46), which acts on the point, so on the
// grid (eq. 47-48), and, opposite, on the block at the contact point (eq. 49-50).
#pragma once

#include <vector>

#include "mpm_sdem/core/blocks.hpp"
#include "mpm_sdem/core/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

struct CouplingDef {
  Real normal_stiffness = 1e6;      // k_n of one IMP contact (N/m per metre of thickness)
  Real tangential_stiffness = 5e5;  // k_t (N/m per metre)
  Real contact_radius = 0;          // r_p (m); 0: h / sqrt(points per cell), inside eq. 45
  Real verlet_distance = 0;         // V_d (m); 0: half a cell
};

class ImpCoupling {
 public:
  struct Contact {
    int particle = 0;
    int block = 0;
    Vec2 history{0, 0};  // accumulated tangential sliding (m)
    Vec2 force{0, 0};    // on the particle (N/m); zero when the disks do not overlap
  };

  // contact_radius and verlet_distance must already be resolved (> 0).
  void init(const CouplingDef& def, const Vec2& domain_min, const Vec2& domain_max, Real cell_size);
  // Seed 000 sec. 4.2, step 1: refresh the candidate list if anything moved more than half the
  // Verlet distance, then compute the force of every IMP and add its reaction to the blocks.
  void computeForces(const Particles& particles, Blocks& blocks, Real dt);

  // A block was added: rebuild the candidate list before the next forces.
  void invalidate() { built_ = false; }
  // Block b was removed: drop its pairs and shift the later block indices down, keeping the
  // other pairs' tangential histories.
  void removeBlock(int b);

  const std::vector<Contact>& contacts() const { return candidates_; }
  const CouplingDef& def() const { return def_; }
  long activeContacts() const { return active_; }
  long rebuilds() const { return rebuilds_; }

 private:
  bool needsRebuild(const Particles& P, const Blocks& B) const;
  void rebuild(const Particles& P, const Blocks& B);

  CouplingDef def_;
  Vec2 lo_{0, 0};
  Real bucket_ = 1;
  int nx_ = 0, ny_ = 0;
  std::vector<int> cell_start_, cell_items_, cell_of_;
  std::vector<Real> x_built_, y_built_;
  std::vector<BlockState> blocks_built_;
  std::vector<Contact> candidates_, previous_;
  long active_ = 0, rebuilds_ = 0;
  bool built_ = false;
};

}  // namespace mpm_sdem
