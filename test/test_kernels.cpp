// Test 1: every kernel is a partition of unity with zero gradient sum, reproduces linear
// functions (which APIC and the stress divergence rely on), and its derivative is the derivative
// of its weight. Tolerances: round-off of sums of O(1) terms (1e-12), and the O(eps^2) error of
// a central difference with eps = 1e-6 (1e-6).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "mpm/node_rows.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"

using namespace mpm_sdem;

namespace {

template <class K>
void checkKernel(Real lp) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<Real> pos(3.0, 40.0);
  for (int trial = 0; trial < 2000; ++trial) {
    const Real x = pos(rng), y = pos(rng);
    Stencil1D sx, sy;
    K::stencil(x, lp, sx);
    K::stencil(y, lp, sy);
    Real sum = 0, gx = 0, gy = 0, mx = 0, my = 0, second = 0;
    for (int j = 0; j < K::kSupport; ++j) {
      for (int i = 0; i < K::kSupport; ++i) {
        const Real w = sx.w[i] * sy.w[j];
        EXPECT_GE(w, -1e-15);
        sum += w;
        gx += sx.dw[i] * sy.w[j];
        gy += sx.w[i] * sy.dw[j];
        mx += w * (sx.base + i);
        my += w * (sy.base + j);
      }
      second += sx.w[j] * (sx.base + j - x) * (sx.base + j - x);
    }
    ASSERT_NEAR(sum, 1.0, 1e-12) << "x=" << x << " y=" << y;
    ASSERT_NEAR(gx, 0.0, 1e-12);
    ASSERT_NEAR(gy, 0.0, 1e-12);
    ASSERT_NEAR(mx, x, 1e-12);  // sum_I w_I x_I = x_p
    ASSERT_NEAR(my, y, 1e-12);
    ASSERT_NEAR(second, sx.second_moment, 1e-12);
    // Derivative against a central difference of the weights of the same nodes.
    const Real eps = 1e-6;
    Stencil1D a, b;
    K::stencil(x + eps, lp, a);
    K::stencil(x - eps, lp, b);
    for (int i = 0; i < K::kSupport; ++i) {
      auto weightAt = [&](const Stencil1D& s, int node) {
        const int k = node - s.base;
        return k >= 0 && k < K::kSupport ? s.w[k] : 0.0;
      };
      const int node = sx.base + i;
      const Real fd = (weightAt(a, node) - weightAt(b, node)) / (2 * eps);
      ASSERT_NEAR(sx.dw[i], fd, 1e-6) << "node offset " << node - x;
    }
  }
}

}  // namespace

TEST(Kernels, QuadraticBSpline) {
  checkKernel<QuadraticBSpline>(0);
}
TEST(Kernels, CubicBSpline) {
  checkKernel<CubicBSpline>(0);
}
TEST(Kernels, GimpTwoPointsPerCell) {
  checkKernel<Gimp>(0.25);
}
TEST(Kernels, GimpOnePointPerCell) {
  checkKernel<Gimp>(0.5);
}
TEST(Kernels, GimpFourPointsPerCell) {
  checkKernel<Gimp>(0.125);
}

// The sweeps' four-node windows (node_rows.hpp) against the kernels' own stencils: the window
// starts at the node before the point's cell, so that it stays within the reach the tiles'
// colouring allows (a lane past it would race with another thread's tile); every stencil node
// has its weight and derivative in its lane (1e-15: the quadratic's lanes evaluate the same
// polynomials in x_I - x_p, a rounding apart) and the other lanes are exactly zero. Positions at
// and next to the nodes and half-cells, where the quadratic's pieces and base change, are
// included.
template <class K>
void checkWindow(Real lp) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<Real> pos(3.0, 40.0);
  std::vector<Real> xs;
  for (int trial = 0; trial < 2000; ++trial) xs.push_back(pos(rng));
  for (Real c : {5.0, 17.0}) {
    for (Real f : {0.0, 0.25, 0.5, 0.75}) {
      const Real x = c + f;
      xs.insert(xs.end(), {x, std::nextafter(x, 0.0), std::nextafter(x, 100.0)});
    }
  }
  for (const Real x : xs) {
    Stencil1D s;
    K::stencil(x, lp, s);
    const detail::HWY_NAMESPACE::Window win = detail::HWY_NAMESPACE::window<K>(x, lp);
    ASSERT_EQ(win.first, static_cast<int>(std::floor(x)) - 1) << "x=" << x;
    ASSERT_GE(s.base, win.first) << "x=" << x;
    ASSERT_LE(s.base + K::kSupport, win.first + 4) << "x=" << x;
    EXPECT_EQ(win.second_moment, s.second_moment);
    for (int lane = 0; lane < 4; ++lane) {
      const int node = win.first + lane, k = node - s.base;
      EXPECT_EQ(win.r[lane], node - x);
      if (k >= 0 && k < K::kSupport) {
        EXPECT_NEAR(win.w[lane], s.w[k], 1e-15) << "x=" << x << " node " << node;
        EXPECT_NEAR(win.dw[lane], s.dw[k], 1e-15) << "x=" << x << " node " << node;
      } else {
        EXPECT_EQ(win.w[lane], 0.0) << "x=" << x << " node " << node;
        EXPECT_EQ(win.dw[lane], 0.0) << "x=" << x << " node " << node;
      }
    }
  }
}

TEST(Kernels, WindowsHoldTheStencils) {
  checkWindow<QuadraticBSpline>(0);
  checkWindow<CubicBSpline>(0);
  checkWindow<Gimp>(0.25);
  checkWindow<Gimp>(0.5);
  checkWindow<Gimp>(0.125);
}

// Gao et al. (cited in seed 000 sec. 2.1): GIMP with l_p = L/2 equals the quadratic B-spline.
TEST(Kernels, GimpWithHalfCellEqualsQuadraticBSpline) {
  for (Real x = 5.0; x < 7.0; x += 0.0173) {
    Stencil1D g, q;
    Gimp::stencil(x, 0.5, g);
    QuadraticBSpline::stencil(x, 0, q);
    for (int node = q.base; node < q.base + 3; ++node) {
      const int kg = node - g.base;
      const Real wg = kg >= 0 && kg < 3 ? g.w[kg] : 0.0;
      EXPECT_NEAR(wg, q.w[node - q.base], 1e-12);
    }
  }
}
