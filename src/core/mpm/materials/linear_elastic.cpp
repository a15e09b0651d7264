#include "mpm_sdem/core/mpm/materials/linear_elastic.hpp"

namespace mpm_sdem {

const MaterialTraits& linearElasticModel() {
  static const MaterialTraits traits{MaterialModel::kLinearElastic,
                                     "linear_elastic",
                                     MaterialStiffness::kModuli,
                                     {},
                                     [](const MaterialDef&) { return Problem(); },
                                     [](const MaterialDef&, MaterialParams&) {}};
  return traits;
}

}  // namespace mpm_sdem
