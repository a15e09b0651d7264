/// \file
/// Materials: what a scene declares (MaterialDef), the constants the constitutive update reads
/// (MaterialParams), and the table of models, each describing itself in one row (MaterialTraits,
/// as the coupling schemes do). A model's keys, checks, constants and stress update live in its
/// own files under core/mpm/materials/; constitutive.hpp dispatches the hot update among them.
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// A material's constitutive model (scene key materials[].model), in the order of the table of
/// models (materialModels()).
enum class MaterialModel {
  kLinearElastic,  ///< Hooke's law in rate form (seed 000 eq. 30)
  kDruckerPrager,  ///< seed 000 eq. 31-35: elastic-perfectly plastic with a tension cut-off
  /// Weakly compressible fluid (seed 002 sec. 4.3-4.4 model water this way): pressure from the
  /// volume ratio by Tait's equation, Newtonian viscosity, and a tension cut-off.
  kFluid,
  /// Dense granular flow: the mu(I) rheology of Jop, Forterre & Pouliquen 2006 with
  /// the dense and separated states of Dunatunga & Kamrin 2015. The scene's density is the
  /// critical (random close) packing: a point looser than it (J > 1) has separated and carries
  /// no stress; packed (J <= 1) its pressure is K ln(1 / J) and its shear stress at most
  /// mu(I) p. Elasticity is only the dense state's stiffness.
  kGranular,
};

/// What a scene declares for a material. Elasticity is given as bulk and shear moduli; the scene
/// layer converts Young's modulus and Poisson's ratio (K = E / (3 (1 - 2 nu)), G = E / (2 (1 +
/// nu))).
struct MaterialDef {
  std::string name;                                     ///< as bodies name it
  MaterialModel model = MaterialModel::kLinearElastic;  ///< the constitutive model
  Real density = 0;        ///< kg/m^3 (plane strain: per unit thickness)
  Real bulk_modulus = 0;   ///< Pa
  Real shear_modulus = 0;  ///< Pa
  /// Drucker-Prager only (seed 000 eq. 31-35).
  Real friction_angle = 0;    ///< rad
  Real dilation_angle = 0;    ///< rad, 0 <= psi <= phi
  Real cohesion = 0;          ///< Pa
  Real tensile_strength = 0;  ///< Pa, tension cut-off sigma^t (capped at the cone apex)
  /// Volume ratio J = V / V0 above which the grains have lost contact with each other: the
  /// point carries no stress and no elastic wave until it is packed again (the disconnected
  /// phase of a cohesionless granular continuum, Dunatunga and Kamrin 2015). Keeps a free-falling
  /// stream from bounding the step by the stiffness of a density it no longer has. 0: off.
  Real separation_volume_ratio = 0;
  /// Granular only (mu(I), Jop et al. 2006): mu = mu_s + (mu_2 - mu_s) / (I_0 / I + 1) with the
  /// inertial number I = gamma_dot d / sqrt(p / rho_s), rho_s = density / solid_fraction the
  /// grains' own density.
  Real mu_s = 0;            ///< static friction coefficient (dimensionless)
  Real mu_2 = 0;            ///< limiting friction coefficient at large I, >= mu_s
  Real inertial_i0 = 0;     ///< I_0 (dimensionless)
  Real grain_diameter = 0;  ///< d (m)
  Real solid_fraction = 0;  ///< phi of the critical packing (dimensionless)
  /// Fluid only. Pressure p = (K / gamma) (J^-gamma - 1) with K = rho0 c0^2 in bulk_modulus
  /// (Tait's equation; gamma = 7 for water), never below -tensile_strength (the tension the fluid
  /// sustains before it cavitates: seed 002 keeps water's surface smooth with 6 kPa); deviatoric
  /// stress 2 eta D' (plane strain, no bulk viscosity). c0 may be an artificial sound speed:
  /// density errors scale as the Mach number squared (diagnostics' max_mach).
  Real tait_exponent = 7;  ///< gamma (dimensionless)
  Real viscosity = 0;      ///< eta (Pa s)
};

/// Derived constants, computed once. Kept small: the constitutive loop reads one per particle.
struct MaterialParams {
  MaterialModel model = MaterialModel::kLinearElastic;  ///< as the definition
  bool batches_stress = false;                          ///< as its row (MaterialTraits)
  ///@{
  /// K, G, lambda = K - 2G/3 (Pa)
  Real bulk = 0, shear = 0, lame = 0;
  ///@}
  ///@{
  /// seed 000 eq. 35 and its dilatant analogue
  Real q_phi = 0, k_phi = 0, q_psi = 0;
  ///@}
  Real tension = 0;  ///< effective tension cut-off (Pa)
  ///@{
  /// Constants of the Drucker-Prager return, computed once: the corner shear stress
  /// k_phi - q_phi sigma^t (Pa), the slope alpha^P of the line that splits shear from tensile
  /// returns, and 1 / (G + K q_phi q_psi) (1/Pa).
  Real tau_corner = 0, alpha_p = 0, inv_return_modulus = 0;
  ///@}
  Real modulus_over_density = 0;  ///< (K + 4G/3) / rho0: squared P-wave speed at J = 1
  Real separation = std::numeric_limits<Real>::infinity();  ///< J above which: no stress
  ///@{
  /// fluid only
  Real tait_gamma = 7, viscosity = 0;
  ///@}
  ///@{
  /// Granular only: mu_s, mu_2 - mu_s, I_0, and d sqrt(rho_s) (so that I = gamma_dot
  /// inertial_scale / sqrt(p)).
  Real mu_s = 0, mu_span = 0, i0 = 0, inertial_scale = 0;
  ///@}
};

/// How a model's stiffness is given.
enum class MaterialStiffness {
  kModuli,      ///< a solid's: youngs_modulus and poisson_ratio, or bulk_modulus and shear_modulus
  kSoundSpeed,  ///< a fluid's: sound_speed (bulk modulus density c0^2), no shear modulus
};

/// One scene key of a model (materials[].key): the definition's field it sets, its range in the
/// scene's unit, whether it may be left out, and the factor from the scene's unit to SI.
struct MaterialKey {
  const char* key;            ///< as the scene names it
  Real MaterialDef::*field;   ///< the definition's field
  limits::Range range;        ///< in the scene's unit; checked at the key's line
  bool required = false;      ///< without it the material is refused
  Real fallback = 0;          ///< in the scene's unit, when not required and left out
  Real to_si = 1;             ///< scene unit -> SI (deg -> rad: kDeg)
  const char* why = nullptr;  ///< the range's reason, added to its message
};

/// What a constitutive model is, in one row: its scene name and keys, how its stiffness is given,
/// which checks and constants it adds to the common ones (elasticity, density), and how its
/// update runs. Each model defines its row in its own file (core/mpm/materials/); the table
/// (materialModels) lists them in the enum's order.
struct MaterialTraits {
  MaterialModel model;            ///< its enum value
  const char* name;               ///< the scene's model: value
  MaterialStiffness stiffness;    ///< moduli or sound speed
  std::vector<MaterialKey> keys;  ///< its own keys, beyond the common ones
  /// Checks that span keys, once they are read (a key-tagged Problem; empty when none).
  Problem (*check)(const MaterialDef&);
  /// Its own constants, after the common ones (MaterialParams' bulk, shear, lame, wave speed).
  void (*derive)(const MaterialDef&, MaterialParams&);
  /// Whether its stress update runs in SIMD batches (stress_batch.hpp): measured per model.
  bool batches_stress = false;
  /// Whether its wave speed depends on J otherwise than a solid's (modulus J / rho0): the CFL
  /// loop then looks each point's model up.
  bool own_wave_speed = false;
  /// Whether the diagnostics report its Mach number (a weakly compressible fluid's density error
  /// grows as its square).
  bool reports_mach = false;
  /// Whether it flows without limit (granular, fluid): its points keep their volumes tiling
  /// the space under SolverDef::volume_fit.
  bool flows = false;
};

/// Every model, in the enum's order.
const std::vector<MaterialTraits>& materialModels();
/// A model's row.
const MaterialTraits& materialTraits(MaterialModel model);

/// The derived constants of a definition: the common ones, then the model's own (derive).
MaterialParams makeMaterialParams(const MaterialDef& def);

}  // namespace mpm_sdem
