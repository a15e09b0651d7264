// The material's height profile (core/terrain.hpp), the node's ~terrain: exact on a flat bed
// filled to a lattice line, and within its stated bound on a slope.
#include <gtest/gtest.h>

#include <cmath>

#include "helpers.hpp"
#include "mpm_sdem/core/terrain.hpp"

using namespace mpm_sdem;

namespace {

// A bed of elastic material on the floor of a 1 m x 0.5 m domain, cells of h, 2 x 2 points per
// cell, with the given top outline (left to right).
World bed(Real h, const std::vector<Vec2>& top) {
  WorldDef d = test::box(Vec2(0, 0), Vec2(1, 0.5), h);
  d.materials.push_back(test::elastic(1800, 1e7, 0.3));
  BodyDef b;
  b.name = "bed";
  b.shape.type = ShapeType::kPolygon;
  b.shape.vertices = {Vec2(top.back().x(), 0), Vec2(top.front().x(), 0)};
  b.shape.vertices.insert(b.shape.vertices.end(), top.begin(), top.end());
  b.points_per_cell = 2;
  d.bodies.push_back(b);
  return World(d);
}

}  // namespace

// Filled to y = 0.2 m, a lattice line at 5 mm spacing: every column's top is the bed's.
TEST(Terrain, FlatBedIsExact) {
  const World w = bed(0.01, {Vec2(0.1, 0.2), Vec2(0.9, 0.2)});
  std::vector<Real> height;
  heightProfile(w.particles(), 0, 0.02, 50, height);
  for (int c = 0; c < 50; ++c) {
    const Real x = (c + 0.5) * 0.02;
    if (x < 0.1 || x > 0.9) {
      EXPECT_TRUE(std::isnan(height[c])) << "empty column " << c;
    } else {
      EXPECT_NEAR(height[c], 0.2, 1e-12) << "column " << c;
    }
  }
}

// A 20-degree slope from (0.1, 0.1) to (0.9, 0.1 + 0.8 tan 20): each column within
// d / 2 + s dx / 2 of the surface at its centre (terrain.hpp), d = 5 mm, dx = 2 cm; and the
// columns together give the slope (least squares) within 1%. Measured: worst 4.96 mm of the
// bound's 6.14 mm; slope 0.36374 against 0.36397.
TEST(Terrain, SlopeWithinTheLatticeBound) {
  const Real s = std::tan(20 * M_PI / 180), dx = 0.02, d = 0.005;
  const World w = bed(0.01, {Vec2(0.1, 0.1), Vec2(0.9, 0.1 + 0.8 * s)});
  std::vector<Real> height;
  heightProfile(w.particles(), 0, dx, 50, height);
  Real worst = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (int c = 0; c < 50; ++c) {
    const Real x = (c + 0.5) * dx;
    if (x < 0.1 + dx || x > 0.9 - dx) continue;  // columns the bed's sides cut
    const Real err = height[c] - (0.1 + (x - 0.1) * s);
    worst = std::fmax(worst, std::abs(err));
    sx += x, sy += height[c], sxx += x * x, sxy += x * height[c], ++n;
  }
  const Real fitted = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  std::printf("worst %.2f mm (bound %.2f mm); slope %.5f against %.5f\n", 1e3 * worst,
              1e3 * (d / 2 + s * dx / 2), fitted, s);
  EXPECT_LE(worst, d / 2 + s * dx / 2);
  EXPECT_NEAR(fitted, s, 0.01 * s);
}
