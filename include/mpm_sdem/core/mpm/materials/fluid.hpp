/// \file
/// The weakly compressible fluid (seed 002 sec. 4.3-4.4 model water this way): pressure from the
/// volume ratio by Tait's equation, Newtonian viscosity, and a tension cut-off.
#pragma once

#include "mpm_sdem/core/mpm/stress.hpp"

namespace mpm_sdem {

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

/// A fluid's stress after dt: a function of its new volume ratio J and of L alone (fluidStress),
/// so no error accumulates in it.
inline Stress fluidUpdate(const MaterialParams& m, const Stress& /*s*/, const VelocityGradient& L,
                          Real J, Real /*dt*/) {
  return fluidStress(m, J, L);
}

/// Tait's dp/drho at volume ratio J: c0^2 J^(1 - gamma) (m^2/s^2).
inline Real fluidSquaredWaveSpeed(const MaterialParams& m, Real J) {
  return m.modulus_over_density * std::pow(J, 1 - m.tait_gamma);
}

/// The work a fluid's pressure stores, int_J^1 p dJ' per reference volume, as a density per
/// current volume (J/m^3), with J recovered from p = -sigma_m (viscous stress has no mean part);
/// a point held at the tension cut-off is counted at the cut-off's J.
inline Real fluidEnergyDensity(const MaterialParams& m, const Stress& s) {
  const Real g = m.tait_gamma;
  const Real J = std::pow(1 - g * meanStress(s) / m.bulk, -1 / g);
  return m.bulk / g * ((std::pow(J, 1 - g) - 1) / (g - 1) - 1 + J) / J;
}

/// Its row of the table of models: the Tait exponent, the viscosity and the tension it sustains;
/// its stiffness is its sound speed.
const MaterialTraits& fluidModel();

}  // namespace mpm_sdem
