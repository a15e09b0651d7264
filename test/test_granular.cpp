// Issue 41: the mu(I) granular material (granularReturn, Jop, Forterre & Pouliquen 2006; the
// dense and separated states of Dunatunga & Kamrin 2015), point by point.
//  - Steady simple shear at a held pressure: the shear stress settles at mu(I) p with I from the
//    imposed rate, for inertial numbers from 1e-3 to 10, at steps from 1e-6 to 1e-2 s (the
//    closed-form return has no step bound of its own).
//  - A point looser than the critical packing carries no stress; packed again, its pressure is
//    K ln(1 / J) whatever happened while it was loose.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "mpm_sdem/core/mpm/constitutive.hpp"

using namespace mpm_sdem;

namespace {

// Glass beads (Jop et al. 2006): mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I_0 = 0.279,
// d = 0.5 mm, phi = 0.6 at 1500 kg/m^3 bulk; stiffness K = 1 MPa, G = 0.5 MPa.
MaterialParams glassBeads() {
  MaterialDef d;
  d.model = MaterialModel::kGranular;
  d.density = 1500;
  d.bulk_modulus = 1e6;
  d.shear_modulus = 5e5;
  d.mu_s = std::tan(20.9 * M_PI / 180);
  d.mu_2 = std::tan(32.76 * M_PI / 180);
  d.inertial_i0 = 0.279;
  d.grain_diameter = 5e-4;
  d.solid_fraction = 0.6;
  return makeMaterialParams(d);
}

// Simple shear at the engineering rate gamma_dot (L_xy = gamma_dot) of a point held at volume
// ratio J, from rest, for n steps of dt: the shear stress sqrt(J2) it ends with.
Real shearStress(const MaterialParams& m, Real J, Real gamma_dot, Real dt, int n) {
  Stress s;
  const VelocityGradient L{0, gamma_dot, 0, 0};
  for (int k = 0; k < n; ++k) {
    s = jaumannElasticUpdate(m, s, L, dt);
    granularReturn(m, s, J, dt);
  }
  return equivalentShear(s);
}

}  // namespace

// The shear rate is imposed and the pressure held (J fixed), so the steady shear stress must be
// mu(I) p with I = gamma_dot d / sqrt(p / rho_s): the return solves that relation in closed form
// at every step. Tolerance 1e-5 relative: the Jaumann spin tilts the deviator off the shear
// direction by about mu p / G (1e-3 rad here), so the plastic rate falls short of gamma_dot by
// its cosine's 1e-6. Steps up to dt gamma_dot = 0.05, what the CFL bound allows a point (a
// faster shear would cross a cell per step).
TEST(Granular, SimpleShearSettlesAtMuOfI) {
  const MaterialParams m = glassBeads();
  const Real J = std::exp(-1e3 / m.bulk);  // p = 1 kPa
  const Real p = 1e3, rho_s = 1500 / 0.6;
  int cases = 0;
  for (const Real I : {1e-3, 1e-2, 0.1, 0.279, 1.0, 10.0}) {
    const Real gamma_dot = I * std::sqrt(p / rho_s) / 5e-4;
    for (const Real dt : {1e-6, 1e-4, 1e-2}) {
      // Enough steps to load elastically to mu_2 p and then some: G gamma_dot t >> mu_2 p.
      const int n = static_cast<int>(std::ceil(20 * 0.7 * p / (m.shear * gamma_dot * dt))) + 20;
      if (n > 2000000 || gamma_dot * dt > 0.05) continue;
      const Real tau = shearStress(m, J, gamma_dot, dt, n);
      SCOPED_TRACE("I " + std::to_string(I) + ", dt " + std::to_string(dt));
      // The rate the return sees is the plastic one, which equals gamma_dot once the elastic
      // strain is steady.
      EXPECT_NEAR(tau / p, muOfI(m, I), 1e-5 * muOfI(m, I));
      ++cases;
    }
  }
  EXPECT_EQ(cases, 11) << "every I with at least one step";
}

// mu(I) itself against the closed form at its landmarks: mu_s at I -> 0, the mean of mu_s and
// mu_2 at I = I_0, mu_2 as I grows.
TEST(Granular, MuOfIHasItsLandmarks) {
  const MaterialParams m = glassBeads();
  EXPECT_NEAR(muOfI(m, 0), std::tan(20.9 * M_PI / 180), 1e-15);
  EXPECT_NEAR(muOfI(m, 0.279), 0.5 * (std::tan(20.9 * M_PI / 180) + std::tan(32.76 * M_PI / 180)),
              1e-15);
  EXPECT_NEAR(muOfI(m, 1e12), std::tan(32.76 * M_PI / 180), 1e-9);
}

// Below mu_s p nothing flows: a small shear strain is carried elastically (tau = G gamma).
TEST(Granular, BelowTheStaticFrictionThePointIsElastic) {
  const MaterialParams m = glassBeads();
  const Real J = std::exp(-1e3 / m.bulk);
  const Real tau = shearStress(m, J, 1.0, 1e-4, 1);  // gamma = 1e-4: G gamma = 50 Pa < 382 Pa
  EXPECT_NEAR(tau, m.shear * 1e-4, 1e-9);
}

// Looser than the critical packing (J >= 1) a point has separated: no stress at all, whatever
// its trial stress. Packed again (J < 1) its pressure is K ln(1 / J) exactly: it follows J, so
// nothing accumulated while loose or during the flow can leave it behind.
TEST(Granular, SeparatedPointsCarryNoStressAndRepackToTheirPressure) {
  const MaterialParams m = glassBeads();
  Stress s{-500, -800, 300, -600};
  granularReturn(m, s, 1.2, 1e-4);
  EXPECT_EQ(s.xx, 0);
  EXPECT_EQ(s.yy, 0);
  EXPECT_EQ(s.xy, 0);
  EXPECT_EQ(s.zz, 0);
  granularReturn(m, s, 1.0, 1e-4);  // exactly at the critical packing: still no contact
  EXPECT_EQ(pressure(s), 0);
  const Real J = 0.995;
  granularReturn(m, s, J, 1e-4);
  EXPECT_NEAR(pressure(s), -m.bulk * std::log(J), 1e-9);
  EXPECT_EQ(squaredWaveSpeed(m, 1.01), 0) << "a separated point sets no wave-speed limit";
  EXPECT_GT(squaredWaveSpeed(m, 0.99), 0);
}
