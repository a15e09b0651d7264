#include "mpm_sdem/core/coupling/coupling.hpp"

#include "coupling/imp_coupling.hpp"
#include "coupling/multi_velocity.hpp"
#include "coupling/particle_surface.hpp"
#include "coupling/partitioned.hpp"

namespace mpm_sdem {

const std::vector<SchemeTraits>& couplingSchemes() {
  //                 scheme                              name                springs
  //                                                     takes_later_blocks
  static const std::vector<SchemeTraits> schemes = {
      {CouplingScheme::kImp, "imp", true, true},
      {CouplingScheme::kImpGrid, "imp_grid", true, true},
      {CouplingScheme::kMultiVelocity, "multi_velocity", false, true},
      {CouplingScheme::kParticleSurface, "particle_surface", false, true},
      {CouplingScheme::kPartitioned, "partitioned", true, false},
  };
  return schemes;
}

const SchemeTraits& schemeTraits(CouplingScheme s) {
  const std::vector<SchemeTraits>& all = couplingSchemes();
  return all[static_cast<std::size_t>(s)];  // listed in the enum's order
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
