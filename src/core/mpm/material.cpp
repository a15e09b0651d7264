#include "mpm_sdem/core/mpm/material.hpp"

#include <cmath>
#include <limits>

namespace mpm_sdem {

namespace {
// Seed 000 eq. 35: the Drucker-Prager cone inscribed to Mohr-Coulomb in plane strain.
Real coneSlope(Real angle) {
  const Real t = std::tan(angle);
  return 3 * t / std::sqrt(9 + 12 * t * t);
}
}  // namespace

Real flowingFrictionAngle(Real friction_angle) {
  return std::asin(coneSlope(friction_angle));
}

MaterialParams makeMaterialParams(const MaterialDef& def) {
  MaterialParams p;
  p.model = def.model;
  p.bulk = def.bulk_modulus;
  p.shear = def.shear_modulus;
  p.lame = def.bulk_modulus - Real(2) / 3 * def.shear_modulus;
  p.modulus_over_density = (def.bulk_modulus + Real(4) / 3 * def.shear_modulus) / def.density;
  if (def.separation_volume_ratio > 0) p.separation = def.separation_volume_ratio;
  if (def.model == MaterialModel::kFluid) {
    p.tait_gamma = def.tait_exponent;
    p.viscosity = def.viscosity;
    p.tension = def.tensile_strength;
  }
  if (def.model == MaterialModel::kGranular) {
    p.mu_s = def.mu_s;
    p.mu_span = def.mu_2 - def.mu_s;
    p.i0 = def.inertial_i0;
    p.inertial_scale = def.grain_diameter * std::sqrt(def.density / def.solid_fraction);
    p.separation = 1;  // looser than the critical packing: separated
  }
  if (def.model == MaterialModel::kDruckerPrager) {
    const Real t = std::tan(def.friction_angle);
    p.q_phi = coneSlope(def.friction_angle);
    p.k_phi = 3 * def.cohesion / std::sqrt(9 + 12 * t * t);
    p.q_psi = coneSlope(def.dilation_angle);
    // The tension cut-off cannot lie beyond the apex of the cone, sigma_m = k_phi / q_phi.
    const Real apex = p.q_phi > 0 ? p.k_phi / p.q_phi : std::numeric_limits<Real>::infinity();
    p.tension = std::fmin(def.tensile_strength, apex);
    p.tau_corner = p.k_phi - p.q_phi * p.tension;
    p.alpha_p = std::sqrt(1 + p.q_phi * p.q_phi) - p.q_phi;
    p.inv_return_modulus = 1 / (p.shear + p.bulk * p.q_phi * p.q_psi);
  }
  return p;
}

}  // namespace mpm_sdem
