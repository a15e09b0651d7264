#include "mpm_sdem/core/mpm/materials/drucker_prager.hpp"

#include <cmath>
#include <limits>

namespace mpm_sdem {

namespace {

// Seed 000 eq. 35: the Drucker-Prager cone inscribed to Mohr-Coulomb in plane strain.
Real coneSlope(Real angle) {
  const Real t = std::tan(angle);
  return 3 * t / std::sqrt(9 + 12 * t * t);
}

constexpr Real kDegree = M_PI / 180;

Problem druckerPragerProblem(const MaterialDef& d) {
  if (!(d.dilation_angle >= 0 && d.dilation_angle <= d.friction_angle))
    return {"dilation_angle",
            "must be in [0, friction_angle] deg, got " + limits::shown(d.dilation_angle / kDegree)};
  if (d.separation_volume_ratio != 0 && !(d.separation_volume_ratio > 1))
    return {"separation_volume_ratio",
            "must be > 1 (a volume ratio V / V0 looser than the initial packing) or 0 for off, "
            "got " +
                limits::shown(d.separation_volume_ratio)};
  return {};
}

void druckerPragerConstants(const MaterialDef& def, MaterialParams& p) {
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

}  // namespace

Real flowingFrictionAngle(Real friction_angle) {
  return std::asin(coneSlope(friction_angle));
}

const MaterialTraits& druckerPragerModel() {
  static const MaterialTraits traits{
      MaterialModel::kDruckerPrager,
      "drucker_prager",
      MaterialStiffness::kModuli,
      {{"friction_angle",
        &MaterialDef::friction_angle,
        {0, kMaxFrictionAngle / kDegree, "deg"},
        true,
        0,
        kDegree,
        "the plane-strain Drucker-Prager cone (seed 000 eq. 35) holds no flowing slope steeper "
        "than 60 deg (docs/scene_reference.md)"},
       {"dilation_angle", &MaterialDef::dilation_angle, limits::anyIn("deg"), false, 0, kDegree},
       {"cohesion", &MaterialDef::cohesion, limits::kStrength},
       {"tensile_strength", &MaterialDef::tensile_strength, limits::kStrength},
       {"separation_volume_ratio", &MaterialDef::separation_volume_ratio,
        limits::anyIn("(dimensionless)")}},
      druckerPragerProblem,
      druckerPragerConstants,
      /*batches_stress=*/true};
  return traits;
}

}  // namespace mpm_sdem
