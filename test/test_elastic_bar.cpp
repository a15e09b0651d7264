// Test 4: one-dimensional elastic waves. A strip between slip walls with nu = 0 is a 1D bar with
// wave speed c = sqrt(E / rho).
//  - Fixed-free bar in its first mode, v = v0 sin(pi x / 2L): the period is 4L/c within 2% (the
//    dispersion error of this resolution, 50 cells along the bar, is well below 1%).
//  - Seed 001 sec. 5.1 reversibility: v = 0.01 c sin(10 pi x) on a fixed-fixed copper bar; after
//    500 steps the velocities are reversed and 500 more steps return -v(x, 0) within 1% of the
//    amplitude. This holds for FLIP (alpha = 0) with update-stress-first, the combination seed 000
//    sec. 2.2 singles out for energy conservation (measured: 0.09%, the energy 1.000 of its
//    start). APIC is dissipative by design (it drops sub-grid velocity modes: 18% of the energy
//    over this run at 20 cells per wavelength), so it cannot retrace; it is held instead to never
//    gaining energy.
//  - Seed 001 sec. 5.2: the free copper bar under a 1 MPa traction on both ends at the seed's
//    resolution (10 cells, 2 points per cell along it) comes to the static strain -sigma / E =
//    -7.8125e-6 within 0.1% (measured: 1e-5; the time average still holds some of the ringing).
//    With the traction on the end points' centres instead of the faces it was 7.8% off.
#include <gtest/gtest.h>

#include <vector>

#include "helpers.hpp"

using namespace mpm_sdem;

namespace {

WorldDef strip(Real length, Real height, Real h, const MaterialDef& m, int ppc) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(length * 1.2, height), h);
  def.solver.gravity = Vec2(0, 0);
  def.domain.left.type = WallType::kSticky;
  def.materials.push_back(m);
  def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(length, height), ppc));
  return def;
}

Real momentumX(const World& w) {
  return measure(w).momentum.x();
}

Real measuredPeriod(const WorldDef& def, Real L, Real v0) {
  World w(def);
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) P.vx[p] = v0 * std::sin(M_PI * P.x[p] / (2 * L));
  // The total momentum goes as cos(2 pi t / T): find two successive zero crossings.
  std::vector<Real> crossings;
  Real prev = momentumX(w), prev_t = 0;
  while (crossings.size() < 2 && w.time() < 10 * L) {
    stepStable(w);
    // Velocities are staggered half a step behind the positions.
    const Real t = w.time() - 0.5 * w.chooseTimeStep().dt;
    const Real m = momentumX(w);
    if ((prev > 0) != (m > 0)) crossings.push_back(prev_t + (t - prev_t) * prev / (prev - m));
    prev = m;
    prev_t = t;
  }
  EXPECT_EQ(crossings.size(), 2u);
  return 2 * (crossings[1] - crossings[0]);
}

}  // namespace

TEST(ElasticBar, FixedFreePeriodApic) {
  const Real L = 1.0, E = 1e7, rho = 1000;
  WorldDef def = strip(L, 0.04, 0.02, test::elastic(rho, E, 0.0), 2);
  const Real T = measuredPeriod(def, L, 0.01);
  const Real expected = 4 * L / std::sqrt(E / rho);
  EXPECT_NEAR(T / expected, 1.0, 0.02) << "T = " << T << " s, 4L/c = " << expected << " s";
}

TEST(ElasticBar, FixedFreePeriodGimpFlipUsl) {
  const Real L = 1.0, E = 1e7, rho = 1000;
  WorldDef def = strip(L, 0.04, 0.02, test::elastic(rho, E, 0.0), 2);
  def.solver.kernel = KernelType::kGimp;
  def.solver.transfer = TransferScheme::kFlip;
  def.solver.pic_fraction = 0;
  def.solver.stress_update = StressUpdate::kUsl;
  const Real T = measuredPeriod(def, L, 0.01);
  const Real expected = 4 * L / std::sqrt(E / rho);
  EXPECT_NEAR(T / expected, 1.0, 0.02) << "T = " << T << " s, 4L/c = " << expected << " s";
}

TEST(ElasticBar, Seed001ReversibilityFlipUsf) {
  const cases::Reversal r = cases::reversal(TransferScheme::kFlip, StressUpdate::kUsf);
  EXPECT_LT(r.velocity_error, 0.01);
  EXPECT_NEAR(r.energy_ratio, 1.0, 0.01);
}

TEST(ElasticBar, ApicNeverGainsEnergy) {
  for (StressUpdate u : {StressUpdate::kUsf, StressUpdate::kUsl}) {
    EXPECT_LT(cases::reversal(TransferScheme::kApic, u).energy_ratio, 1.0);
  }
}

TEST(ElasticBar, Seed001StressBoundaryStaticStrain) {
  const cases::BarStrain b = cases::stressBar(0.1, 2, 1e6, 20, 40);
  EXPECT_NEAR(b.mean_strain / -7.8125e-6, 1.0, 1e-3) << "strain " << b.mean_strain;
}
