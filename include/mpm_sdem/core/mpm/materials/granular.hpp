/// \file
/// The granular material: the mu(I) rheology of Jop, Forterre & Pouliquen 2006 with the dense
/// and separated states of Dunatunga & Kamrin 2015.
#pragma once

#include "mpm_sdem/core/mpm/stress.hpp"

namespace mpm_sdem {

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

/// A granular point's stress after dt: the Jaumann-rate trial stress (eq. 21-25), then the mu(I)
/// return with the point's new volume ratio J.
inline Stress granularUpdate(const MaterialParams& m, const Stress& s, const VelocityGradient& L,
                             Real J, Real dt) {
  Stress r = jaumannElasticUpdate(m, s, L, dt);
  granularReturn(m, r, J, dt);
  return r;
}

/// Its row of the table of models: mu_s, mu_2, I_0, the grain diameter and the solid fraction;
/// a point looser than the critical packing (J > 1) has separated.
const MaterialTraits& granularModel();

}  // namespace mpm_sdem
