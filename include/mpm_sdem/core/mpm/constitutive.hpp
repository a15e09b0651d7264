/// \file
/// Constitutive updates as small pure functions of one material point (plane strain, tension
/// positive). The stress keeps its out-of-plane component sigma_zz, which plane strain makes
/// non-zero and which enters the invariants of the Drucker-Prager criterion.
#pragma once

#include <cmath>

#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// A plane-strain Cauchy stress (Pa), tension positive: the in-plane components and sigma_zz.
struct Stress {
  ///@{
  /// Pa
  Real xx = 0, yy = 0, xy = 0, zz = 0;
  ///@}
};

/// L_ij = d v_i / d x_j (1/s).
struct VelocityGradient {
  ///@{
  /// 1/s
  Real xx = 0, xy = 0, yx = 0, yy = 0;
  ///@}
};

/// Hypoelastic update with the Jaumann rate over a time dt (seed 000 eq. 21-25 with C of eq. 36):
/// sigma += dt (C : D + W sigma - sigma W), D and W the symmetric and skew parts of L. Plane
/// strain: D_zz = 0, so sigma_zz changes only through lambda tr(D).
inline Stress jaumannElasticUpdate(const MaterialParams& m, const Stress& s,
                                   const VelocityGradient& L, Real dt) {
  const Real dxx = L.xx * dt, dyy = L.yy * dt, dxy = Real(0.5) * (L.xy + L.yx) * dt;
  const Real w = Real(0.5) * (L.xy - L.yx) * dt;  // W_xy dt
  const Real tr = dxx + dyy;
  Stress r;
  r.xx = s.xx + m.lame * tr + 2 * m.shear * dxx + 2 * w * s.xy;
  r.yy = s.yy + m.lame * tr + 2 * m.shear * dyy - 2 * w * s.xy;
  r.xy = s.xy + 2 * m.shear * dxy + w * (s.yy - s.xx);
  r.zz = s.zz + m.lame * tr;
  return r;
}

/// Stress invariants of seed 000 eq. 33-34: mean stress sigma_m and tau = sqrt(J2).
inline Real meanStress(const Stress& s) {
  return (s.xx + s.yy + s.zz) / 3;
}
/// tau = sqrt(J2) (Pa).
inline Real equivalentShear(const Stress& s) {
  const Real m = meanStress(s);
  const Real ax = s.xx - m, ay = s.yy - m, az = s.zz - m;
  return std::sqrt(Real(0.5) * (ax * ax + ay * ay + az * az) + s.xy * s.xy);
}

/// What the outputs show (the node's clouds, pictures, ParaView files), one definition for all:
/// the pressure -sigma_m (compression positive, Pa) and the von Mises stress sqrt(3 J2) (Pa).
inline Real pressure(const Stress& s) {
  return -meanStress(s);
}
/// The von Mises stress sqrt(3 J2) (Pa).
inline Real vonMises(const Stress& s) {
  return std::sqrt(Real(3)) * equivalentShear(s);
}

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

/// The mu(I) friction coefficient of Jop, Forterre & Pouliquen 2006 at inertial number I.
inline Real muOfI(const MaterialParams& m, Real I) {
  return m.mu_s + m.mu_span * I / (I + m.i0);
}

/// A granular point's stress after the step, from its Jaumann trial stress s and its
/// new volume ratio J (Dunatunga & Kamrin 2015, sec. 2-3, in rate form):
/// - J >= 1, looser than the critical packing: separated, no stress.
/// - Dense: pressure p = K ln(1 / J), from J itself so that it cannot drift; the trial deviator
///   s* with shear stress tau* = sqrt(J2). Below mu_s p the point is elastic. Above, it flows at
///   the plastic shear rate gamma_dot = (tau* - tau) / (G dt) (a shear stress relaxes by G per
///   unit engineering shear strain), with tau = mu(I) p and I = gamma_dot d sqrt(rho_s / p).
///   With x = tau* - tau, a = tau* - mu_s p and c = I_0 G dt sqrt(p) / (d sqrt(rho_s)) this is
///   x^2 + (c - a + (mu_2 - mu_s) p) x - a c = 0, whose non-negative root is taken in closed form:
///   no iteration, and no bound on dt from the rate dependence. The deviator is scaled back
///   radially (isochoric flow, no dilatancy).
inline void granularReturn(const MaterialParams& m, Stress& s, Real J, Real dt) {
  if (!(J < 1)) {
    s = Stress{};
    return;
  }
  const Real p = -m.bulk * std::log(J);
  const Real sm = meanStress(s);
  const Real tau = equivalentShear(s);
  Real scale = 1;
  const Real a = tau - m.mu_s * p;
  if (a > 0) {
    const Real c = dt > 0 ? m.i0 * m.shear * dt * std::sqrt(p) / m.inertial_scale : Real(0);
    const Real b = c - a + m.mu_span * p;
    const Real root = std::sqrt(b * b + 4 * a * c);
    const Real x = b > 0 ? 2 * a * c / (b + root) : Real(0.5) * (root - b);  // no cancellation
    scale = (tau - x) / tau;
  }
  s.xx = (s.xx - sm) * scale - p;
  s.yy = (s.yy - sm) * scale - p;
  s.zz = (s.zz - sm) * scale - p;
  s.xy *= scale;
}

/// Tait's pressure at volume ratio J, p = (K / gamma) (J^-gamma - 1), cut off at the tension the
/// fluid sustains (Pa, compression positive).
inline Real taitPressure(const MaterialParams& m, Real J) {
  const Real p = m.bulk / m.tait_gamma * (std::pow(J, -m.tait_gamma) - 1);
  return std::fmax(p, -m.tension);
}

/// A fluid's stress at volume ratio J under velocity gradient L: -p I + 2 eta D', D' the deviator
/// of the plane-strain rate of deformation (D_zz = 0, so sigma_zz carries -2 eta tr(D) / 3). Not
/// incremental: the pressure is a function of J alone, so no error accumulates in it.
inline Stress fluidStress(const MaterialParams& m, Real J, const VelocityGradient& L) {
  const Real p = taitPressure(m, J);
  const Real third = (L.xx + L.yy) / 3;
  const Real eta2 = 2 * m.viscosity;
  return {-p + eta2 * (L.xx - third), -p + eta2 * (L.yy - third), m.viscosity * (L.xy + L.yx),
          -p - eta2 * third};
}

/// Recoverable (elastic) energy density of a stress state (J/m^3, per current volume). Solids:
/// sigma_m^2 / (2K) + J2 / (2G). A fluid stores the work of its pressure, int_J^1 p dJ' per
/// reference volume, with J recovered from p = -sigma_m (viscous stress has no mean part); a point
/// held at the tension cut-off is counted at the cut-off's J.
inline Real elasticEnergyDensity(const MaterialParams& m, const Stress& s) {
  if (m.model == MaterialModel::kFluid) {
    const Real g = m.tait_gamma;
    const Real J = std::pow(1 - g * meanStress(s) / m.bulk, -1 / g);
    return m.bulk / g * ((std::pow(J, 1 - g) - 1) / (g - 1) - 1 + J) / J;
  }
  const Real sm = meanStress(s);
  const Real tau = equivalentShear(s);
  return sm * sm / (2 * m.bulk) + tau * tau / (2 * m.shear);
}

}  // namespace mpm_sdem
