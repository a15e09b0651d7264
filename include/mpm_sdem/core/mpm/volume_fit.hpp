/// \file
/// Volume-consistent points (SolverDef::volume_fit, docs/method.md, Volume-consistent points).
/// A material point stands for the volume V_p = J_p V0_p, and the grid integrates with the points
/// as its quadrature: node i sees the volume v_i = sum_p S_ip V_p, which for points that tile
/// their body equals the part of the node's support inside the domain, its capacity
/// V_i = integral of S_i (taken as a lattice of the bodies' points fills it, so that a lattice at
/// rest reads exactly full, walls included). Under sustained shear the points drift from that
/// tiling: in issue 41's chute they crowd in bands while their J says they expanded. The fit
/// measures each node's over-fill H_i = max(0, v_i - V_i) and moves the flowing points down the
/// gradient of Phi = (1/2) sum_i H_i^2, by the Gauss-Newton step that minimises Phi linearised
/// along that gradient (no rate to choose), each point at most as far as its neighbours shear past
/// it in the step, l_p gamma_dot_p dt (l_p = sqrt(V_p)): material that does not shear is left
/// alone. Only positions change: mass, momentum, J and stress are the points' own, untouched.
#pragma once

#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The nodes' capacities and the scratch of the fit (see the file's comment).
class VolumeFit {
 public:
  /// What a fit or a measurement found.
  struct Result {
    Real largest_overfill = 0;  ///< max_i max(0, v_i - V_i) / h^2 over the nodes
    long moved = 0;             ///< points moved (0 for a measurement)
  };

  /// The capacities of the grid's nodes for the domain [lo, hi] (periodic in x: every column
  /// whole) under kernel, as a lattice of points_per_cell^2 points per cell fills them.
  void init(const Grid& g, KernelType kernel, const Vec2& lo, const Vec2& hi, bool periodic_x,
            int points_per_cell);
  /// The nodes' over-fill from every material point's volume (SPH particles not counted).
  Result measure(const Particles& P, const Grid& g);
  /// The fit over dt: the over-fill, then the points whose material flows (flows[material],
  /// awake) moved as the file's comment says, inside [lo, hi] (wrapped in x when periodic).
  /// The over-fill returned is the one before the move.
  Result fit(Particles& P, const Grid& g, const std::vector<char>& flows, Real dt);

  /// Node i's capacity V_i (m^2) in the grid's flat index.
  Real capacity(int i, int j) const { return capacity_x_[i] * capacity_y_[j]; }

 private:
  template <class K>
  Result run(Particles& P, const Grid& g, const std::vector<char>* flows, Real dt);

  KernelType kernel_ = KernelType::kQuadraticBSpline;
  Vec2 lo_{0, 0}, hi_{0, 0};
  bool periodic_x_ = false;
  std::vector<Real> capacity_x_, capacity_y_;  ///< per node column and row (m)
  std::vector<Real> fill_;                     ///< v_i, then H_i (m^2)
  std::vector<Real> push_;                     ///< (J g)_i = sum_p V_p grad S_ip . g_p (m^4)
  std::vector<Real> gx_, gy_;                  ///< per point: dPhi / dx_p
};

}  // namespace mpm_sdem
