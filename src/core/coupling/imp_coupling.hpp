// Identified material points (seed 000 sec. 4): material points within the Verlet distance of a
// block are pairs; those whose contact disk (radius r_p, at most the point's depth below its
// body's outline: materialReach in particles.hpp) overlaps the block's rounded outline exchange a
// DEM contact force with it (eq. 44-46), which acts on the material at the contact point, so on the
// grid around the point (eq. 47-48 shifted to the contact point), and, opposite, on the block at
// the same point (eq. 49-50). The MPM-GRID variant (seed 000 sec. 5.4, Fig. 17B) puts the same
// force on the nodes around the contact point instead.
//
// Multi-rate (ContactIntegration::kSubcycled): the springs are stiffer than the material, so they
// take n substeps of h = dt / n inside the material's step, each within eq. 51's contact bound,
// as subcycling does in explicit dynamics (Belytschko, Yen & Mullen 1979; the separate MPM and
// DEM steps of GeoTaichi's MPDEM). The material near a contact moves as the grid does over the
// step: its nodes' velocity ramps from v^n to v^{n+1} under the held internal force and gravity
// (seed 000 eq. 17 cut into n parts), plus the impulses the springs have given them so far. Each
// substep reads the grid's velocity at the contact and moves the point through the adjoint of the
// map that spreads its force (ContactStencil), so the spring and the grid exchange equal work; the
// blocks take the substep with the reactions. The grid receives the sum of the substeps'
// impulses and each block minus the same, so momentum is exchanged exactly. At n = 1 it is the
// explicit scheme of sec. 4.2 with the force put on the grid after the velocity update.
#pragma once

#include <cmath>
#include <vector>

#include "coupling/contact_search.hpp"
#include "mpm/contact_stencil.hpp"
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
  // Multi-rate: the substeps of the springs and the bodies (see above).
  void correctGridVelocity(CouplingStep& s) override;
  // Subcycled, the forces come in the substeps (correctGridVelocity), not before the step.
  CouplingHooks hooks() const override { return {true, !subcycles(), subcycles(), false}; }
  bool correctsVelocities() const override { return subcycles(); }
  bool subcycles() const override {
    return def_.normal_integration == ContactIntegration::kSubcycled;
  }
  void bodiesChanged() override { search_.invalidate(); }
  std::string settings() const override;
  void saveState(cereal::BinaryOutputArchive& ar) override;
  void loadState(cereal::BinaryInputArchive& ar) override;

  const std::vector<ContactPair>& contacts() const { return search_.pairs(); }
  long rebuilds() const { return search_.rebuilds(); }

 private:
  // Eq. 43-46 for pair c with shape b at core distance d, the point at x with velocity v_centre
  // (its centre's, with affine the point's velocity gradient adds the part at the contact
  // point; without, it is the velocity at the contact point), over a step dt: the force
  // on the point and the contact point, or false (history released) when they do not touch.
  bool springForce(ContactPair& c, int b, const CoreDistance& d, const Vec2& x,
                   const Vec2& v_centre, bool affine, const Particles& P, const ContactBodies& B,
                   Real dt, Real cell_size, Vec2& point, Vec2& force) const;
  // One point near one body during a multi-rate step.
  struct Substepping {
    int pair = 0;                    // index of the pair that carries the contact
    Vec2 shift{0, 0};                // how far the point has moved in the step (m)
    Vec2 start{0, 0};                // its grid's velocity at the contact at the step's start (m/s)
    Vec2 velocity{0, 0};             // the material's at the contact in the last substep (m/s)
    Vec2 ramp{0, 0};                 // its grid's change of velocity over the step, no contact
    Vec2 impulse{0, 0};              // on the point so far (N s/m)
    detail::ContactStencil stencil;  // how its force reaches the grid
    bool sph = false;                // an SPH particle: moved by its own mass
    bool apart = false;              // too far from the body to touch within the step
  };
  void beginSubcycle(CouplingStep& s);
  ContactSearch search_;
  std::vector<Substepping> substepping_;
  // Per grid node, the springs' impulses so far in this step (N s/m): zero outside the step's
  // contact stencils, and zero again once the grid has them.
  std::vector<Real> impulse_x_, impulse_y_;
};

}  // namespace mpm_sdem
