/// \file
/// The velocity's divergence averaged over the grid's nodes before the stress update: an
/// anti-locking projection for explicit MPM (issue 90).
#pragma once

#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"

namespace mpm_sdem {

struct Tiles;

/// B-bar for the velocity gradient, after the F-bar of Zhao, Jiang, Choo et al. (2023,
/// "Circumventing volumetric locking in explicit material point methods"): each point's
/// divergence tr L_p is replaced by the volume-weighted mean of the divergences around it,
/// projected onto the nodes and interpolated back,
///   d_I = sum_p S_Ip V_p tr L_p / sum_p S_Ip V_p,   dbar_p = sum_I S_Ip d_I,
///   Lbar_p = L_p + (dbar_p - tr L_p) / 2 I  (plane strain: the two in-plane directions).
/// A plastic flow that keeps its volume (zero dilation) then asks each point for no more than
/// the mean volume change of its neighbourhood, instead of one per point that the grid's few
/// velocities cannot meet (the locking that stiffens isochoric flow at coarse cells). The total
/// volume rate sum_p V_p tr L_p is unchanged, the deviatoric part and the spin untouched.
class VolumetricAverage {
 public:
  /// Each material point's L_p from the pre-kick grid velocity (vel0), then its divergence
  /// averaged as above. Points of the grid sums only (T), SPH band excluded.
  void apply(KernelType kernel, Particles& P, const Grid& G, const Tiles& T);

 private:
  std::vector<Real> volume_, rate_;  ///< per node: sum S V (m^2), sum S V tr L (m^2/s)
};

}  // namespace mpm_sdem
