/// \file
/// Grid weighting functions S_Ip (seed 000, Appendix A). Each kernel is separable: the 2D weight is
/// the product of two 1D stencils. Coordinates are in grid units (x / h, measured from node 0), so
/// the same code serves every cell size; gradients are per grid unit and are divided by h by the
/// caller.
#pragma once

#include <cmath>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The grid's shape functions (scene key solver.kernel).
enum class KernelType { kQuadraticBSpline, kCubicBSpline, kGimp };

/// One axis of a particle's stencil: the first node index, the weights and their derivatives for
/// kMaxSupport consecutive nodes, and the second moment sum_I w_I (x_I - x_p)^2 (grid units^2),
/// which is the diagonal of the APIC inertia matrix D_p (seed 000 eq. 29).
struct Stencil1D {
  static constexpr int kMaxSupport = 4;  ///< the widest kernel's nodes per axis
  int base = 0;                          ///< index of the first node
  Real w[kMaxSupport] = {0, 0, 0, 0};    ///< weights
  Real dw[kMaxSupport] = {0, 0, 0, 0};   ///< their derivatives (1/grid unit)
  Real second_moment = 0;                ///< grid units^2
};

/// Quadratic B-spline, support 3 nodes. D_p = h^2/4 I exactly (seed 000 eq. 29, quadratic case).
struct QuadraticBSpline {
  static constexpr int kSupport = 3;  ///< nodes per axis
  /// The stencil of a particle at grid coordinate xg (its half size in grid units, used by GIMP
  /// only).
  [[gnu::always_inline]] static inline void stencil(Real xg, Real /*half_size*/, Stencil1D& s) {
    s.base = static_cast<int>(std::floor(xg - Real(0.5)));
    const Real f = xg - s.base;  // in [0.5, 1.5)
    const Real a = Real(1.5) - f, b = f - Real(1), c = f - Real(0.5);
    s.w[0] = Real(0.5) * a * a;
    s.w[1] = Real(0.75) - b * b;
    s.w[2] = Real(0.5) * c * c;
    s.dw[0] = -a;
    s.dw[1] = Real(-2) * b;
    s.dw[2] = c;
    s.second_moment = Real(0.25);
  }
};

/// Cubic B-spline, support 4 nodes. This is the polynomial printed as eq. A4 of seed 000 (which the
/// seed labels "quadratic"; the formula is the cubic B-spline). D_p = h^2/3 I.
struct CubicBSpline {
  static constexpr int kSupport = 4;  ///< nodes per axis
  /// The stencil of a particle at grid coordinate xg (its half size in grid units, used by GIMP
  /// only).
  [[gnu::always_inline]] static inline void stencil(Real xg, Real /*half_size*/, Stencil1D& s) {
    s.base = static_cast<int>(std::floor(xg)) - 1;
    for (int k = 0; k < 4; ++k) {
      const Real r = xg - (s.base + k);  // particle minus node, in (-2, 2)
      const Real q = std::abs(r);
      const Real sgn = r >= 0 ? Real(1) : Real(-1);
      if (q < 1) {
        s.w[k] = Real(0.5) * q * q * q - q * q + Real(2) / 3;
        s.dw[k] = sgn * (Real(1.5) * q * q - Real(2) * q);
      } else {
        const Real t = Real(2) - q;
        s.w[k] = t * t * t / 6;
        s.dw[k] = -sgn * Real(0.5) * t * t;
      }
    }
    s.second_moment = Real(1) / 3;
  }
};

/// GIMP with a constant characteristic function over a square of half size lp and linear nodal
/// shape functions, seed 000 eq. A2 (in grid units, L = 1). The printed fifth case of A2 has
/// "1 + xi"; continuity with the neighbouring cases requires 1 - xi, which is what is used here.
/// Requires lp <= 1/2, so that at most 3 nodes per axis are touched.
struct Gimp {
  static constexpr int kSupport = 3;  ///< nodes per axis
  /// The weight at node distance xi (grid units) for half size lp, and its derivative.
  static inline Real weight(Real xi, Real lp, Real& dweight) {
    const Real q = std::abs(xi);
    const Real sgn = xi >= 0 ? Real(1) : Real(-1);
    if (q >= Real(1) + lp) {
      dweight = 0;
      return 0;
    }
    if (q > Real(1) - lp) {
      const Real t = Real(1) + lp - q;
      dweight = -sgn * t / (Real(2) * lp);
      return t * t / (Real(4) * lp);
    }
    if (q > lp) {
      dweight = -sgn;
      return Real(1) - q;
    }
    dweight = -xi / lp;
    return Real(1) - (xi * xi + lp * lp) / (Real(2) * lp);
  }
  /// The stencil of a particle at grid coordinate xg (its half size in grid units, used by GIMP
  /// only).
  [[gnu::always_inline]] static inline void stencil(Real xg, Real lp, Stencil1D& s) {
    // First node strictly inside the support (x_p - 1 - lp, x_p + 1 + lp).
    s.base = static_cast<int>(std::floor(xg - Real(1) - lp)) + 1;
    s.second_moment = 0;
    for (int k = 0; k < 3; ++k) {
      const Real xi = xg - (s.base + k);
      s.w[k] = weight(xi, lp, s.dw[k]);
      s.second_moment += s.w[k] * xi * xi;
    }
  }
};

}  // namespace mpm_sdem
