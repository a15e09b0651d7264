// What the topic files of the cases library share beyond cases.hpp.
#pragma once

#include <string>
#include <vector>

#include "cases.hpp"

namespace mpm_sdem::cases {

// A number, a point or a list of points as a scene override writes them (--set key=value): every
// bit kept (%.17g reads back to the same double).
std::string exact(Real v);
std::string exact(const Vec2& v);
std::string exact(const std::vector<Vec2>& points);

// A shipped scene, config/scenes/NAME.yaml, with overrides (key=value, as the runner's --set).
WorldDef shippedScene(const std::string& name, const std::vector<std::string>& set);

// The incline's and the thrown disk's material: rho = 1000 kg/m^3, E = 10 MPa, nu = 0.3.
MaterialDef elasticDisk();

}  // namespace mpm_sdem::cases
