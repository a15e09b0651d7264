#include "mpm_sdem/core/coupling/coupling.hpp"

#include "coupling/imp_coupling.hpp"
#include "coupling/multi_velocity.hpp"
#include "coupling/particle_surface.hpp"
#include "coupling/partitioned.hpp"

namespace mpm_sdem {

const char* couplingSchemeName(CouplingScheme s) {
  switch (s) {
    case CouplingScheme::kImp:
      return "imp";
    case CouplingScheme::kImpGrid:
      return "imp_grid";
    case CouplingScheme::kMultiVelocity:
      return "multi_velocity";
    case CouplingScheme::kParticleSurface:
      return "particle_surface";
    case CouplingScheme::kPartitioned:
      return "partitioned";
  }
  return "?";
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
