/// \file
/// Whole-world measures for the time series and the conservation tests.
#pragma once

#include <string>

#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

/// Energies (J/m), momentum (N s/m), mass (kg/m) and extremes of a world at one instant.
struct Diagnostics {
  Real kinetic = 0;  ///< J per metre of thickness, 1/2 sum m |v|^2 (staggered velocities)
  Real elastic = 0;  ///< J/m, recoverable strain energy from the stress, sum V w(sigma)
  Real gravity = 0;  ///< J/m, -sum m g . (x - domain min)

  /// Kinetic, elastic and gravitational energy together (J/m).
  Real total() const { return kinetic + elastic + gravity; }
  Vec2 momentum{0, 0};        ///< kg m/s per metre
  Real angular_momentum = 0;  ///< kg m^2/s per metre about the world origin, with the APIC spin
  Vec2 center_of_mass{0, 0};  ///< m
  Real mass = 0;              ///< kg per metre
  Real max_speed = 0;         ///< m/s (material points)
  /// The largest |v| / c of a fluid point, c its current sound speed: a weakly compressible fluid
  /// errs in density by about Ma^2 / 2, so an artificial c0 should keep this below 0.1 (0.5%).
  Real max_mach = 0;
  /// Dynamic blocks, included in the energies and momenta above as well.
  Real block_kinetic = 0;     ///< J/m, translation and rotation
  Vec2 block_momentum{0, 0};  ///< kg m/s per metre
  /// FEM bodies, included in the energies and momenta above as well.
  Real fem_kinetic = 0;  ///< J/m
  Real fem_strain = 0;   ///< J/m
  bool finite = true;    ///< every summed quantity is finite
};

/// The world's measures now.
Diagnostics measure(const World& world);

/// The material mass on one side of a line (a discharge or a front gauge; scene output.gauges).
struct MassGauge {
  /// Which side of the line is counted.
  enum class Side { kBelow, kRightOf };
  std::string name;          ///< as the outputs name it
  Side side = Side::kBelow;  ///< below a height, or right of an abscissa
  Real at = 0;               ///< m: the height (kBelow: y < at) or the abscissa (kRightOf: x > at)
};
/// kg per metre of thickness, over the material points (SPH particles included).
Real gaugeMass(const Particles& P, const MassGauge& g);

/// The Mach number past which the runner and the node warn (once): a density error of about
/// Ma^2 / 2 = 0.5% (docs/scene_reference.md, fluid).
inline constexpr Real kMachWarning = 0.1;
/// That warning's text for a state that reached max_mach at time t (s); "" below kMachWarning.
std::string machWarning(const Diagnostics& d, Real t);

}  // namespace mpm_sdem
