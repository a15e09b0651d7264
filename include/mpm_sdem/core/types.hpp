/// \file
/// Scalar and small vector types of the physics core. SI units throughout (REP 103).
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace mpm_sdem {

// Double precision by default: the momentum-conservation tests resolve drifts of 1e-10 per step.
// A build may choose single precision (CMake option MPM_SDEM_SINGLE_PRECISION): half the memory
// traffic per point, at the accuracy cost measured in bench/README.md. Box2D is
// single precision either way.
/// The physics' floating-point type: double, or float in a single-precision build
/// (MPM_SDEM_SINGLE_PRECISION).
#ifdef MPM_SDEM_SINGLE_PRECISION
using Real = float;
#else
using Real = double;
#endif
/// The simulation clock: double in every build. A float clock stops resolving the step (its ulp is
/// 1e-6 s at 10 s, a 3% error on a 30 us step) and can stall a run short of its end.
using Time = double;
/// A vector of the plane (x right, y up).
using Vec2 = Eigen::Matrix<Real, 2, 1>;
/// A 2 x 2 matrix.
using Mat2 = Eigen::Matrix<Real, 2, 2>;

/// The z component of a x b: the moment of a force b at lever a (N m/m), twice a triangle's area.
inline Real cross(const Vec2& a, const Vec2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// v turned counter-clockwise by angle (rad): a block frame's vector in the world frame.
inline Vec2 rotated(Real angle, const Vec2& v) {
  const Real c = std::cos(angle), s = std::sin(angle);
  return Vec2(c * v.x() - s * v.y(), s * v.x() + c * v.y());
}

namespace detail {
/// Reads and writes the state that outlives a step, for checkpoints (core/checkpoint.cpp). A class
/// holding such state befriends it and lists those members in a stateIo(archive) template, next to
/// the members themselves.
struct CheckpointAccess;
}  // namespace detail

}  // namespace mpm_sdem
