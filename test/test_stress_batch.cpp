// Issue 42: the stress update across points in SIMD lanes (updateStressBatch) against the
// point-by-point one (updatePointStress, the definition of constitutive.hpp), for states drawn
// to reach every branch: elastic, shear and tensile Drucker-Prager returns, the corner, and
// points beyond the separation volume ratio. Every lane must agree with its point to round-off
// (the two may order a fused multiply-add differently): 1e-12 of the state's stress scale in
// double.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "mpm/stress_batch.hpp"
#include "mpm/transfer.hpp"

namespace mpm_sdem {
namespace {

MaterialDef solid(MaterialModel model) {
  MaterialDef d;
  d.model = model;
  d.density = 1800;
  d.bulk_modulus = 2e6;
  d.shear_modulus = 1e6;
  d.friction_angle = 30 * M_PI / 180;
  d.dilation_angle = 5 * M_PI / 180;
  d.cohesion = 200;
  d.tensile_strength = 50;
  d.separation_volume_ratio = 1.05;
  return d;
}

// How many of the drawn points took each path of the point-by-point update: the comparison
// proves only what the states reach.
struct Paths {
  int elastic = 0, shear = 0, tension = 0;  // Drucker-Prager returns
  int tension_below_corner = 0;             // tensile returns that keep their shear stress
  int loose = 0;                            // beyond the separation volume ratio: no stress
};

// Every lane of updateStressBatch against updatePointStress over 1,000 random points.
Paths compare(MaterialModel model, Real dt) {
  const MaterialParams m = makeMaterialParams(solid(model));
  std::mt19937 rng(42);
  std::uniform_real_distribution<Real> u(-1, 1);
  const Real stress_scale = 2e3, rate = 50;  // Pa, 1/s: strain increments of order 1e-3
  const int n = 1000;
  Particles P;
  P.resize(n);
  detail::StressBatch b;
  Paths paths;
  Real worst_stress = 0, worst_j = 0;
  for (int start = 0; start < n; start += detail::StressBatch::kSize) {
    b.count = std::min(detail::StressBatch::kSize, n - start);
    for (int k = 0; k < b.count; ++k) {
      const int p = start + k;
      // Mostly compressive states around the cone, some in tension; one in four with a small
      // deviator and a slow deformation, so that tensile returns below the corner occur too.
      const Real small = p % 4 == 0 ? Real(0.01) : Real(1);
      const Real mean = -stress_scale * (Real(0.3) + u(rng)), deviator = small * stress_scale;
      P.lxx[p] = b.lxx[k] = small * rate * u(rng);
      P.lxy[p] = b.lxy[k] = small * rate * u(rng);
      P.lyx[p] = b.lyx[k] = small * rate * u(rng);
      P.lyy[p] = b.lyy[k] = small * rate * u(rng);
      P.sxx[p] = b.sxx[k] = mean + deviator * u(rng);
      P.syy[p] = b.syy[k] = mean + deviator * u(rng);
      P.szz[p] = b.szz[k] = mean + deviator * u(rng);
      P.sxy[p] = b.sxy[k] = deviator * u(rng);
      // Compressed and expanded points, some beyond the separation volume ratio.
      P.J[p] = b.J[k] = 1 + Real(0.06) * u(rng);
    }
    detail::updateStressBatch(m, b, dt);
    for (int k = 0; k < b.count; ++k) {
      const int p = start + k;
      const VelocityGradient L{P.lxx[p], P.lxy[p], P.lyx[p], P.lyy[p]};
      Stress trial = jaumannElasticUpdate(m, {P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]}, L, dt);
      const Real trial_tau = equivalentShear(trial);
      detail::updatePointStress(m, P, p, dt);
      if (model == MaterialModel::kDruckerPrager) {
        const PlasticMode mode = druckerPragerReturn(m, trial).mode;
        paths.elastic += mode == PlasticMode::kElastic;
        paths.shear += mode == PlasticMode::kShear;
        paths.tension += mode == PlasticMode::kTension;
        paths.tension_below_corner += mode == PlasticMode::kTension && trial_tau < m.tau_corner;
      }
      paths.loose += P.J[p] > m.separation;
      for (const auto& [a, c] : {std::pair{P.sxx[p], b.sxx[k]}, std::pair{P.syy[p], b.syy[k]},
                                 std::pair{P.sxy[p], b.sxy[k]}, std::pair{P.szz[p], b.szz[k]}})
        worst_stress = std::max(worst_stress, std::abs(a - c) / stress_scale);
      worst_j = std::max(worst_j, std::abs(P.J[p] - b.J[k]));
    }
  }
  EXPECT_LT(worst_stress, 1e-12);
  EXPECT_LT(worst_j, 1e-14);
  return paths;
}

TEST(StressBatch, LinearElasticLanesMatchThePointByPointUpdate) {
  compare(MaterialModel::kLinearElastic, 1e-4);
}

TEST(StressBatch, DruckerPragerLanesMatchThePointByPointUpdateOnEveryReturn) {
  const Paths paths = compare(MaterialModel::kDruckerPrager, 1e-4);
  EXPECT_GT(paths.elastic, 50);
  EXPECT_GT(paths.shear, 50);
  EXPECT_GT(paths.tension, 50);
  EXPECT_GT(paths.tension_below_corner, 20);
  EXPECT_GT(paths.loose, 20);
}

}  // namespace
}  // namespace mpm_sdem
