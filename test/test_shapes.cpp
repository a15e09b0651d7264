// Shapes a body is filled from: their area moments against closed forms, and the points' volumes
// (pointVolumes) carrying the shape's area, centroid and polar moment wherever the outline sits on
// the lattice. Tolerances: round-off of sums over a few thousand points (1e-12 relative).
#include <gtest/gtest.h>

#include <cmath>

#include "mpm_sdem/core/mpm/shapes.hpp"

using namespace mpm_sdem;

namespace {

AreaMoments pointMoments(const std::vector<Vec2>& points, const std::vector<Real>& volumes,
                         Real spacing) {
  AreaMoments m;
  for (std::size_t p = 0; p < points.size(); ++p) {
    m.area += volumes[p];
    m.centroid += volumes[p] * points[p];
  }
  m.centroid /= m.area;
  // Each point stands for a square of side spacing, whose own polar moment is V spacing^2 / 6.
  for (std::size_t p = 0; p < points.size(); ++p)
    m.polar += volumes[p] * ((points[p] - m.centroid).squaredNorm() + spacing * spacing / 6);
  return m;
}

ShapeDef polygon(std::vector<Vec2> v) {
  ShapeDef s;
  s.type = ShapeType::kPolygon;
  s.vertices = std::move(v);
  return s;
}

}  // namespace

TEST(AreaMoments, ClosedForms) {
  ShapeDef rect;
  rect.min = Vec2(1, 2);
  rect.max = Vec2(4, 3);
  const AreaMoments r = areaMoments(rect);
  EXPECT_NEAR(r.area, 3, 1e-14);
  EXPECT_NEAR((r.centroid - Vec2(2.5, 2.5)).norm(), 0, 1e-14);
  EXPECT_NEAR(r.polar, 3 * (9 + 1) / 12.0, 1e-14);  // A (w^2 + h^2) / 12

  // The same rectangle as a polygon turned by 30 degrees about its centre, clockwise.
  std::vector<Vec2> v;
  const Real c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  for (const Vec2& d : {Vec2(1.5, 0.5), Vec2(1.5, -0.5), Vec2(-1.5, -0.5), Vec2(-1.5, 0.5)})
    v.push_back(Vec2(2.5, 2.5) + Vec2(c * d.x() - s * d.y(), s * d.x() + c * d.y()));
  const AreaMoments p = areaMoments(polygon(v));
  EXPECT_NEAR(p.area, r.area, 1e-13);
  EXPECT_NEAR((p.centroid - r.centroid).norm(), 0, 1e-13);
  EXPECT_NEAR(p.polar, r.polar, 1e-13);

  // An L (concave): a 2 x 1 bar with a 1 x 1 square on its left end, by parts.
  const AreaMoments l = areaMoments(polygon({{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}}));
  const Vec2 c1(1, 0.5), c2(0.5, 1.5), cl = (2 * c1 + c2) / 3;
  const Real polar =
      2 * 5 / 12.0 + 2 * (c1 - cl).squaredNorm() + 2 / 12.0 + (c2 - cl).squaredNorm();
  EXPECT_NEAR(l.area, 3, 1e-14);
  EXPECT_NEAR((l.centroid - cl).norm(), 0, 1e-14);
  EXPECT_NEAR(l.polar, polar, 1e-14);
}

// The lattice alone (every point spacing^2) is off at the five offsets by: area 1.0003-1.0059,
// centroid up to 0.117 mm, polar moment 1.0007-1.0117 of the disk's (printed below).
TEST(PointVolumes, CarryTheDisksMomentsAtEveryLatticeOffset) {
  const Real h = 0.005, s = h / 2, R = 0.05;
  for (Real offset : {0.0, 0.2, 0.4, 0.6, 0.8}) {
    ShapeDef disk;
    disk.type = ShapeType::kDisk;
    disk.center = Vec2(0.15, 0.15) + Vec2::Constant(offset * h);
    disk.radius = R;
    const std::vector<Vec2> points = fillPoints(disk, Vec2(0, 0), h, 2);
    const std::vector<Real> volumes = pointVolumes(disk, points, s);
    const AreaMoments want = areaMoments(disk);
    const AreaMoments lattice = pointMoments(points, std::vector<Real>(points.size(), s * s), s);
    const AreaMoments got = pointMoments(points, volumes, s);
    std::printf("offset %.1f: lattice area %.5f, centroid off by %.3f mm, polar %.5f\n", offset,
                lattice.area / want.area, 1e3 * (lattice.centroid - want.centroid).norm(),
                lattice.polar / want.polar);
    EXPECT_NEAR(got.area / want.area, 1, 1e-12);
    EXPECT_NEAR((got.centroid - want.centroid).norm() / R, 0, 1e-12);
    EXPECT_NEAR(got.polar / want.polar, 1, 1e-12);
    for (std::size_t p = 0; p < points.size(); ++p) {
      if (outlineDistance(disk, points[p]) >= s) {
        EXPECT_EQ(volumes[p], s * s) << "an interior point keeps its lattice volume";
      } else {
        EXPECT_GE(volumes[p], 0.5 * s * s);
        EXPECT_LE(volumes[p], 1.5 * s * s);
      }
    }
  }
}

TEST(PointVolumes, StraightEdgesAndTinyDisksKeepTheLatticeVolumes) {
  ShapeDef column;  // edges on the lattice: the staircase is exact
  column.min = Vec2(0, 0);
  column.max = Vec2(0.1, 0.2);
  const std::vector<Vec2> points = fillPoints(column, Vec2(0, 0), 0.01, 2);
  for (Real v : pointVolumes(column, points, 0.005)) EXPECT_EQ(v, 0.005 * 0.005);

  ShapeDef off = column;  // off the lattice: still spacing^2 (a strip, not a reweighting)
  off.min = Vec2(0.0013, 0.0021);
  off.max = Vec2(0.1037, 0.2008);
  const std::vector<Vec2> shifted = fillPoints(off, Vec2(0, 0), 0.01, 2);
  for (Real v : pointVolumes(off, shifted, 0.005)) EXPECT_EQ(v, 0.005 * 0.005);

  ShapeDef speck;  // a disk of a few points: no reweighting within bounds, so none
  speck.type = ShapeType::kDisk;
  speck.center = Vec2(0.0512, 0.0497);
  speck.radius = 0.004;
  const std::vector<Vec2> few = fillPoints(speck, Vec2(0, 0), 0.01, 2);
  ASSERT_GT(few.size(), 0u);
  for (Real v : pointVolumes(speck, few, 0.005)) EXPECT_EQ(v, 0.005 * 0.005);
}
