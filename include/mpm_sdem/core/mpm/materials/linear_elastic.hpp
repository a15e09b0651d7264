/// \file
/// The linear elastic material: Hooke's law in rate form (seed 000 eq. 30), the Jaumann update
/// every solid starts from.
#pragma once

#include "mpm_sdem/core/mpm/stress.hpp"

namespace mpm_sdem {

/// A linear elastic point's stress after dt: the Jaumann-rate update alone (eq. 21-25, 36).
inline Stress linearElasticUpdate(const MaterialParams& m, const Stress& s,
                                  const VelocityGradient& L, Real /*J*/, Real dt) {
  return jaumannElasticUpdate(m, s, L, dt);
}

/// Its row of the table of models: no keys beyond the common ones.
const MaterialTraits& linearElasticModel();

}  // namespace mpm_sdem
