#include "mpm_sdem/core/mpm/materials/granular.hpp"

#include <cmath>

namespace mpm_sdem {

namespace {

Problem granularProblem(const MaterialDef& d) {
  if (!(d.mu_2 >= d.mu_s))
    return {"mu_2", "must be in [mu_s, 4] (the friction at large inertial number), got " +
                        limits::shown(d.mu_2)};
  if (!(d.solid_fraction < 1))
    return {"solid_fraction",
            "must be in (0, 1) (the grains' share of the volume at the critical "
            "packing), got " +
                limits::shown(d.solid_fraction)};
  return {};
}

void granularConstants(const MaterialDef& def, MaterialParams& p) {
  p.mu_s = def.mu_s;
  p.mu_span = def.mu_2 - def.mu_s;
  p.i0 = def.inertial_i0;
  p.inertial_scale = def.grain_diameter * std::sqrt(def.density / def.solid_fraction);
  p.separation = 1;  // looser than the critical packing: separated
}

}  // namespace

// Glass beads (Jop, Forterre & Pouliquen 2006): mu_s = tan 20.9 deg = 0.382, mu_2 = tan 32.76 deg
// = 0.643, I_0 = 0.279, d = 0.53 mm, phi = 0.6.
const MaterialTraits& granularModel() {
  static const MaterialTraits traits{
      MaterialModel::kGranular,
      "granular",
      MaterialStiffness::kModuli,
      {{"mu_s", &MaterialDef::mu_s, {0, 2, ""}, true, 0, 1, "tan of the static friction angle"},
       {"mu_2",
        &MaterialDef::mu_2,
        {0, 4, ""},
        true,
        0,
        1,
        "the friction at large inertial number, at least mu_s"},
       {"i_0", &MaterialDef::inertial_i0, {0, 10, "", true}, true, 0, 1, "0.279 for glass beads"},
       {"grain_diameter", &MaterialDef::grain_diameter, {0, 1, "m", true}, true},
       {"solid_fraction",
        &MaterialDef::solid_fraction,
        {0, 1, "", true},
        false,
        0.6,
        1,
        "the grains' share of the volume at the critical packing, below 1"}},
      granularProblem,
      granularConstants,
      /*batches_stress=*/false,
      /*own_wave_speed=*/false,
      /*reports_mach=*/false,
      /*flows=*/true};
  return traits;
}

}  // namespace mpm_sdem
