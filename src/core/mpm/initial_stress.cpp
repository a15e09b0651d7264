#include "mpm_sdem/core/mpm/initial_stress.hpp"

#include <cmath>
#include <map>

namespace mpm_sdem {

void setLayerWeightAsStress(Particles& P, std::size_t begin, std::size_t end, const MaterialDef& m,
                            Real g, Real spacing, Real x0) {
  // Poisson's ratio from the moduli (plane strain's at-rest ratio of an elastic layer held
  // laterally): nu = (3K - 2G) / (2 (3K + G)).
  const Real nu =
      (3 * m.bulk_modulus - 2 * m.shear_modulus) / (2 * (3 * m.bulk_modulus + m.shear_modulus));
  const Real k0 = nu / (1 - nu);
  auto column = [&](std::size_t p) { return std::lround((P.x[p] - x0) / spacing - 0.5); };
  std::map<long, Real> top;
  for (std::size_t p = begin; p < end; ++p) {
    auto it = top.find(column(p));
    if (it == top.end() || it->second < P.y[p]) top[column(p)] = P.y[p];
  }
  for (std::size_t p = begin; p < end; ++p) {
    const Real z = top[column(p)] + spacing / 2 - P.y[p];
    P.syy[p] = -m.density * g * z;
    P.sxx[p] = P.szz[p] = k0 * P.syy[p];
    P.sxy[p] = 0;
    if (m.model == MaterialModel::kGranular) {
      // The granular pressure is K ln(1 / J), a function of the volume ratio: sigma_m = K ln J.
      const Real J = std::exp((P.sxx[p] + P.syy[p] + P.szz[p]) / (3 * m.bulk_modulus));
      P.J[p] = J;
      P.volume0[p] /= J;
    }
  }
}

const char* geostaticProblem(const MaterialDef& m) {
  if (materialTraits(m.model).stiffness == MaterialStiffness::kSoundSpeed)
    return "a fluid's pressure follows from its density: it cannot start from a stress";
  return "";
}

}  // namespace mpm_sdem
