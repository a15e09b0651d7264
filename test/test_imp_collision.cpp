// Seed 000 sec. 5.1.1 (Table 1 in SI units): an elastic MPM disk at 2 m/s hits an equal, free
// rigid disk; no gravity. Asserted for the seed's soft and hard disks: total momentum conserved
// within 0.5% (the contact forces on points and block are equal and opposite each step; what
// remains is the half-step staggering of the velocities) and kinetic energy never above its
// initial value (the coupling creates no energy). In the near-rigid limit (moduli x100) an
// undamped head-on collision of equal masses exchanges the velocities: the block must leave with
// at least 95% of the energy (measured 96.5%; the rest is the APIC transfer's dissipation of the
// impulsive load, 3% with FLIP as well, 14% with PIC).
//
// Not yet reached, so not asserted: the seed's 99.2% (hard) and 92.16% (soft) shares. Measured
// here 77% and 71% at 4 mm (APIC, USF), 87-88% (hard) under refinement to 1.5 mm; at the
// seed's own resolution (3 mm, 5000 points) 80%. The contact lasts about 1 ms, less than the
// disk's lowest vibration period (about 3 ms), so the disk keeps vibration energy that the
// transfers then dissipate; see the issue notes.
//
// CI resolution: 4 mm cells with 2x2 points (the seed: 3 mm, 5000 points); r_p = 1 mm,
// V_d = 2 mm and k_n = 6e6 N/cm as in Table 1. The IMP spring on a 8 g point then limits the
// step to 2.3 microseconds (eq. 51 with the point's mass).
#include <gtest/gtest.h>

#include <cstdio>

#include "block_helpers.hpp"

using namespace mpm_sdem;

namespace {

struct Outcome {
  Real momentum_error;  // max over steps |P(t) - P(0)| / |P(0)|
  Real energy_peak;     // max KE(t) / KE(0)
  Real block_share;     // KE of the block at the end / KE(0)
};

Outcome collide(Real bulk, Real shear) {
  const Real R = 0.02, rho = 2000;
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.2, 0.08), 0.004);
  def.solver.gravity = Vec2(0, 0);
  def.solver.kernel = KernelType::kGimp;  // seed 000 uses GIMP for the elastic disks
  def.solver.transfer = TransferScheme::kApic;
  MaterialDef m;
  m.name = "disk";
  m.density = rho;
  m.bulk_modulus = bulk;
  m.shear_modulus = shear;
  def.materials.push_back(m);
  BodyDef disk = test::disk(Vec2(0.05, 0.04), R, 2);
  disk.velocity = Vec2(2, 0);
  def.bodies.push_back(disk);
  BlockDef block =
      test::diskBlock("block", Vec2(0.05 + 2 * R + 0.004, 0.04), R, BodyType::kDynamic, rho);
  block.restitution = 1;  // Table 1 has no contact damping
  block.friction = 0.1;
  def.blocks.push_back(block);
  def.coupling.normal_stiffness = 6e8;
  def.coupling.tangential_stiffness = 3e7;
  def.coupling.contact_radius = 0.001;
  def.coupling.verlet_distance = 0.002;
  World w(def);
  const Diagnostics d0 = measure(w);
  Outcome out{0, 0, 0};
  while (w.time() < 0.012) {
    w.step(w.chooseTimeStep().dt);
    const Diagnostics d = measure(w);
    out.momentum_error =
        std::max(out.momentum_error, (d.momentum - d0.momentum).norm() / d0.momentum.norm());
    out.energy_peak = std::max(out.energy_peak, d.kinetic / d0.kinetic);
  }
  out.block_share = measure(w).block_kinetic / d0.kinetic;
  return out;
}

}  // namespace

TEST(ImpCollision, HardDisk) {
  const Outcome o = collide(5e6, 3.7e6);
  EXPECT_LT(o.momentum_error, 0.005);
  EXPECT_LE(o.energy_peak, 1.0);
  std::printf("hard disk: block share %.4f\n", o.block_share);
}

TEST(ImpCollision, SoftDisk) {
  const Outcome o = collide(5e5, 3.7e5);
  EXPECT_LT(o.momentum_error, 0.005);
  EXPECT_LE(o.energy_peak, 1.0);
  std::printf("soft disk: block share %.4f\n", o.block_share);
}

TEST(ImpCollision, RigidLimitExchangesVelocities) {
  const Outcome o = collide(5e8, 3.7e8);
  EXPECT_LT(o.momentum_error, 0.005);
  EXPECT_LE(o.energy_peak, 1.0);
  EXPECT_GE(o.block_share, 0.95);
}
