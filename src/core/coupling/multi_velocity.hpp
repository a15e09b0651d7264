// Grid-based multi-velocity contact (seed 002 sec. 2.4; the scheme of Liu et al. that seed 000
// compares against, its Fig. 17C): each block is sampled by points of its own, which give the
// block a mass and an outward normal at the grid nodes (eq. 23). At a node shared with the
// material, an approach (eq. 22) closer than the material's gap to the block there is resolved by
// the stick impulse that equalises the two velocities (eq. 27-28), or its Coulomb-slip limit (eq.
// 29-32). Adapted to rigid blocks: the block's side of eq. 28 uses its effective mass at the node
// (mass and inertia), so that stick makes the node's material velocity equal to the block's
// velocity there.
#pragma once

#include <vector>

#include "mpm_sdem/core/coupling/coupling.hpp"

namespace mpm_sdem {

class MultiVelocityCoupling final : public Coupling {
 public:
  MultiVelocityCoupling(const CouplingDef& def, Real cell_size);

  void correctGridVelocity(CouplingStep& s) override;
  std::string settings() const override;
  // No state beyond the base's: its samples and patches are scratch.
  CouplingHooks hooks() const override { return {false, false, true, false}; }
  bool correctsVelocities() const override { return true; }

 private:
  Real h_;
  std::vector<Vec2> samples_;  // one body's points, reused
  std::vector<Real> patch_mass_;
  std::vector<Vec2> patch_normal_;
  std::vector<int> near_points_;
  std::vector<Real> patch_gap_;  // the material's gap to the block at the node (m)
};

}  // namespace mpm_sdem
