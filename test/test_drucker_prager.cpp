// Test 6: Drucker-Prager return mapping at one material point (seed 000 eq. 31-35).
//  - trial stresses outside the cone or beyond the tension cut-off end on the yield surface,
//    |f| <= 1e-8 relative to the stress magnitude (round-off of a closed-form return);
//  - stresses inside are returned bit-for-bit unchanged;
//  - the shear return is non-associated with the dilation angle: the plastic volume strain
//    (-Delta sigma_m / K) equals q_psi times the plastic shear strain (-Delta tau / G).
#include <gtest/gtest.h>

#include <random>

#include "helpers.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"

using namespace mpm_sdem;

namespace {

MaterialParams params(Real phi, Real psi, Real cohesion, Real tension) {
  MaterialDef d = test::druckerPrager(1500, 1e7, 0.3, phi, psi);
  d.cohesion = cohesion;
  d.tensile_strength = tension;
  return makeMaterialParams(d);
}

Real shearYield(const MaterialParams& m, const Stress& s) {
  return equivalentShear(s) + m.q_phi * meanStress(s) - m.k_phi;
}

Real magnitude(const Stress& s) {
  return std::sqrt(s.xx * s.xx + s.yy * s.yy + s.zz * s.zz + 2 * s.xy * s.xy);
}

// Mean stress from tension to deep compression, deviatoric parts over three decades, so that
// elastic states, shear returns and tensile returns are all well represented.
Stress randomStress(std::mt19937& rng) {
  std::uniform_real_distribution<Real> mean(-2e5, 5e4), unit(-1, 1), decade(2, 5);
  const Real m = mean(rng), scale = std::pow(10.0, decade(rng));
  const Real dx = scale * unit(rng), dy = scale * unit(rng), dxy = scale * unit(rng);
  return Stress{m + dx, m + dy, dxy, m - dx - dy};
}

void checkReturns(const MaterialParams& m) {
  std::mt19937 rng(7);
  int outside = 0, inside = 0;
  for (int i = 0; i < 20000; ++i) {
    const Stress trial = randomStress(rng);
    Stress s = trial;
    const PlasticReturn r = druckerPragerReturn(m, s);
    const Real scale = magnitude(trial);
    if (r.mode == PlasticMode::kElastic) {
      ++inside;
      EXPECT_LE(shearYield(m, trial), 0);
      EXPECT_LE(meanStress(trial), m.tension);
      EXPECT_EQ(s.xx, trial.xx);
      EXPECT_EQ(s.yy, trial.yy);
      EXPECT_EQ(s.xy, trial.xy);
      EXPECT_EQ(s.zz, trial.zz);
      continue;
    }
    ++outside;
    // On the surface: on the cone or the cut-off, and outside neither.
    const Real fs = shearYield(m, s), ft = meanStress(s) - m.tension;
    ASSERT_LE(fs, 1e-8 * scale);
    ASSERT_LE(ft, 1e-8 * scale);
    ASSERT_GE(std::max(fs, ft), -1e-8 * scale) << "returned inside the surface";
  }
  EXPECT_GT(outside, 1000);
  EXPECT_GT(inside, 1000);
}

}  // namespace

TEST(DruckerPrager, CohesionlessReturnsToSurface) {
  checkReturns(params(30, 0, 0, 0));
}
TEST(DruckerPrager, CohesiveWithTensionCutOff) {
  checkReturns(params(35, 10, 2e4, 1e4));
}
TEST(DruckerPrager, AssociatedFlow) {
  checkReturns(params(25, 25, 5e3, 0));
}

TEST(DruckerPrager, TensionCutOffIsCappedAtTheApex) {
  // A requested tensile strength beyond the apex k_phi / q_phi is meaningless: capped there.
  const MaterialParams m = params(30, 0, 1e3, 1e9);
  EXPECT_NEAR(m.tension, m.k_phi / m.q_phi, 1e-9 * m.tension);
}

TEST(DruckerPrager, PureTensionReturnsToCutOff) {
  const MaterialParams m = params(30, 0, 2e4, 5e3);
  Stress s{2e4, 2e4, 0, 2e4};  // hydrostatic tension, tau = 0: below h = 0, a tensile return
  const PlasticReturn r = druckerPragerReturn(m, s);
  EXPECT_EQ(r.mode, PlasticMode::kTension);
  EXPECT_NEAR(meanStress(s), 5e3, 1e-9);
  EXPECT_NEAR(equivalentShear(s), 0, 1e-9);
}

TEST(DruckerPrager, PlasticVolumeChangeFollowsDilationAngle) {
  for (Real psi : {0.0, 10.0, 20.0}) {
    const MaterialParams m = params(30, psi, 0, 0);
    // Compressive mean stress with a deviatoric part well above the cone.
    Stress s{-1e5, -3e5, 1e5, -2e5};
    const Stress trial = s;
    ASSERT_GT(shearYield(m, trial), 0);
    const PlasticReturn r = druckerPragerReturn(m, s);
    ASSERT_EQ(r.mode, PlasticMode::kShear);
    const Real plastic_volume = (meanStress(trial) - meanStress(s)) / m.bulk;  // > 0: dilation
    const Real plastic_shear = (equivalentShear(trial) - equivalentShear(s)) / m.shear;
    EXPECT_NEAR(plastic_shear, r.multiplier, 1e-12);
    EXPECT_NEAR(plastic_volume, m.q_psi * plastic_shear, 1e-12) << "psi = " << psi;
    if (psi == 0) {
      EXPECT_EQ(meanStress(trial), meanStress(s));
    }
    // The deviatoric direction is kept (radial return in the deviatoric plane).
    const Real kx = (s.xx - meanStress(s)) / (trial.xx - meanStress(trial));
    EXPECT_NEAR(s.xy / trial.xy, kx, 1e-12);
  }
}

// Plane-strain simple shear at constant volume under 100 kPa without dilation: the flowing point
// settles at the in-plane friction angle asin(q_phi) (Mohr circle radius over centre), which the
// scene reference gives for each friction angle; at the 60 deg limit it is 50.8 deg, and the
// cone's ceiling q_phi = sqrt(3)/2 would be 60 deg (why steeper angles are refused). The
// returns are exact to round-off, so 1e-3 rad allows for the steady state's last oscillation.
TEST(DruckerPrager, PlaneStrainFlowHoldsTheFlowingFrictionAngle) {
  for (Real phi : {30.0, 45.0, 60.0}) {
    const MaterialParams m = params(phi, 0, 0, 0);
    Stress s{-1e5, -1e5, 0, -1e5};
    const VelocityGradient L{0, 1, 0, 0};  // dv_x/dy = 1/s
    for (int i = 0; i < 20000; ++i) {
      s = jaumannElasticUpdate(m, s, L, 1e-5);
      druckerPragerReturn(m, s);
    }
    const Real centre = 0.5 * (s.xx + s.yy);
    const Real radius = std::sqrt(0.25 * (s.xx - s.yy) * (s.xx - s.yy) + s.xy * s.xy);
    EXPECT_NEAR(std::asin(radius / -centre), flowingFrictionAngle(phi * M_PI / 180), 1e-3)
        << "phi " << phi;
  }
  EXPECT_NEAR(flowingFrictionAngle(kMaxFrictionAngle) * 180 / M_PI, 50.77, 0.01);
}
