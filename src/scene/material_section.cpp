// The scene's materials section.
#include "scene_sections.hpp"

#include <cmath>

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem::scene {

namespace {

MaterialDef parseMaterial(const Context& ctx, const YAML::Node& n, const std::string& path) {
  MapReader r(ctx, n, path,
              {"name",           "model",         "density",          "youngs_modulus",
               "poisson_ratio",  "bulk_modulus",  "shear_modulus",    "friction_angle",
               "dilation_angle", "cohesion",      "tensile_strength", "separation_volume_ratio",
               "sound_speed",    "tait_exponent", "viscosity",        "mu_s",
               "mu_2",           "i_0",           "grain_diameter",   "solid_fraction"});
  MaterialDef m;
  m.name = r.name("name");
  m.model = r.choiceOf<MaterialModel>(r.node("model"), r.path("model"),
                                      {{"linear_elastic", MaterialModel::kLinearElastic},
                                       {"drucker_prager", MaterialModel::kDruckerPrager},
                                       {"granular", MaterialModel::kGranular},
                                       {"fluid", MaterialModel::kFluid}});
  m.density = r.number("density", limits::kDensity);
  const bool fluid = m.model == MaterialModel::kFluid;
  const std::vector<const char*> solid_keys = {"youngs_modulus", "poisson_ratio", "bulk_modulus",
                                               "shear_modulus"};
  const std::vector<const char*> fluid_keys = {"sound_speed", "tait_exponent", "viscosity"};
  for (const char* k : fluid ? solid_keys : fluid_keys) {
    r.require(!r.has(k), k,
              fluid ? "applies only to a solid; a fluid's stiffness is its sound_speed"
                    : "applies only to model: fluid");
  }
  const bool e_nu = r.has("youngs_modulus") || r.has("poisson_ratio");
  const bool k_g = r.has("bulk_modulus") || r.has("shear_modulus");
  if (fluid) {
    const Real c = r.number("sound_speed", limits::kSoundSpeed);
    m.bulk_modulus = m.density * c * c;
    r.require(m.bulk_modulus >= limits::kModulus.min && m.bulk_modulus <= limits::kModulus.max,
              "sound_speed",
              "gives a bulk modulus density * sound_speed^2 = " + num(m.bulk_modulus) +
                  " Pa outside [1, 1e13] Pa");
    m.tait_exponent = r.number("tait_exponent", limits::kTaitExponent, 7);
    m.viscosity = r.number("viscosity", limits::kViscosity, 0);
    m.tensile_strength = r.number("tensile_strength", limits::kStrength, 0);
  } else if (e_nu == k_g) {
    ctx.fail(n, path,
             "give the elasticity either as youngs_modulus and poisson_ratio or as "
             "bulk_modulus and shear_modulus (Pa)");
  } else if (e_nu) {
    const Real E = r.number("youngs_modulus", limits::kModulus);
    const Real nu = r.number("poisson_ratio", "(dimensionless)");
    r.require(nu > -1 && nu < 0.5, "poisson_ratio",
              "must be in (-1, 0.5) (0.5 is incompressible), got " + num(nu));
    m.bulk_modulus = E / (3 * (1 - 2 * nu));
    m.shear_modulus = E / (2 * (1 + nu));
  } else {
    m.bulk_modulus = r.number("bulk_modulus", limits::kModulus);
    m.shear_modulus = r.number("shear_modulus", limits::kModulus);
  }
  const char* plastic_keys[] = {"friction_angle", "dilation_angle", "cohesion", "tensile_strength",
                                "separation_volume_ratio"};
  if (m.model == MaterialModel::kDruckerPrager) {
    const Real phi = r.number("friction_angle", "deg");
    r.require(phi >= 0 && phi <= kMaxFrictionAngle / kDeg, "friction_angle",
              "must be in [0, " + num(kMaxFrictionAngle / kDeg) + "] deg, got " + num(phi) +
                  ": the plane-strain Drucker-Prager cone (seed 000 eq. 35) holds no flowing "
                  "slope steeper than 60 deg (docs/scene_reference.md)");
    const Real psi = r.number("dilation_angle", "deg", 0);
    r.require(psi >= 0 && psi <= phi, "dilation_angle",
              "must be in [0, friction_angle] deg, got " + num(psi));
    m.friction_angle = phi * kDeg;
    m.dilation_angle = psi * kDeg;
    m.cohesion = r.number("cohesion", limits::kStrength, 0);
    m.tensile_strength = r.number("tensile_strength", limits::kStrength, 0);
    m.separation_volume_ratio = r.number("separation_volume_ratio", "(dimensionless)", 0);
    r.require(m.separation_volume_ratio == 0 || m.separation_volume_ratio > 1,
              "separation_volume_ratio",
              "must be > 1 (a volume ratio V / V0 looser than the initial packing) or 0 for "
              "off, got " +
                  num(m.separation_volume_ratio));
  } else {
    for (const char* k : plastic_keys) {
      if (fluid && std::string(k) == "tensile_strength") continue;
      r.require(!r.has(k), k, "applies only to model: drucker_prager");
    }
  }
  const char* granular_keys[] = {"mu_s", "mu_2", "i_0", "grain_diameter", "solid_fraction"};
  if (m.model == MaterialModel::kGranular) {
    // Glass beads (Jop, Forterre & Pouliquen 2006): mu_s = tan 20.9 deg = 0.382, mu_2 = tan
    // 32.76 deg = 0.643, I_0 = 0.279, d = 0.53 mm, phi = 0.6.
    m.mu_s = r.number("mu_s", "(dimensionless)");
    r.require(m.mu_s >= 0 && m.mu_s <= 2, "mu_s",
              "must be in [0, 2] (tan of the static friction angle), got " + num(m.mu_s));
    m.mu_2 = r.number("mu_2", "(dimensionless)");
    r.require(m.mu_2 >= m.mu_s && m.mu_2 <= 4, "mu_2",
              "must be in [mu_s, 4] (the friction at large inertial number), got " + num(m.mu_2));
    m.inertial_i0 = r.number("i_0", "(dimensionless)");
    r.require(m.inertial_i0 > 0 && m.inertial_i0 <= 10, "i_0",
              "must be in (0, 10] (0.279 for glass beads), got " + num(m.inertial_i0));
    m.grain_diameter = r.number("grain_diameter", "m");
    r.require(m.grain_diameter > 0 && m.grain_diameter <= 1, "grain_diameter",
              "must be in (0, 1] m, got " + num(m.grain_diameter));
    m.solid_fraction = r.number("solid_fraction", "(dimensionless)", 0.6);
    r.require(m.solid_fraction > 0 && m.solid_fraction < 1, "solid_fraction",
              "must be in (0, 1) (the grains' share of the volume at the critical packing), got " +
                  num(m.solid_fraction));
  } else {
    for (const char* k : granular_keys) r.require(!r.has(k), k, "applies only to model: granular");
  }
  return m;
}

}  // namespace

// The list of materials; their indices by name (bodies name their material).
std::map<std::string, int> parseMaterials(const Context& ctx, const MapReader& top, Scene& s) {
  const YAML::Node mats = top.node("materials");
  if (!mats.IsSequence() || mats.size() == 0) {
    ctx.fail(mats, "materials", "expected a list of at least one material");
  }
  std::map<std::string, int> by_name;
  for (std::size_t i = 0; i < mats.size(); ++i) {
    const std::string path = "materials[" + std::to_string(i) + "]";
    MaterialDef m = parseMaterial(ctx, mats[i], path);
    if (by_name.count(m.name))
      ctx.fail(mats[i], path, "a material named '" + m.name + "' exists already");
    by_name[m.name] = static_cast<int>(s.world.materials.size());
    s.world.materials.push_back(std::move(m));
  }
  return by_name;
}

}  // namespace mpm_sdem::scene
