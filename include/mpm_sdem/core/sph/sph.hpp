/// \file
/// An SPH region coupled to the MPM region (seed 001): which particles are SPH particles, the
/// kernel, and the artificial viscosity. Particles carry all state, so a particle changes kind
/// simply by crossing a region's outline; its kind only chooses the scheme that updates it.
#pragma once

#include <cstdint>
#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Particles::kind.
enum ParticleKind : std::uint8_t { kMaterialPoint = 0, kSphParticle = 1 };

/// The two standard compact kernels, both written with support radius R = 2 h_s.
/// kCubicSpline: Monaghan's (1992) M4 spline, 2D normalisation 10 / (7 pi h_s^2).
/// kWendlandC2: Wendland's (1995) C2 function, 2D normalisation 7 / (pi R^2); no pairing
/// instability at many neighbours (Dehnen and Aly 2012).
enum class SphKernel { kCubicSpline, kWendlandC2 };
/// The kernel's name as a scene writes it.
const char* sphKernelName(SphKernel k);

/// The SPH particles of a scene (section `sph`, seed 001): where they are and their settings.
struct SphDef {
  /// A particle inside any of these shapes is an SPH particle, any other a material point,
  /// re-evaluated every step (seed 001 sec. 4: the kind follows the position).
  std::vector<ShapeDef> regions;
  /// Bodies (indices into WorldDef::bodies) whose points are SPH particles wherever they are.
  std::vector<int> bodies;
  SphKernel kernel = SphKernel::kCubicSpline;  ///< the smoothing kernel
  /// Smoothing length h_s (m); 0: the cell width, as seed 001 sec. 4 sets it so that the SPH and
  /// MPM resolutions agree. The kernels reach R = 2 h_s, at most 3 cells (the tiles of 3 cells
  /// are the neighbour search's cell list): h_s in [0.5, 1.5] cells. (With R = one cell, 8
  /// neighbours at 2 points per cell, the coupled bar of sec. 5.1 did not retrace: 114%.)
  Real smoothing_length = 0;
  ///@{
  /// Artificial viscosity of seed 001 eq. 2.7-2.8 (Cleary's form): alpha (linear in the
  /// approach speed, times the sound speed) and beta (quadratic). Both 0: none, and the SPH
  /// equations are time-reversible (sec. 5.1 runs without it).
  Real viscosity_alpha = 0.5;
  Real viscosity_beta = 0;
  ///@}
  /// Bonet and Lok's (1999) corrected kernel gradient C_a grad W with C_a = (sum_b V_b (x_b -
  /// x_a) (x) grad W)^-T: the velocity gradient of a linear field is exact also where the
  /// kernel is cut off (free surfaces, thin strips), and momentum and energy stay conserved (see
  /// sph_step.cpp). false: the seed's plain gradients (eq. 2.4, 2.6, 2.9).
  bool corrected_gradient = true;

  /// Whether the scene has SPH particles.
  bool enabled() const { return !regions.empty() || !bodies.empty(); }
};

/// Why a world of this cell size cannot take d (empty when it can), naming the key: the smoothing
/// length's range and the viscosity factors'. The one check, for the scene parser and World;
/// what SPH particles may not meet (USL, some coupling schemes) is the exclusions' table's.
Problem sphProblem(const SphDef& d, Real cell_size);

}  // namespace mpm_sdem
