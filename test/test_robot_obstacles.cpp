// A robot's links as blocks (robot/robot_obstacles.hpp): the sections of URDF's solids by the
// simulation plane against their closed forms, the blocks' outlines against the sections, a
// two-link arm's blocks where its rest pose puts them, and a description that cannot become
// blocks refused with the link's name.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

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
  EXPECT_NE(refusal("mesh").find("link 'mesh': its collision is a mesh, which is not supported"),
            std::string::npos);
  EXPECT_EQ(refusal("bare"), "link 'bare' has no collision geometry to meet the material");
  EXPECT_NE(refusal("lifted").find("link 'lifted': its collision geometry does not cross the "
                                   "simulation plane"),
            std::string::npos);
  EXPECT_NE(refusal("lifted").find("stays 0.45 m from it"), std::string::npos) << refusal("lifted");
  EXPECT_THROW(robot.restPose("wheel"), RobotError);
}
