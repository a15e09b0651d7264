// Seed 000 sec. 5.1.1 (Table 1): an elastic MPM disk at 2 m/s hits an equal, free rigid disk; no
// gravity. Asserted: total momentum conserved within 0.5% (the contact forces on points and block
// are equal and opposite each step; what remains is the half-step staggering of the velocities),
// kinetic energy never above its initial value (the coupling creates no energy), and the block
// leaving with at least 99% of the kinetic energy for the hard disk and 90% for the soft one
// (the seed: 99.2% and 92.16%).
//
// Units of Table 1. The seed works in cgs (speeds in cm/s, g = 100 cm/s^2 in Table 2) and its
// "6e6 N/cm" stiffness is 6e6 dyn/cm = 6e3 N/m: Table 1's dt = 1e-4 s is stable only for an IMP
// spring up to about 2e3 N/m on a 5 mg point (7e4 N/m on its nodal mass), while the literal
// 6e8 N/m would need dt of about 6e-8 s. With the cgs reading (k_t = 3e5 dyn/cm = 3e2 N/m) the
// block's share is 99.989% (hard) and 99.904% (soft) here, 99.940% and 99.071% at the seed's
// resolution. With the literal 6e8 N/m the contact lasts about 1 ms, less than the disk's lowest
// vibration period (about 3 ms): the disk keeps vibration energy the transfers dissipate, and the
// shares drop to 77.2% and 71.2% (80.9% and 73.4% at seed resolution); momentum and energy
// bounds still hold and are asserted below, and the near-rigid limit exchanges 95.4%. The
// seed's soft-disk 92.16% lies between our 6e4 N/m (98.6%) and 6e5 N/m (91.5%) results (3 mm,
// 2x2 points).
//
// CI resolution: 4 mm cells with 2x2 points; with MPM_SDEM_SEED_RESOLUTION=1 the seed's 3 mm cells
// with 6x6 points (5,024 points against its 5,000). r_p = 1 mm and V_d = 2 mm as in Table 1.
#include <gtest/gtest.h>

#include <cstdio>

#include "block_helpers.hpp"
#include "cases.hpp"
#include "mpm_sdem/core/stepper.hpp"

using namespace mpm_sdem;

namespace {

struct Outcome {
  Real momentum_error;  // max over steps |P(t) - P(0)| / |P(0)|
  Real energy_peak;     // max KE(t) / KE(0)
  Real block_share;     // KE of the block at the end / KE(0)
  long steps;
};

// A sum of N ~ 5000 kinetic energies carries a round-off of about N * 2.2e-16 relative (measured
// 4e-16 to 1.3e-15 while the disk flies freely at the seed's resolution).
constexpr Real kRoundOff = 1e-12;

Outcome collide(Real bulk, Real shear, Real kn, Real kt, Real duration,
                ContactIntegration integration = ContactIntegration::kExplicit, Real step_scale = 1,
                TransferScheme transfer = TransferScheme::kApic) {
  cases::DiskCollision c;
  c.bulk_modulus = bulk;
  c.shear_modulus = shear;
  c.normal_stiffness = kn;
  c.tangential_stiffness = kt;
  c.cell_size = test::seedResolution() ? 0.003 : 0.004;
  c.points_per_cell = test::seedResolution() ? 6 : 2;
  WorldDef def = cases::diskCollision(c);
  def.coupling.normal_integration = integration;
  def.solver.transfer = transfer;
  def.time_step.contact_factor *= step_scale;
  def.time_step.cfl *= step_scale;
  World w(def);
  const Diagnostics d0 = measure(w);
  Outcome out{0, 0, 0, 0};
  while (w.time() < duration) {
    stepStable(w);
    const Diagnostics d = measure(w);
    out.momentum_error =
        std::max(out.momentum_error, (d.momentum - d0.momentum).norm() / d0.momentum.norm());
    out.energy_peak = std::max(out.energy_peak, d.kinetic / d0.kinetic);
  }
  out.block_share = measure(w).block_kinetic / d0.kinetic;
  out.steps = w.stepCount();
  return out;
}

}  // namespace

// Asserts the bounds that hold for every case and the block's share; prints what it measured.
void expectExchange(const char* label, const Outcome& o, Real min_share) {
  std::printf("%s: block share %.5f, momentum error %.2e, KE peak - 1 = %.2e, %ld steps\n", label,
              o.block_share, o.momentum_error, o.energy_peak - 1, o.steps);
  EXPECT_LT(o.momentum_error, 0.005);
  EXPECT_LE(o.energy_peak, 1.0 + kRoundOff) << "excess " << o.energy_peak - 1;
  EXPECT_GE(o.block_share, min_share);
}

TEST(ImpCollision, HardDisk) {
  expectExchange(
      "hard", collide(5e6, 3.7e6, test::kSeedNormalStiffness, test::kSeedTangentialStiffness, 0.15),
      0.99);
}

TEST(ImpCollision, SoftDisk) {
  expectExchange(
      "soft", collide(5e5, 3.7e5, test::kSeedNormalStiffness, test::kSeedTangentialStiffness, 0.15),
      0.90);
}

// Issue 40's transfer, ASFLIP, keeps the seed's results and the bounds: measured hard 0.99991,
// soft 0.99938 (APIC 0.99988, 0.99901); with the literal 6e8 N/m 0.858 and 0.834 (APIC 0.767,
// 0.697): the disk's vibration is no longer damped at every transfer, so less of it is lost.
TEST(ImpCollision, AsflipKeepsTheSharesAndCreatesNoEnergy) {
  const auto asflip = [](Real bulk, Real shear) {
    return collide(bulk, shear, test::kSeedNormalStiffness, test::kSeedTangentialStiffness, 0.15,
                   ContactIntegration::kExplicit, 1, TransferScheme::kAsflip);
  };
  expectExchange("ASFLIP, hard", asflip(5e6, 3.7e6), 0.99);
  expectExchange("ASFLIP, soft", asflip(5e5, 3.7e5), 0.90);
}

TEST(ImpCollision, StiffContactConservesMomentumAndCreatesNoEnergy) {
  // No share asserted: with the literal 6e8 N/m the disk keeps vibration energy (see above).
  expectExchange("stiff contact, hard", collide(5e6, 3.7e6, 6e8, 3e7, 0.012), 0.0);
  expectExchange("stiff contact, soft", collide(5e5, 3.7e5, 6e8, 3e7, 0.012), 0.0);
}

TEST(ImpCollision, StiffContactRigidLimitExchangesVelocities) {
  expectExchange("stiff contact, rigid limit", collide(5e8, 3.7e8, 6e8, 3e7, 0.012), 0.95);
}

// The normal springs integrated exactly over the step (coupling.normal_integration: exact).
// At the seed's soft contact the step is the material's either way, and the share is within the
// first-order error of the free-pair impulse (a point held by its disk is not pushed out as a
// free one would be): 0.9955 against the explicit 0.9999, 0.9977 and 0.9988 at half and a
// quarter of the step. With the literal 6e8 N/m the contact no longer sets the step: 1,461
// steps against 6,534 (share 82.8%), momentum and energy bounds as above. (The stiff contact's
// share depends on the step under both integrations, 0.77-0.67 explicit and 0.83-0.73 exact from
// 1 to 0.1 of it: the disk's vibration is damped per transfer, so it is not asserted.)
TEST(ImpCollision, ExactContactTakesTheMaterialsStep) {
  const auto exact = ContactIntegration::kExact;
  expectExchange(
      "exact, hard",
      collide(5e6, 3.7e6, test::kSeedNormalStiffness, test::kSeedTangentialStiffness, 0.15, exact),
      0.99);
  const Outcome stiff = collide(5e6, 3.7e6, 6e8, 3e7, 0.012, exact);
  expectExchange("exact, stiff contact, hard", stiff, 0.0);
  const Outcome explicit_stiff = collide(5e6, 3.7e6, 6e8, 3e7, 0.012);
  EXPECT_LT(4 * stiff.steps, explicit_stiff.steps);
}

// Multi-rate (coupling.normal_integration: subcycled): the step is the disk's own (CFL) and the
// springs and the block take substeps within it. The springs' impulses reach the grid through the
// adjoint of the map that reads the points' velocity, so the bounds above hold as they do for
// the explicit springs. The seed's soft contact (6e3 N/m) does not bound the step even
// explicitly; the literal 6e8 N/m does, and subcycled it leaves the step to the disk. Every step
// and substep at a quarter (step_scale 0.25) moves the hard disk's share by less than 0.5%.
// Momentum: the grid gets the sum of the substeps' impulses and the block minus each, so what
// remains is Box2D's single precision (float epsilon 6e-8 on the block's velocity, summed over
// the block's substeps: measured 3e-7; the explicit springs' 3e-5 is the staggering above).
// Measured shares: hard 99.985%, 99.987% at a quarter of every step; the literal 6e8 N/m 86.4% in
// 716 steps.
TEST(ImpCollision, SubcycledContactTakesTheMaterialsStep) {
  const auto sub = ContactIntegration::kSubcycled;
  const Outcome hard =
      collide(5e6, 3.7e6, test::kSeedNormalStiffness, test::kSeedTangentialStiffness, 0.15, sub);
  expectExchange("subcycled, hard", hard, 0.99);
  EXPECT_LT(hard.momentum_error, 1e-5);
  const Outcome quarter = collide(5e6, 3.7e6, test::kSeedNormalStiffness,
                                  test::kSeedTangentialStiffness, 0.15, sub, 0.25);
  expectExchange("subcycled, hard, quarter step", quarter, 0.99);
  EXPECT_NEAR(hard.block_share, quarter.block_share, 0.005);
  const Outcome stiff = collide(5e6, 3.7e6, 6e8, 3e7, 0.012, sub);
  expectExchange("subcycled, stiff contact, hard", stiff, 0.0);
  const Outcome stiff_quarter = collide(5e6, 3.7e6, 6e8, 3e7, 0.012, sub, 0.25);
  expectExchange("subcycled, stiff contact, hard, quarter step", stiff_quarter, 0.0);
  const Outcome explicit_stiff = collide(5e6, 3.7e6, 6e8, 3e7, 0.012);
  EXPECT_LT(4 * stiff.steps, explicit_stiff.steps);
}
