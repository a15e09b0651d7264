/// \file
/// The material's free surface seen from above, for robots (a blade's or a wheel's perception):
/// the plane's elevation map.
#pragma once

#include <vector>

#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Height of the material's top in each of `columns` columns of width dx from x0 (m): the
/// highest top of a material point whose centre lies in the column, a point's top being its
/// centre plus half its current spacing (sqrt(V0 J) / 2, the lattice it was filled on). NaN where
/// a column holds no point. On a surface of slope s filled at spacing d, a column's value lies
/// within d / 2 + |s| dx / 2 of the surface at the column's centre.
void heightProfile(const Particles& points, Real x0, Real dx, int columns,
                   std::vector<Real>& height);

}  // namespace mpm_sdem
