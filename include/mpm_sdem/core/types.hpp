// Scalar and small vector types of the physics core. SI units throughout (REP 103).
#pragma once

#include <Eigen/Core>

namespace mpm_sdem {

// Double precision: the momentum-conservation tests resolve drifts of 1e-10 per step, and the
// precision trade-off is measured before it is changed (issue 5).
using Real = double;
using Vec2 = Eigen::Matrix<Real, 2, 1>;

}  // namespace mpm_sdem
