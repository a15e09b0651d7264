// The weakly compressible fluid (issue 18; seed 002 sec. 4.3-4.4 model water this way):
//  - Tait's pressure and its stored energy against their closed forms, the tension cut-off.
//  - Hydrostatics: a water column at rest carries p = rho g d, time-averaged over its acoustic
//    ringing, and the bottom carries the column's weight.
//  - Viscosity: a viscous column falling between two sticky walls follows the start-up of plane
//    Poiseuille flow, converging under refinement.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

MaterialDef water(Real sound_speed, Real viscosity = 0) {
  return test::fluid(1000, sound_speed, viscosity);
}

}  // namespace

// p(J) and the energy it stores: a 1% compression of water at c0 = 1480 m/s is
// (K / 7)(0.99^-7 - 1) = 22.4 MPa, 4.1% stiffer than linear; the energy is the integral of p over
// the volume change, checked against a fine midpoint sum; stretched, the pressure stops at the
// cut-off.
TEST(FluidEos, TaitPressureAndItsEnergy) {
  MaterialDef def = water(1480);
  def.tensile_strength = 6000;
  const MaterialParams m = makeMaterialParams(def);
  const Real K = def.bulk_modulus;
  EXPECT_NEAR(taitPressure(m, 0.99), K / 7 * (std::pow(0.99, -7) - 1), 1e-6);
  EXPECT_NEAR(taitPressure(m, 0.99) / (K * 0.01), 1.04123, 1e-5);  // 4% stiffer than linear
  EXPECT_EQ(taitPressure(m, 1.01), -6000);                         // cut off
  const Real J = 0.98;
  Real work = 0;  // int_J^1 p dJ' per reference volume
  const int n = 100000;
  for (int i = 0; i < n; ++i) work += taitPressure(m, J + (1 - J) * (i + 0.5) / n) * (1 - J) / n;
  const VelocityGradient rest;
  const Stress s = fluidStress(m, J, rest);
  EXPECT_NEAR(elasticEnergyDensity(m, s) * J / work, 1, 1e-6);
  // Shear flow: sigma_xy = eta (dv_x/dy), no pressure from it.
  def.viscosity = 2;
  const MaterialParams mv = makeMaterialParams(def);
  VelocityGradient L;
  L.xy = 3;
  const Stress shear = fluidStress(mv, 1, L);
  EXPECT_DOUBLE_EQ(shear.xy, 6);
  EXPECT_DOUBLE_EQ(meanStress(shear), 0);
}

// A 0.2 m column of water (c0 = 20 m/s: Mach well under 0.1, the column compressed by
// rho g H / K = 0.5%) released without its initial pressure rings at the acoustic period 4H/c0 =
// 0.04 s about the hydrostatic state. Averaged over 0.1-0.3 s, the pressure at 1/4, 1/2 and 3/4
// of the depth is rho g d within 3% (points near the free surface sit in partly filled cells;
// measured 1.2%, 1.3%, 0.7% low: the surface sinks by about a millimetre as the column settles,
// of which rho g H^2 / 2K alone is 0.5 mm) and the mean pressure of the column is rho g H / 2,
// its weight on the bottom, within 2%.
TEST(FluidHydrostatics, AColumnAtRestCarriesItsWeight) {
  WorldDef w;
  const Real H = 0.2, h = 0.01;
  w.domain.min = Vec2(0, 0);
  w.domain.max = Vec2(0.2, 0.3);
  w.cell_size = h;
  w.materials = {water(20, 0.01)};
  w.bodies = {test::rectangle(Vec2(0, 0), Vec2(0.2, H), 2)};
  World world(w);
  const Particles& P = world.particles();
  const Real rho_g = 1000 * 9.81;
  Real band[3] = {0, 0, 0}, count[3] = {0, 0, 0}, mean = 0, samples = 0, mach = 0;
  while (world.time() < 0.3) {
    stepStable(world);
    mach = std::fmax(mach, measure(world).max_mach);
    if (world.time() < 0.1) continue;
    Real column = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Real pressure = -(P.sxx[p] + P.syy[p] + P.szz[p]) / 3;
      column += pressure;
      for (int k = 0; k < 3; ++k) {
        if (std::abs(P.y[p] - H * (1 - 0.25 * (k + 1))) < 0.5 * h) {
          band[k] += pressure;
          count[k] += 1;
        }
      }
    }
    mean += column / P.size();
    samples += 1;
  }
  std::printf("max Mach %.3f\n", mach);
  EXPECT_LT(mach, 0.1);
  for (int k = 0; k < 3; ++k) {
    const Real depth = H * 0.25 * (k + 1);
    std::printf("depth %.3f m: %.1f Pa against %.1f\n", depth, band[k] / count[k], rho_g * depth);
    EXPECT_NEAR(band[k] / count[k] / (rho_g * depth), 1, 0.03) << "depth " << depth;
  }
  EXPECT_NEAR(mean / samples / (rho_g * H / 2), 1, 0.02);
}

// Plane Poiseuille flow without a periodic domain: a column of viscous fluid falls between
// sticky walls W apart; its middle reaches v(x) = -g x (W - x) / (2 nu).
struct Poiseuille {
  Real centre = 0;  // measured centre speed over g W^2 / (8 nu)
  Real worst = 0;   // largest |v - exact| over the centre speed
  StepLimit limit = StepLimit::kCfl;
};
Poiseuille poiseuille(Real h, Real nu, Real sound_speed, Real t_end) {
  WorldDef w;
  const Real W = 0.05;
  w.domain.min = Vec2(0, 0);
  w.domain.max = Vec2(W, 0.3);
  w.domain.left.type = w.domain.right.type = WallType::kSticky;
  w.cell_size = h;
  w.materials = {water(sound_speed, 1000 * nu)};
  w.domain.max = Vec2(W, 0.4);
  w.bodies = {test::rectangle(Vec2(0, 0.15), Vec2(W, 0.35), 2)};
  World world(w);
  Poiseuille r;
  r.limit = world.chooseTimeStep().limit;
  runUntil(world, t_end);
  const Particles& P = world.particles();
  const Real centre = 9.81 * W * W / (8 * nu);
  Real top = 0, sum = 0;
  int n = 0;
  for (std::size_t p = 0; p < P.size(); ++p) top = std::fmax(top, P.y[p]);
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.y[p] < top - 0.14 || P.y[p] > top - 0.06) continue;  // the middle of the column
    const Real x = P.x[p];
    // Start-up from rest: the steady profile less its sine series, each mode decaying at
    // exp(-n^2 pi^2 nu t / W^2).
    Real exact = 9.81 * x * (W - x) / (2 * nu);
    for (int k = 1; k < 40; k += 2)
      exact -= 4 * 9.81 * W * W / (nu * k * k * k * M_PI * M_PI * M_PI) *
               std::sin(k * M_PI * x / W) * std::exp(-k * k * M_PI * M_PI * nu * t_end / (W * W));
    r.worst = std::fmax(r.worst, std::abs(P.vy[p] + exact) / centre);
    if (std::abs(x - W / 2) < h) {
      sum -= P.vy[p];
      ++n;
    }
  }
  Real exact_centre = centre;
  for (int k = 1; k < 40; k += 2)
    exact_centre -= 4 * 9.81 * W * W / (nu * k * k * k * M_PI * M_PI * M_PI) *
                    std::sin(k * M_PI / 2) * std::exp(-k * k * M_PI * M_PI * nu * t_end / (W * W));
  r.centre = sum / n / exact_centre;
  return r;
}

// nu = 0.01 m^2/s between walls W = 5 cm apart (time constant W^2 / (pi^2 nu) = 25 ms), c0 = 40
// m/s, at t = 0.05 s against the start-up series. The acoustic step binds, so the transfers' loss
// of the profile's curvature (APIC keeps affine fields only) costs O(h^2) a step over O(1/h) steps:
// first order. Measured at h = 5, 2.5, 1.25 mm: centre speed 0.804, 0.975, 1.009 of the series,
// largest deviation 0.159, 0.030, 0.009 of the centre speed. When the viscous bound h^2 / (2 nu)
// sets the step instead, that loss does not shrink with h (docs/limitations.md).
TEST(FluidViscosity, AColumnBetweenStickyWallsConvergesToPoiseuilleStartUp) {
  const Poiseuille coarse = poiseuille(0.0025, 0.01, 40, 0.05);
  const Poiseuille fine = poiseuille(0.00125, 0.01, 40, 0.05);
  std::printf("centre %.4f, %.4f of the series; worst %.4f, %.4f\n", coarse.centre, fine.centre,
              coarse.worst, fine.worst);
  EXPECT_EQ(fine.limit, StepLimit::kCfl);
  EXPECT_NEAR(fine.centre, 1, 0.02);
  EXPECT_LT(fine.worst, 0.02);
  EXPECT_LT(fine.worst, coarse.worst / 2);  // at least first order
}
