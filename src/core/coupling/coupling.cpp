#include "mpm_sdem/core/coupling/coupling.hpp"

#include "coupling/imp_coupling.hpp"
#include "coupling/multi_velocity.hpp"
#include "coupling/particle_surface.hpp"
#include "coupling/partitioned.hpp"

namespace mpm_sdem {

const std::vector<SchemeTraits>& couplingSchemes() {
  //                 scheme                              name                springs imp_springs
  //                                                     meets_fem meets_sph takes_later_blocks
  static const std::vector<SchemeTraits> schemes = {
      {CouplingScheme::kImp, "imp", true, true, true, true, true},
      {CouplingScheme::kImpGrid, "imp_grid", true, true, true, true, true},
      {CouplingScheme::kMultiVelocity, "multi_velocity", false, false, false, false, true},
      {CouplingScheme::kParticleSurface, "particle_surface", false, false, true, true, true},
      {CouplingScheme::kPartitioned, "partitioned", true, false, false, false, false},
  };
  return schemes;
}

const SchemeTraits& schemeTraits(CouplingScheme s) {
  const std::vector<SchemeTraits>& all = couplingSchemes();
  return all[static_cast<std::size_t>(s)];  // listed in the enum's order
}

Problem schemeProblem(CouplingScheme s, bool fem_bodies, bool sph_particles) {
  const SchemeTraits& t = schemeTraits(s);
  const bool fem = fem_bodies && !t.meets_fem_bodies, sph = sph_particles && !t.meets_sph_particles;
  if (!fem && !sph) return {};
  std::string able;
  for (const SchemeTraits& o : couplingSchemes())
    if ((!fem || o.meets_fem_bodies) && (!sph || o.meets_sph_particles))
      able += std::string(able.empty() ? "" : ", ") + o.name;
  const std::string what = fem ? "FEM bodies (it needs a block's interior lattice or a wall of its "
                                 "own, built from the material's outline)"
                               : "SPH particles (it meets bodies on the grid, which does not move "
                                 "them)";
  return {"coupling.scheme", std::string(t.name) + " cannot meet " + what + "; use " + able};
}

std::unique_ptr<Coupling> makeCoupling(const CouplingDef& def, const Vec2& lo, const Vec2& hi,
                                       Real cell_size, const std::vector<BodyDef>& bodies) {
  switch (def.scheme) {
    case CouplingScheme::kImp:
    case CouplingScheme::kImpGrid:
      return std::make_unique<ImpCoupling>(def, lo, hi, cell_size);
    case CouplingScheme::kMultiVelocity:
      return std::make_unique<MultiVelocityCoupling>(def, cell_size);
    case CouplingScheme::kParticleSurface:
      return std::make_unique<ParticleSurfaceCoupling>(def, lo, hi, cell_size);
    case CouplingScheme::kPartitioned:
      return std::make_unique<PartitionedCoupling>(def, cell_size, bodies);
  }
  return nullptr;
}

}  // namespace mpm_sdem
