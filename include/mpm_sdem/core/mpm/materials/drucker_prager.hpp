/// \file
/// The Drucker-Prager material (seed 000 eq. 31-35, Fig. 2): elastic-perfectly plastic with a
/// tension cut-off, its cone inscribed to Mohr-Coulomb in plane strain.
#pragma once

#include "mpm_sdem/core/mpm/stress.hpp"

namespace mpm_sdem {

/// The steepest friction angle a Drucker-Prager material may ask for (rad). Eq. 35's cone matches
/// Mohr-Coulomb in plane strain only when the plastic flow is associated; with less dilation the
/// out-of-plane stress settles where the plastic flow has no out-of-plane part, and the in-plane
/// angle the flowing material holds is asin(q_phi) (flowingFrictionAngle). q_phi never exceeds
/// sqrt(3)/2, so no material flows at an angle above 60 deg: friction_angle 80 deg flowed like
/// 58.9 deg. Angles up to this limit are accepted and their flowing angle documented.
constexpr Real kMaxFrictionAngle = M_PI / 3;
/// The in-plane friction angle of the flowing material without dilation: asin(q_phi(phi)), e.g.
/// 28.7 deg for 30, 40.9 for 45, 50.8 for 60 (rad in, rad out).
Real flowingFrictionAngle(Real friction_angle);

/// Which surface a stress update returned to, if any.
enum class PlasticMode { kElastic, kShear, kTension };

/// What a stress update did: stayed elastic, or returned to the shear or tension surface.
struct PlasticReturn {
  PlasticMode mode = PlasticMode::kElastic;  ///< elastic, or the surface returned to
  Real multiplier = 0;  ///< shear: Delta lambda of the return (dimensionless strain increment)
};

/// Drucker-Prager with tension cut-off (seed 000 eq. 31-35, Fig. 2), return mapping of the trial
/// stress in the (sigma_m, tau) plane. Shear failure returns along the non-associated flow
/// potential g = tau + q_psi sigma_m: tau drops by G dl and sigma_m by K q_psi dl, with
/// dl = f^s / (G + K q_phi q_psi), so the plastic volume strain is q_psi dl (dilation angle).
/// Beyond the cut-off the line h = 0 through the corner (sigma^t, tau^P) with slope
/// alpha^P = sqrt(1 + q_phi^2) - q_phi splits shear returns from tensile returns; a tensile return
/// sets sigma_m = sigma^t and caps tau at the corner.
inline PlasticReturn druckerPragerReturn(const MaterialParams& m, Stress& s) {
  PlasticReturn out;
  const Real sm = meanStress(s);
  const Real tau = equivalentShear(s);
  const Real fs = tau + m.q_phi * sm - m.k_phi;  // eq. 31
  const Real ft = sm - m.tension;                // eq. 32
  if (fs <= 0 && ft <= 0) return out;

  const Real tau_corner = m.tau_corner;
  const bool shear = ft <= 0 || tau - tau_corner - m.alpha_p * (sm - m.tension) > 0;
  Real sm_new, tau_new;
  if (shear) {
    out.mode = PlasticMode::kShear;
    out.multiplier = fs * m.inv_return_modulus;
    sm_new = sm - m.bulk * m.q_psi * out.multiplier;
    tau_new = m.k_phi - m.q_phi * sm_new;
    if (sm_new > m.tension) {  // the return overshot the cut-off: land on the corner
      sm_new = m.tension;
      tau_new = tau_corner;
    }
  } else {
    out.mode = PlasticMode::kTension;
    sm_new = m.tension;
    tau_new = tau < tau_corner ? tau : tau_corner;  // fmin's result, NaN included, without a call
  }
  const Real scale = tau > 0 ? (tau_new > 0 ? tau_new : Real(0)) / tau : Real(0);
  s.xx = (s.xx - sm) * scale + sm_new;
  s.yy = (s.yy - sm) * scale + sm_new;
  s.zz = (s.zz - sm) * scale + sm_new;
  s.xy *= scale;
  return out;
}

/// A Drucker-Prager point's stress after dt: the Jaumann-rate trial stress (eq. 21-25), then the
/// return to the cone or the cut-off.
inline Stress druckerPragerUpdate(const MaterialParams& m, const Stress& s,
                                  const VelocityGradient& L, Real /*J*/, Real dt) {
  Stress r = jaumannElasticUpdate(m, s, L, dt);
  druckerPragerReturn(m, r);
  return r;
}

/// Its row of the table of models: friction and dilation angles, cohesion, tension cut-off and
/// separation volume ratio; its constants of eq. 35 and of the return.
const MaterialTraits& druckerPragerModel();

}  // namespace mpm_sdem
