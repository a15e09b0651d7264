// SPH kernels in 2D as functions of the distance r, both with support radius R = 2 h_s. Each
// returns W (1/m^2) and its radial derivative dW/dr (1/m^3); the gradient with respect to x_a
// is dW/dr (x_a - x_b) / r. Internal header of the core library.
#pragma once

#include <cmath>

#include "mpm_sdem/core/sph/sph.hpp"

namespace mpm_sdem::detail {

struct KernelValue {
  Real w = 0, dw = 0;
};

// Monaghan's (1992) cubic spline, q = r / h_s in [0, 2).
struct SphCubicSpline {
  static KernelValue eval(Real r, Real R) {
    const Real hs = Real(0.5) * R, q = r / hs;
    const Real norm = Real(10) / (7 * M_PI * hs * hs);
    if (q < 1)
      return {norm * (1 - Real(1.5) * q * q + Real(0.75) * q * q * q),
              norm / hs * (-3 * q + Real(2.25) * q * q)};
    if (q < 2) {
      const Real t = 2 - q;
      return {norm * Real(0.25) * t * t * t, -norm / hs * Real(0.75) * t * t};
    }
    return {};
  }
};

// Wendland's C2 function, q = r / R in [0, 1): W = 7 / (pi R^2) (1 - q)^4 (1 + 4 q).
struct SphWendlandC2 {
  static KernelValue eval(Real r, Real R) {
    const Real q = r / R;
    if (q >= 1) return {};
    const Real norm = Real(7) / (M_PI * R * R), t = 1 - q, t3 = t * t * t;
    return {norm * t3 * t * (1 + 4 * q), -norm / R * 20 * q * t3};
  }
};

// Call f(Kernel{}) for the scene's kernel: one dispatch per stage, none per pair.
template <class F>
void withSphKernel(SphKernel k, F&& f) {
  if (k == SphKernel::kWendlandC2)
    f(SphWendlandC2{});
  else
    f(SphCubicSpline{});
}

}  // namespace mpm_sdem::detail
