/// \file
/// A material point's stress and velocity gradient (plane strain, tension positive), their
/// invariants, and the update every solid shares: Jaumann-rate elasticity. The stress keeps its
/// out-of-plane component sigma_zz, which plane strain makes non-zero and which enters the
/// invariants of the Drucker-Prager criterion.
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

/// The volume ratio's factor over dt, det(I + dt L) (seed 000: V^{n+1} = det(I + dt L) V^n).
inline Real volumeChange(const VelocityGradient& L, Real dt) {
  return (1 + dt * L.xx) * (1 + dt * L.yy) - dt * dt * L.xy * L.yx;
}

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

/// A solid's recoverable energy density (J/m^3, per current volume): sigma_m^2 / (2K) +
/// J2 / (2G).
inline Real solidEnergyDensity(const MaterialParams& m, const Stress& s) {
  const Real sm = meanStress(s);
  const Real tau = equivalentShear(s);
  return sm * sm / (2 * m.bulk) + tau * tau / (2 * m.shear);
}

/// A solid's squared P-wave speed at volume ratio J (m^2/s^2): its constant modulus over the
/// current density rho0 / J.
inline Real solidSquaredWaveSpeed(const MaterialParams& m, Real J) {
  return m.modulus_over_density * J;
}

}  // namespace mpm_sdem
