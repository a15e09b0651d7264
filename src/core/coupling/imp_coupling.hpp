// Identified material points (seed 000 sec. 4): material points within the Verlet distance of a
// block are pairs; those whose contact disk (radius r_p, at most the point's depth below its
// body's outline: materialReach in particles.hpp) overlaps the block's rounded outline exchange a
// DEM contact force with it (eq. 44-46), which acts on the material at the contact point, so on the
// grid around the point (eq. 47-48 shifted to the contact point), and, opposite, on the block at
// the same point (eq. 49-50). The MPM-GRID variant (seed 000 sec. 5.4, Fig. 17B) puts the same
// force on the nodes around the contact point instead.
#pragma once

#include <cmath>
#include <vector>

#include "coupling/contact_search.hpp"
#include "mpm_sdem/core/coupling/coupling.hpp"

namespace mpm_sdem {

// What point p's springs are k_n and k_t times: 1, or its lattice spacing (m; the length of
// contact it stands for) when the stiffness is per length of contact. The spacing, not
// sqrt(V0): an outer point's volume carries the shape's moments (pointVolumes) but not the
// length of its face.
inline Real impSpringScale(SpringBasis basis, const Particles& P, std::size_t p, Real cell_size) {
  return basis == SpringBasis::kPerLength ? 2 * P.half_size[p] * cell_size : Real(1);
}

class ImpCoupling final : public Coupling {
 public:
  ImpCoupling(const CouplingDef& def, const Vec2& domain_min, const Vec2& domain_max,
              Real cell_size);

  // Seed 000 sec. 4.2, step 1: the force of every IMP from the state at the start of the step;
  // the reactions go to the blocks.
  void beforeStep(CouplingStep& s) override;
  void addGridForces(CouplingStep& s) override;
  bool hasSprings() const override { return true; }
  void bodiesChanged() override { search_.invalidate(); }

  const std::vector<ContactPair>& contacts() const { return search_.pairs(); }
  long rebuilds() const { return search_.rebuilds(); }

 private:
  friend struct detail::CheckpointAccess;
  ContactSearch search_;
};

}  // namespace mpm_sdem
