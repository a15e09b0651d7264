#include "mpm_sdem/core/mpm/materials/fluid.hpp"

namespace mpm_sdem {

namespace {

void fluidConstants(const MaterialDef& def, MaterialParams& p) {
  p.tait_gamma = def.tait_exponent;
  p.viscosity = def.viscosity;
  p.tension = def.tensile_strength;
}

}  // namespace

const MaterialTraits& fluidModel() {
  static const MaterialTraits traits{
      MaterialModel::kFluid,
      "fluid",
      MaterialStiffness::kSoundSpeed,
      {{"tait_exponent", &MaterialDef::tait_exponent, limits::kTaitExponent, false, 7},
       {"viscosity", &MaterialDef::viscosity, limits::kViscosity},
       {"tensile_strength", &MaterialDef::tensile_strength, limits::kStrength}},
      [](const MaterialDef&) { return Problem(); },
      fluidConstants,
      /*batches_stress=*/false,
      /*own_wave_speed=*/true,
      /*reports_mach=*/true,
      /*flows=*/true};
  return traits;
}

}  // namespace mpm_sdem
