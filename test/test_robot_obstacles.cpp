// A robot's links as blocks (robot/robot_obstacles.hpp): the sections of URDF's solids by the
// simulation plane against their closed forms, the blocks' outlines against the sections, a
// two-link arm's blocks where its rest pose puts them, and a description that cannot become
// blocks refused with the link's name.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "mpm_sdem/robot/mesh_hull.hpp"
#include "mpm_sdem/robot/plane_section.hpp"
#include "mpm_sdem/robot/robot_obstacles.hpp"

using namespace mpm_sdem;
using namespace mpm_sdem::robot;

namespace {

double area(const std::vector<Vec2>& polygon) {
  double twice = 0;
  for (std::size_t i = 0; i < polygon.size(); ++i) {
    const Vec2 &a = polygon[i], &b = polygon[(i + 1) % polygon.size()];
    twice += a.x() * b.y() - a.y() * b.x();
  }
  return twice / 2;
}

// A spheropolygon's area: its core, the strips along its edges and the corners' disc.
double outlineArea(const BlockDef& b) {
  double perimeter = 0;
  for (std::size_t i = 0; b.core.size() > 1 && i < b.core.size(); ++i)
    perimeter += (b.core[(i + 1) % b.core.size()] - b.core[i]).norm();
  return (b.core.size() > 2 ? area(b.core) : 0) + perimeter * b.rounding +
         M_PI * b.rounding * b.rounding;
}

Eigen::Isometry3d at(double x, double y, double z, const Eigen::Matrix3d& r) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translate(Eigen::Vector3d(x, y, z));
  t.rotate(r);
  return t;
}

Eigen::Matrix3d about(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

}  // namespace

// A box through the plane: its rectangle; turned 45 deg about x, the chord of its 0.1 x 0.3 face
// through the centre, 0.1 / cos 45 deg; a box above the plane misses it by its gap.
TEST(PlaneSection, BoxesGiveTheirRectangles) {
  Solid box;
  box.size = Eigen::Vector3d(0.2, 0.1, 0.3);
  const Section flat = sectionByPlane(box, Eigen::Isometry3d::Identity());
  ASSERT_EQ(flat.polygon.size(), 4u);
  EXPECT_NEAR(area(flat.polygon), 0.02, 1e-15);
  const Section turned =
      sectionByPlane(box, at(0.5, -0.2, 0, about(Eigen::Vector3d::UnitX(), M_PI / 4)));
  ASSERT_EQ(turned.polygon.size(), 4u);
  EXPECT_NEAR(area(turned.polygon), 0.2 * 0.1 * std::sqrt(2.0), 1e-14);
  for (const Vec2& v : turned.polygon) {
    EXPECT_NEAR(std::abs(v.x() - 0.5), 0.1, 1e-14);
    EXPECT_NEAR(std::abs(v.y() + 0.2), 0.05 * std::sqrt(2.0), 1e-14);
  }
  const Section above = sectionByPlane(box, at(0, 0, 0.17, Eigen::Matrix3d::Identity()));
  EXPECT_TRUE(above.empty());
  EXPECT_NEAR(above.gap, 0.02, 1e-15);
}

// A box turned about the plane's normal, at 2,000 angles round the circle: always its rectangle
// of 4 corners (the crossings of its faces' diagonals lie on the edges, and rounding put some a
// hair outside them: 7 corners, a core refused as not convex, before such points were dropped).
TEST(PlaneSection, TurnedBoxesKeepFourCorners) {
  Solid stick;
  stick.size = Eigen::Vector3d(0.35, 0.04, 0.06);
  int wrong = 0;
  for (int k = 0; k < 2000; ++k) {
    const double angle = -M_PI + 2 * M_PI * k / 2000;
    const Section s =
        sectionByPlane(stick, at(0.5, 0.55, 0, about(Eigen::Vector3d::UnitZ(), angle)));
    if (s.polygon.size() != 4 || std::abs(area(s.polygon) - 0.35 * 0.04) > 1e-14) ++wrong;
  }
  EXPECT_EQ(wrong, 0);
}

// A sphere: the disc of radius sqrt(r^2 - d^2); a cylinder normal to the plane: its disc, in
// the plane: its rectangle, at 45 deg: the ellipse of semi-axes r and r / cos 45 deg, from
// inside within r (1 - cos(pi / 64)).
TEST(PlaneSection, RoundSolidsGiveDiscsRectanglesAndEllipses) {
  Solid sphere;
  sphere.kind = Solid::Kind::kSphere;
  sphere.radius = 0.1;
  const Section disc = sectionByPlane(sphere, at(0.3, 0.4, -0.06, Eigen::Matrix3d::Identity()));
  EXPECT_NEAR(disc.radius, 0.08, 1e-15);
  EXPECT_NEAR((disc.centre - Vec2(0.3, 0.4)).norm(), 0, 1e-15);
  EXPECT_NEAR(sectionByPlane(sphere, at(0, 0, 0.12, Eigen::Matrix3d::Identity())).gap, 0.02, 1e-15);

  Solid cylinder;
  cylinder.kind = Solid::Kind::kCylinder;
  cylinder.radius = 0.05;
  cylinder.length = 0.6;
  const Section normal =
      sectionByPlane(cylinder, at(0, 0, 0.1, about(Eigen::Vector3d::UnitX(), M_PI)));
  EXPECT_NEAR(normal.radius, 0.05, 1e-15);
  const Section lying =
      sectionByPlane(cylinder, at(0, 0, 0, about(Eigen::Vector3d::UnitY(), M_PI / 2)));
  ASSERT_EQ(lying.polygon.size(), 4u);
  EXPECT_NEAR(area(lying.polygon), 0.6 * 0.1, 1e-12);
  const Section oblique =
      sectionByPlane(cylinder, at(0, 0, 0, about(Eigen::Vector3d::UnitY(), M_PI / 4)));
  const double ellipse = M_PI * 0.05 * 0.05 * std::sqrt(2.0);
  EXPECT_LE(area(oblique.polygon), ellipse);
  EXPECT_GE(area(oblique.polygon), ellipse * std::pow(std::cos(M_PI / kCylinderFacets), 2));
}

// The outline: the section shrunk by the rounding and swept by it, so its area is the
// section's less the corners' (4 - pi) a^2 for a rectangle; a disc stays a disc; the block's
// frame turned by 30 deg holds the same outline turned back.
TEST(PlaneSection, OutlinesAreTheSectionsWithRoundedCorners) {
  Solid box;
  box.size = Eigen::Vector3d(0.2, 0.1, 0.3);
  const Section s = sectionByPlane(box, at(1, 2, 0, about(Eigen::Vector3d::UnitZ(), 0.3)));
  BlockDef b;
  outlineInFrame(s, Vec2(1, 2), 0.3 + M_PI / 6, 0.004, b);
  EXPECT_DOUBLE_EQ(b.rounding, 0.004);
  EXPECT_NEAR(outlineArea(b), 0.02 - (4 - M_PI) * 0.004 * 0.004, 1e-14);
  // In the block's frame the rectangle is turned by -30 deg about the frame's origin (1, 2).
  for (const Vec2& v : b.core) EXPECT_NEAR(v.norm(), std::hypot(0.096, 0.046), 1e-14);
  // A thin section keeps a core: its rounding at most a quarter of its width.
  Solid plate;
  plate.size = Eigen::Vector3d(0.3, 0.004, 0.1);
  outlineInFrame(sectionByPlane(plate, Eigen::Isometry3d::Identity()), Vec2(0, 0), 0, 0.004, b);
  EXPECT_DOUBLE_EQ(b.rounding, 0.001);
  EXPECT_EQ(b.core.size(), 4u);
  Solid sphere;
  sphere.kind = Solid::Kind::kSphere;
  sphere.radius = 0.05;
  outlineInFrame(sectionByPlane(sphere, Eigen::Isometry3d::Identity()), Vec2(0.1, 0), 0, 0.004, b);
  ASSERT_EQ(b.core.size(), 1u);
  EXPECT_NEAR((b.core[0] - Vec2(-0.1, 0)).norm(), 0, 1e-15);
  EXPECT_DOUBLE_EQ(b.rounding, 0.05);
}

namespace {

// A two-link arm in the x-y plane: a base box, and an arm on a revolute joint about z at
// (0.1, 0.2, 0) turned by 0.5 rad, with a box and a sphere (its end, 0.3 m out) for collision.
const char* kArm = R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="base"><collision><geometry><box size="0.2 0.1 0.2"/></geometry></collision></link>
  <link name="arm">
    <collision><origin xyz="0.15 0 0"/><geometry><box size="0.3 0.04 0.05"/></geometry></collision>
    <collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.03"/></geometry></collision>
  </link>
  <link name="lifted"><collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
  <link name="mesh"><collision><geometry><mesh filename="package://x/m.stl"/></geometry></collision></link>
  <link name="bare"/>
  <joint name="j1" type="revolute">
    <parent link="base"/><child link="arm"/><origin xyz="0.1 0.2 0" rpy="0 0 0.5"/>
    <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j2" type="fixed"><parent link="base"/><child link="lifted"/></joint>
  <joint name="j3" type="fixed"><parent link="base"/><child link="mesh"/></joint>
  <joint name="j4" type="fixed"><parent link="base"/><child link="bare"/></joint>
</robot>)";

}  // namespace

// The arm at rest: its frame at (0.1, 0.2) turned by 0.5 rad; its box and its sphere two kinematic
// blocks (arm, arm_2) in that frame, the sphere's disc 0.3 m out along the arm.
TEST(RobotObstacles, AnArmsLinksBecomeBlocksInTheirFrames) {
  const RobotDescription robot(kArm);
  EXPECT_EQ(robot.name(), "arm");
  const Eigen::Isometry3d rest = robot.restPose("arm");
  EXPECT_NEAR((rest.translation() - Eigen::Vector3d(0.1, 0.2, 0)).norm(), 0, 1e-15);
  RobotObstaclesDef def;
  def.links = {"base", "arm"};
  def.friction = 0.4;
  const std::vector<LinkBlock> blocks =
      robot.obstacles(def, [&](const std::string& link) { return robot.restPose(link); });
  ASSERT_EQ(blocks.size(), 3u);
  EXPECT_EQ(blocks[0].block.name, "base");
  EXPECT_EQ(blocks[1].block.name, "arm");
  EXPECT_EQ(blocks[2].block.name, "arm_2");
  EXPECT_EQ(blocks[2].link, "arm");
  const BlockDef& arm = blocks[1].block;
  EXPECT_EQ(arm.type, BodyType::kKinematic);
  EXPECT_DOUBLE_EQ(arm.friction, 0.4);
  EXPECT_NEAR((arm.position - Vec2(0.1, 0.2)).norm(), 0, 1e-15);
  EXPECT_NEAR(arm.angle, 0.5, 1e-15);
  EXPECT_NEAR(outlineArea(arm), 0.3 * 0.04 - (4 - M_PI) * 0.002 * 0.002, 1e-14);
  for (const Vec2& v : arm.core) EXPECT_NEAR(std::abs(v.y()), 0.018, 1e-14);  // in its frame
  const BlockDef& end = blocks[2].block;
  ASSERT_EQ(end.core.size(), 1u);
  EXPECT_NEAR((end.core[0] - Vec2(0.3, 0)).norm(), 0, 1e-14);
  EXPECT_DOUBLE_EQ(end.rounding, 0.03);
}

// What cannot become a block is refused with the link's name and what to do.
TEST(RobotObstacles, BadDescriptionsAreRefusedNamingTheLink) {
  EXPECT_THROW(RobotDescription("<robot name='x'><link name='a'/>"), RobotError);
  const RobotDescription robot(kArm);
  auto refusal = [&](const std::string& link) {
    RobotObstaclesDef def;
    def.links = {link};
    try {
      robot.obstacles(def, [&](const std::string& l) { return robot.restPose(l); });
    } catch (const RobotError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(refusal("wheel"), "link 'wheel' is not in the robot description of 'arm'");
  EXPECT_EQ(refusal("mesh"),
            "link 'mesh': its collision mesh 'package://x/m.stl' is in a ROS package, which only "
            "the node can find (give the file's path)");
  EXPECT_EQ(refusal("bare"), "link 'bare' has no collision geometry to meet the material");
  EXPECT_NE(refusal("lifted").find("link 'lifted': its collision geometry does not cross the "
                                   "simulation plane"),
            std::string::npos);
  EXPECT_NE(refusal("lifted").find("stays 0.45 m from it"), std::string::npos) << refusal("lifted");
  EXPECT_THROW(robot.restPose("wheel"), RobotError);
}

namespace {

// An L-shaped profile in x-y (arms 0.2 m long, 0.05 m thick) extruded from z = -0.03 to 0.03 m,
// as an ASCII STL at `path`: a mesh that is not convex. Its hull's section by z = 0 is the L
// with the corner between its arms' ends filled: 0.2^2 - 0.15^2 / 2 = 0.02875 m^2, 5 corners.
const std::vector<Vec2> kL = {{0, 0}, {0.2, 0}, {0.2, 0.05}, {0.05, 0.05}, {0.05, 0.2}, {0, 0.2}};

std::string writeL(const std::string& path) {
  std::ofstream out(path);
  out << "solid l\n";
  auto facet = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
    out << "facet normal 0 0 0\nouter loop\n";
    for (const Eigen::Vector3d& v : {a, b, c})
      out << "vertex " << v.x() << " " << v.y() << " " << v.z() << "\n";
    out << "endloop\nendfacet\n";
  };
  const std::size_t n = kL.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 &p = kL[i], &q = kL[(i + 1) % n];
    const Eigen::Vector3d p0(p.x(), p.y(), -0.03), p1(p.x(), p.y(), 0.03);
    const Eigen::Vector3d q0(q.x(), q.y(), -0.03), q1(q.x(), q.y(), 0.03);
    facet(p0, q0, q1);  // the side
    facet(p0, q1, p1);
    if (i > 0 && i + 1 < n) {  // the caps, fanned from the first corner
      facet(Eigen::Vector3d(kL[0].x(), kL[0].y(), -0.03), q0, p0);
      facet(Eigen::Vector3d(kL[0].x(), kL[0].y(), 0.03), p1, q1);
    }
  }
  out << "endsolid l\n";
  return path;
}

}  // namespace

// A collision mesh is its convex hull: the L's section by the plane is the hull's (the closed
// form above), scaled per axis as URDF's scale says; a link with it becomes one block whose
// outline is that polygon with its corners rounded (area less r^2 sum(tan(e/2) - e/2) over
// the exterior angles e).
TEST(RobotObstacles, AMeshIsItsConvexHull) {
  const std::string path = writeL(::testing::TempDir() + "l_profile.stl");
  Solid hull;
  hull.kind = Solid::Kind::kConvex;
  hull.corners = meshHullCorners(path, Eigen::Vector3d(1, 1, 1));
  EXPECT_EQ(hull.corners.size(), 10u);  // the inner corner of the L is not on the hull
  const Section s = sectionByPlane(hull, Eigen::Isometry3d::Identity());
  ASSERT_EQ(s.polygon.size(), 5u);
  EXPECT_NEAR(area(s.polygon), 0.02875, 1e-15);
  hull.corners = meshHullCorners(path, Eigen::Vector3d(2, 1, 1));
  EXPECT_NEAR(area(sectionByPlane(hull, Eigen::Isometry3d::Identity()).polygon), 2 * 0.02875,
              1e-15);
  // Lifted 0.02 m: still cut (the prism reaches 0.03 m down); lifted 0.05 m, 0.02 m clear.
  EXPECT_NEAR(area(sectionByPlane(hull, at(0, 0, 0.02, Eigen::Matrix3d::Identity())).polygon),
              2 * 0.02875, 1e-15);
  EXPECT_NEAR(sectionByPlane(hull, at(0, 0, 0.05, Eigen::Matrix3d::Identity())).gap, 0.02, 1e-15);

  const std::string urdf =
      "<robot name='r'><link name='scoop'><collision><geometry><mesh "
      "filename='file://" +
      path + "'/></geometry></collision></link></robot>";
  const RobotDescription robot(urdf);
  RobotObstaclesDef def;
  def.links = {"scoop"};
  def.rounding = 0.004;
  const std::vector<LinkBlock> blocks =
      robot.obstacles(def, [&](const std::string& l) { return robot.restPose(l); });
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].block.name, "scoop");
  ASSERT_EQ(blocks[0].block.core.size(), 5u);
  double lost = 0;  // the corners' rounding
  for (std::size_t i = 0; i < s.polygon.size(); ++i) {
    const Vec2 a = s.polygon[i] - s.polygon[(i + 4) % 5], b = s.polygon[(i + 1) % 5] - s.polygon[i];
    const double e = std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
    lost += std::tan(e / 2) - e / 2;
  }
  EXPECT_NEAR(outlineArea(blocks[0].block), 0.02875 - 0.004 * 0.004 * lost, 1e-14);
}

// A mesh that cannot be read or made a solid is refused naming the file and the link.
TEST(RobotObstacles, BadMeshesAreRefused) {
  auto refusal = [](const std::string& file) {
    try {
      meshHullCorners(file, Eigen::Vector3d(1, 1, 1));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  const std::string dir = ::testing::TempDir();
  EXPECT_NE(refusal(dir + "bucket.dae")
                .find("is not in a format read here (STL, OFF, OBJ or "
                      "PLY)"),
            std::string::npos);
  EXPECT_EQ(refusal(dir + "none.stl"),
            "mesh '" + dir + "none.stl' cannot be opened (no such file?)");
  std::ofstream(dir + "flat.stl") << "solid f\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n"
                                     "vertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nfacet normal "
                                     "0 0 1\nouter loop\nvertex 1 1 0\nvertex 1 0 0\nvertex 0 1 "
                                     "0\nendloop\nendfacet\nendsolid f\n";
  EXPECT_NE(refusal(dir + "flat.stl").find("spans no volume"), std::string::npos)
      << refusal(dir + "flat.stl");
  std::ofstream(dir + "junk.stl") << "not a mesh\n";
  EXPECT_NE(refusal(dir + "junk.stl").find("cannot be read as stl"), std::string::npos)
      << refusal(dir + "junk.stl");
  const RobotDescription robot(
      "<robot name='r'><link name='scoop'><collision><geometry><mesh "
      "filename='" +
      dir + "none.stl'/></geometry></collision></link></robot>");
  RobotObstaclesDef def;
  def.links = {"scoop"};
  try {
    robot.check(def);
    ADD_FAILURE() << "a missing mesh accepted";
  } catch (const RobotError& e) {
    EXPECT_EQ(std::string(e.what()), "link 'scoop': its collision mesh '" + dir +
                                         "none.stl' cannot be opened (no such file?)");
  }
}
