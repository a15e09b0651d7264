#include "mpm_sdem/core/mpm/material.hpp"

#include "mpm_sdem/core/mpm/constitutive.hpp"

namespace mpm_sdem {

const std::vector<MaterialTraits>& materialModels() {
  // One row per model, in the enum's order; each row is defined in the model's own file.
  static const std::vector<MaterialTraits> models = {linearElasticModel(), druckerPragerModel(),
                                                     fluidModel(), granularModel()};
  return models;
}

const MaterialTraits& materialTraits(MaterialModel model) {
  return materialModels()[static_cast<std::size_t>(model)];
}

MaterialParams makeMaterialParams(const MaterialDef& def) {
  MaterialParams p;
  p.model = def.model;
  p.batches_stress = materialTraits(def.model).batches_stress;
  p.bulk = def.bulk_modulus;
  p.shear = def.shear_modulus;
  p.lame = def.bulk_modulus - Real(2) / 3 * def.shear_modulus;
  p.modulus_over_density = (def.bulk_modulus + Real(4) / 3 * def.shear_modulus) / def.density;
  if (def.separation_volume_ratio > 0) p.separation = def.separation_volume_ratio;
  materialTraits(def.model).derive(def, p);
  return p;
}

}  // namespace mpm_sdem
