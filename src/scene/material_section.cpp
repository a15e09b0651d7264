// The scene's materials section: the common keys (name, model, density, the stiffness), then the
// model's own keys and checks as its row of the table of models lists them (material.hpp).
#include "scene_sections.hpp"

#include <algorithm>
#include <cmath>

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem::scene {

namespace {

const std::vector<const char*> kSolidKeys = {"youngs_modulus", "poisson_ratio", "bulk_modulus",
                                             "shear_modulus"};
const char* const kSoundSpeedKey = "sound_speed";

// Every key a material may have: the common ones and each model's own.
std::vector<const char*> materialKeys() {
  std::vector<const char*> keys = {"name", "model", "density", kSoundSpeedKey};
  keys.insert(keys.end(), kSolidKeys.begin(), kSolidKeys.end());
  for (const MaterialTraits& t : materialModels())
    for (const MaterialKey& k : t.keys)
      if (std::none_of(keys.begin(), keys.end(),
                       [&](const char* o) { return o == std::string(k.key); }))
        keys.push_back(k.key);
  return keys;
}

// "drucker_prager or fluid": the models whose rows list the key.
std::string modelsWith(const std::string& key) {
  std::string models;
  for (const MaterialTraits& t : materialModels())
    for (const MaterialKey& k : t.keys)
      if (key == k.key) models += std::string(models.empty() ? "" : " or ") + t.name;
  return models;
}

// A solid's moduli, given as E and nu or as K and G (Pa).
void parseModuli(const Context& ctx, const YAML::Node& n, const std::string& path,
                 const MapReader& r, MaterialDef& m) {
  const bool e_nu = r.has("youngs_modulus") || r.has("poisson_ratio");
  const bool k_g = r.has("bulk_modulus") || r.has("shear_modulus");
  if (e_nu == k_g) {
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
}

// A fluid's stiffness: its sound speed c0, the bulk modulus density c0^2 (Pa).
void parseSoundSpeed(const MapReader& r, MaterialDef& m) {
  const Real c = r.number(kSoundSpeedKey, limits::kSoundSpeed);
  m.bulk_modulus = m.density * c * c;
  r.require(m.bulk_modulus >= limits::kModulus.min && m.bulk_modulus <= limits::kModulus.max,
            kSoundSpeedKey,
            "gives a bulk modulus density * sound_speed^2 = " + num(m.bulk_modulus) +
                " Pa outside [1, 1e13] Pa");
}

MaterialDef parseMaterial(const Context& ctx, const YAML::Node& n, const std::string& path) {
  static const std::vector<const char*> keys = materialKeys();
  MapReader r(ctx, n, path, keys);
  MaterialDef m;
  m.name = r.name("name");
  std::vector<std::pair<const char*, MaterialModel>> names;
  for (const MaterialTraits& t : materialModels()) names.emplace_back(t.name, t.model);
  m.model = r.choiceOf<MaterialModel>(r.node("model"), r.path("model"), names);
  const MaterialTraits& traits = materialTraits(m.model);
  m.density = r.number("density", limits::kDensity);

  const bool fluid = traits.stiffness == MaterialStiffness::kSoundSpeed;
  for (const char* k : kSolidKeys)
    r.require(!(fluid && r.has(k)), k,
              "applies only to a solid; a " + std::string(traits.name) +
                  "'s stiffness is its sound_speed");
  r.require(fluid || !r.has(kSoundSpeedKey), kSoundSpeedKey,
            "applies only to model: fluid (a solid's stiffness is its moduli)");
  if (fluid) {
    parseSoundSpeed(r, m);
  } else {
    parseModuli(ctx, n, path, r, m);
  }

  // The model's own keys; another model's are refused.
  for (const MaterialTraits& other : materialModels()) {
    if (other.model == m.model) continue;
    for (const MaterialKey& k : other.keys) {
      const bool own =
          std::any_of(traits.keys.begin(), traits.keys.end(),
                      [&](const MaterialKey& o) { return o.key == std::string(k.key); });
      r.require(own || !r.has(k.key), k.key, "applies only to model: " + modelsWith(k.key));
    }
  }
  for (const MaterialKey& k : traits.keys) {
    if (k.required || r.has(k.key)) {
      const Real v = r.number(k.key, k.range.unit[0] ? k.range.unit : "(dimensionless)");
      const Problem p = limits::rangeProblem(v, k.range);
      r.require(k.key, k.why && !p.empty() ? Problem(p.message + ": " + k.why) : p);
      m.*k.field = v * k.to_si;
    } else {
      m.*k.field = k.fallback * k.to_si;
    }
  }
  if (const Problem p = traits.check(m); !p.empty()) r.require(p.key.c_str(), p);
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
