// Scalar and small vector types of the physics core. SI units throughout (REP 103).
#pragma once

#include <Eigen/Core>
#include <cmath>

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

// v turned counter-clockwise by angle (rad): a block frame's vector in the world frame.
inline Vec2 rotated(Real angle, const Vec2& v) {
  const Real c = std::cos(angle), s = std::sin(angle);
  return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

namespace detail {
// Reads and writes the state that outlives a step, for checkpoints (core/checkpoint.cpp). A class
// holding such state befriends it and lists those members in a stateIo(archive) template, next to
// the members themselves.
struct CheckpointAccess;
}  // namespace detail

}  // namespace mpm_sdem
