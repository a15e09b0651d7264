/// \file
/// The constitutive update of one material point, dispatched on its model: the one place the hot
/// loops (the transfers, the SPH region, the step's CFL term, the diagnostics) learn which model a
/// point has. Each model's functions live in its own header under materials/; a new model adds a
/// case to each switch here, its row to the table (material.cpp) and its files.
#pragma once

#include "mpm_sdem/core/mpm/materials/drucker_prager.hpp"
#include "mpm_sdem/core/mpm/materials/fluid.hpp"
#include "mpm_sdem/core/mpm/materials/granular.hpp"
#include "mpm_sdem/core/mpm/materials/linear_elastic.hpp"
#include "mpm_sdem/core/mpm/stress.hpp"

namespace mpm_sdem {

/// A point's stress after dt under velocity gradient L, its volume ratio J advanced to
/// det(I + dt L) J first (the granular return and the fluid's pressure read the new J).
[[gnu::always_inline]] inline Stress updateStress(const MaterialParams& m, const Stress& s,
                                                  const VelocityGradient& L, Real& J, Real dt) {
  J *= volumeChange(L, dt);
  switch (m.model) {
    case MaterialModel::kLinearElastic:
      return linearElasticUpdate(m, s, L, J, dt);
    case MaterialModel::kDruckerPrager:
      return druckerPragerUpdate(m, s, L, J, dt);
    case MaterialModel::kFluid:
      return fluidUpdate(m, s, L, J, dt);
    case MaterialModel::kGranular:
      return granularUpdate(m, s, L, J, dt);
  }
  return s;
}

/// Squared wave speed of a point of volume ratio J (m^2/s^2), the CFL term of seed 000 eq. 51:
/// the model's own (a solid's modulus over the current density rho0 / J; Tait's dp/drho for a
/// fluid); none when the point has separated (MaterialParams::separation).
inline Real squaredWaveSpeed(const MaterialParams& m, Real J) {
  if (J > m.separation) return 0;
  if (m.model == MaterialModel::kFluid) return fluidSquaredWaveSpeed(m, J);
  return solidSquaredWaveSpeed(m, J);
}

/// Recoverable (elastic) energy density of a stress state (J/m^3, per current volume): a solid's
/// sigma_m^2 / (2K) + J2 / (2G), the work of a fluid's pressure.
inline Real elasticEnergyDensity(const MaterialParams& m, const Stress& s) {
  if (m.model == MaterialModel::kFluid) return fluidEnergyDensity(m, s);
  return solidEnergyDensity(m, s);
}

}  // namespace mpm_sdem
