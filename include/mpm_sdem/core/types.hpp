// Scalar and small vector types of the physics core. SI units throughout (REP 103).
#pragma once

#include <Eigen/Core>

namespace mpm_sdem {

// Double precision: the momentum-conservation tests resolve drifts of 1e-10 per step, and the
// precision trade-off is measured before it is changed (issue 5).
using Real = double;
using Vec2 = Eigen::Matrix<Real, 2, 1>;
using Mat2 = Eigen::Matrix<Real, 2, 2>;

// The z component of a x b: the moment of a force b at lever a (N m/m), twice a triangle's area.
inline Real cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

}  // namespace mpm_sdem
