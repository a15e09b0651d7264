// What the topic files of the cases library share beyond cases.hpp.
#pragma once

#include "cases.hpp"

namespace mpm_sdem::cases {

// The incline's and the thrown disk's material: rho = 1000 kg/m^3, E = 10 MPa, nu = 0.3.
MaterialDef elasticDisk();

}  // namespace mpm_sdem::cases
