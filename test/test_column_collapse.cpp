// Test 7: collapse of a Drucker-Prager column (aspect ratio H/W = 2, phi = 30 deg, c = 0) on a
// sticky floor. The deposit ends at rest (max speed < 1 cm/s after 1.5 s, several times the
// collapse time sqrt(H/g) = 0.14 s) with a free-surface slope below the friction angle, and the
// total mass is the initial mass exactly (material points carry constant masses; the grid mass
// equals their sum to round-off).
#include <gtest/gtest.h>

#include <map>

#include "helpers.hpp"

using namespace mpm_sdem;

TEST(ColumnCollapse, DepositAtRestBelowFrictionAngle) {
  const Real W = 0.1, H = 0.2, phi = 30;
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.5, 0.25), 0.005);
  def.domain.bottom.type = WallType::kSticky;
  def.materials.push_back(test::druckerPrager(1500, 2e5, 0.3, phi, 0));
  def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(W, H), 2));
  World w(def);
  const Real mass0 = measure(w).mass;
  runUntil(w, 1.5);
  const Diagnostics d = measure(w);
  EXPECT_EQ(d.mass, mass0);
  Real grid_mass = 0;
  for (Real m : w.grid().mass) grid_mass += m;
  EXPECT_NEAR(grid_mass, mass0, 1e-12 * mass0);
  EXPECT_LT(d.max_speed, 0.01);

  // Free surface: the highest point in each column of cells; the slope between the points where
  // the surface is at 80% and at 20% of the deposit's height.
  std::map<int, Real> top;
  const Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    const int bin = static_cast<int>(P.x[p] / def.cell_size);
    top[bin] = std::max(top.count(bin) ? top[bin] : Real(0), P.y[p]);
  }
  Real peak = 0;
  for (const auto& [bin, y] : top) peak = std::max(peak, y);
  Real x80 = 0, x20 = 0;
  for (const auto& [bin, y] : top) {
    if (y >= 0.8 * peak) x80 = (bin + 0.5) * def.cell_size;
    if (y >= 0.2 * peak) x20 = (bin + 0.5) * def.cell_size;
  }
  ASSERT_GT(x20, x80);
  const Real slope = std::atan(0.6 * peak / (x20 - x80)) * 180 / M_PI;
  EXPECT_LT(slope, phi) << "deposit height " << peak << " m";
  EXPECT_GT(slope, 5.0) << "the deposit flattened completely";
  EXPECT_LT(peak, H) << "the column did not collapse";
}
