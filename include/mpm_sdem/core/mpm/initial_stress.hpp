/// \file
/// A body's starting stress: its own weight at rest (BodyDef::geostatic), so that a bed starts in
/// equilibrium instead of ringing while its weight comes on.
#pragma once

#include <cstddef>

#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Points [begin, end) of a layer filled on a lattice of the given spacing (m) from x = x0 (m),
/// of material m under gravity g (m/s^2, downwards): sigma_yy = -rho g z at the depth z below the
/// top of the point's column of points (its highest point plus half a spacing), and
/// sigma_xx = sigma_zz = K0 sigma_yy with the at-rest ratio K0 = nu / (1 - nu) of the material's
/// Poisson ratio (1 for a body without shear stiffness). A granular point (pressure K ln(1 / J))
/// is given the J of that stress and V0 = V / J, so that its volume stays the lattice's.
void setLayerWeightAsStress(Particles& P, std::size_t begin, std::size_t end, const MaterialDef& m,
                            Real g, Real spacing, Real x0);

/// Whether a body of this material can start from its weight: "" or why not (a fluid's pressure
/// is a function of its density alone).
const char* geostaticProblem(const MaterialDef& m);

}  // namespace mpm_sdem
