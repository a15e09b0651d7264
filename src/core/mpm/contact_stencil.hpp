// One contact's force on the grid as a linear map (internal header of the core library).
#pragma once

#include <vector>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::detail {

// How one contact's force reaches the nodes, as a linear map: node I of the stencil gets
// A_I f for a force f on the material. Built once for a step of multi-rate contact, it spreads
// each substep's impulse, and its transpose gives the velocity that force does work against,
// u = sum_I A_I^T v_I: the spread and the reading are then one another's adjoint, so the
// substepped springs exchange exactly the work the grid receives (no energy from the transfer).
struct ContactStencil {
  static constexpr int kMaxNodes = 16;  // 4 x 4, the cubic B-spline's support
  // A_I = w_I (1 + r_I lever^T): a weight, and for a force off the point's centre a couple
  // spread as forces along r_I (spreadParticleForce).
  int count = 0;
  int node[kMaxNodes];
  Real w[kMaxNodes];
  Real rx[kMaxNodes], ry[kMaxNodes];
  Vec2 lever{0, 0};
  // Adds A_I f to (fx, fy).
  void spread(std::vector<Real>& fx, std::vector<Real>& fy, const Vec2& f) const {
    const Real c = lever.dot(f);
    for (int k = 0; k < count; ++k) {
      fx[node[k]] += w[k] * (f.x() + c * rx[k]);
      fy[node[k]] += w[k] * (f.y() + c * ry[k]);
    }
  }
  // sum_I A_I^T value(I).
  template <class V>
  Vec2 gather(V&& value) const {
    Vec2 u(0, 0);
    Real turn = 0;
    for (int k = 0; k < count; ++k) {
      const Vec2 v = value(node[k]);
      u += w[k] * v;
      turn += w[k] * (rx[k] * v.x() + ry[k] * v.y());
    }
    return u + turn * lever;
  }
};

}  // namespace mpm_sdem::detail
