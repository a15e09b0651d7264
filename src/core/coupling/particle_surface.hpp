// Particle-to-surface contact without a penalty stiffness (seed 002 sec. 3), for rigid blocks:
// pairs from the bucket-sort global search (sec. 3.1), the closest point on the block's rounded
// outline as local search (sec. 3.2, gap eq. 40 measured from the rounded surface), and the
// impulse that makes the point's velocity and the contact point's velocity equal (eq. 47-52),
// the block side taken with its effective mass at the contact point (mass and inertia) instead
// of eq. 49's nodal masses. No stiffness: the contact adds no term to the time step bound.
#pragma once

#include <vector>

#include "coupling/contact_search.hpp"
#include "mpm_sdem/core/coupling/coupling.hpp"

namespace mpm_sdem {

class ParticleSurfaceCoupling final : public Coupling {
 public:
  ParticleSurfaceCoupling(const CouplingDef& def, const Vec2& domain_min, const Vec2& domain_max,
                          Real cell_size);

  void correctGridVelocity(CouplingStep& s) override;
  CouplingHooks hooks() const override { return {false, false, true, false}; }
  bool correctsVelocities() const override { return true; }
  void bodiesChanged() override { search_.invalidate(); }
  std::string settings() const override;
  void saveState(cereal::BinaryOutputArchive& ar) override;
  void loadState(cereal::BinaryInputArchive& ar) override;

  struct Record {
    int particle = 0, block = 0;
    Real gap = 0;               // m, from the rounded outline, at the start of the step
    Vec2 normal{0, 1};          // out of the block
    Vec2 impulse{0, 0};         // on the point (N s/m)
    Real target = 0;            // relative normal velocity aimed at: -gap/dt, or 0 (m/s)
    Vec2 relative_after{0, 0};  // point minus contact point velocity after the exchange (m/s)
    bool stuck = false;
    template <class Archive>
    void serialize(Archive& ar) {
      ar(particle, block, gap, normal, impulse, target, relative_after, stuck);
    }
  };
  // The contacts of the last step.
  const std::vector<Record>& contacts() const { return records_; }

 private:
  ContactSearch search_;
  std::vector<Record> records_;
};

}  // namespace mpm_sdem
