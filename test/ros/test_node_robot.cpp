// rostest: the interfaces other robot components use (robot_*.test, one behaviour each) against
// the node on test/data/robot_bed.yaml: per-obstacle wrenches and held loads, cmd_vel, tf
// following, state queries, /tf_static, late listeners while paused, gazebo-style names.
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <mpm_sdem/ApplyObstacleWrench.h>
#include <mpm_sdem/GetObstacleState.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <cmath>

#include "ros_helpers.hpp"

using namespace mpm_sdem;
using test::waitFor;

namespace {

test::NodeClient* g_node = nullptr;
const double kBoxWeight = 0.8 * 9.81;  // robot_bed.yaml's box: 0.04 m square, rounding 2 mm

double yaw(const geometry_msgs::Quaternion& q) {
  return 2 * std::atan2(q.z, q.w);
}

}  // namespace

// The resting box's wrench is its contact load in its own frame: the material carries its weight
// (within 10%, as in node_services' check of ~blocks), and it equals ~blocks' forces turned into
// the box's axes. A held upward load of 1.5 W for 0.1 s lifts it; after the load ends it falls
// back (gravity alone: its upward speed drops).
TEST(Robot, WrenchOfTheRestingBoxAndAHeldLoad) {
  test::NodeClient& n = *g_node;
  test::Latest<geometry_msgs::WrenchStamped> wrench(n.nh, test::kNs + "obstacles/box/wrench");
  ASSERT_TRUE(waitFor([&] { return wrench.count() > 20 && n.blocks.has(); }, 20));
  // Settled by 1 s of simulation (node_services waits as long).
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > 1.0; }, 20));
  const geometry_msgs::WrenchStamped w = wrench.get();
  EXPECT_EQ(w.header.frame_id, "mpm_sdem/box");
  EXPECT_NEAR(w.wrench.force.y, kBoxWeight, 0.1 * kBoxWeight);
  EXPECT_EQ(w.wrench.force.z, 0);
  RigidBlockState box;
  ASSERT_TRUE(n.block("box", box));
  EXPECT_GT(box.contact_count, 0u);

  mpm_sdem::ApplyObstacleWrench a;
  a.request.name = "box";
  a.request.wrench.force.y = 1.5 * kBoxWeight;
  a.request.duration = 0.1;
  ASSERT_TRUE(n.call("apply_obstacle_wrench", a).response.success) << a.response.message;
  const double y0 = box.pose.position.y;
  // Net 0.5 g up for 0.1 s: about 2.5 cm up by its end (less what the bed's pull-back takes),
  // then it rises on and falls back.
  double top = y0, rising = 0;
  ASSERT_TRUE(waitFor(
      [&] {
        if (!n.block("box", box)) return false;
        top = std::max(top, box.pose.position.y);
        rising = std::max(rising, box.twist.linear.y);
        return top > y0 + 0.01 && box.twist.linear.y < 0;
      },
      10))
      << "the load did not lift the box and let it fall back: top " << top - y0 << " m, " << rising
      << " m/s";
  EXPECT_LT(rising, 0.5 * 9.81 * 0.1 * 1.05);  // at most what 0.5 g for 0.1 s gives

  // Refused: an out-of-plane component, a static block, an unknown block.
  a.request.wrench.force.z = 1;
  EXPECT_FALSE(n.call("apply_obstacle_wrench", a).response.success);
  a.request.wrench.force.z = 0;
  a.request.name = "post";
  a = n.call("apply_obstacle_wrench", a);
  EXPECT_FALSE(a.response.success);
  EXPECT_NE(a.response.message.find("not dynamic"), std::string::npos) << a.response.message;
  a.request.name = "nobody";
  EXPECT_FALSE(n.call("apply_obstacle_wrench", a).response.success);
}

// The blade is turned 90 degrees: linear.x of its cmd_vel (its own x axis) moves it along the
// world's y. When the commands stop it stops after ~cmd_vel_timeout (0.5 s of simulation).
TEST(Robot, CmdVelInTheBladesAxesLapsesAfterTheTimeout) {
  test::NodeClient& n = *g_node;
  ros::Publisher cmd =
      n.nh.advertise<geometry_msgs::Twist>(test::kNs + "obstacles/blade/cmd_vel", 1);
  ASSERT_TRUE(waitFor([&] { return cmd.getNumSubscribers() > 0 && n.blocks.has(); }, 20));
  geometry_msgs::Twist t;
  t.linear.x = 0.02;
  RigidBlockState blade;
  // Commands at 20 Hz for 1 s of wall time (real-time pacing: about 1 s of simulation).
  for (int k = 0; k < 20; ++k) {
    cmd.publish(t);
    ros::WallDuration(0.05).sleep();
  }
  ASSERT_TRUE(n.block("blade", blade));
  EXPECT_NEAR(blade.twist.linear.x, 0, 1e-6);
  EXPECT_NEAR(blade.twist.linear.y, 0.02, 1e-6);
  const double stopped_after = n.stats.get().sim_time;
  ASSERT_TRUE(waitFor([&] { return n.block("blade", blade) && blade.twist.linear.y == 0; }, 5))
      << "the blade kept moving after the commands stopped";
  const double t_stop = n.blocks.get().header.stamp.toSec();
  // Lapsed within the timeout after the last command (plus the message rates' slack).
  EXPECT_GT(t_stop - stopped_after, 0.3);
  EXPECT_LT(t_stop - stopped_after, 0.5 + 0.2);
}

// A frame moving at 5 cm/s and turning at 0.2 rad/s, broadcast at 50 Hz with sim-time stamps:
// the follower runs with it (the frame's velocity fed forward), within 2 mm and 0.01 rad.
TEST(Robot, FollowerTracksItsMovingFrame) {
  test::NodeClient& n = *g_node;
  tf2_ros::TransformBroadcaster tf;
  auto target = [](double t, double& x, double& y, double& a) {
    x = -0.05 + 0.05 * t, y = 0.15, a = 0.3 + 0.2 * t;
  };
  ASSERT_TRUE(waitFor([&] { return n.blocks.has(); }, 20));
  const double t0 = ros::Time::now().toSec();
  double worst = 0, worst_angle = 0;
  int checked = 0;
  for (int k = 0; k < 100; ++k) {  // 2 s
    const ros::Time now = ros::Time::now();
    double x, y, a;
    target(now.toSec() - t0, x, y, a);
    geometry_msgs::TransformStamped ts;
    ts.header.stamp = now;
    ts.header.frame_id = "world";
    ts.child_frame_id = "target";
    ts.transform.translation.x = x;
    ts.transform.translation.y = y;
    ts.transform.rotation.z = std::sin(a / 2);
    ts.transform.rotation.w = std::cos(a / 2);
    tf.sendTransform(ts);
    ros::WallDuration(0.02).sleep();
    if (now.toSec() - t0 < 1.0) continue;  // converging (time constant 0.05 s)
    const BlockStates s = n.blocks.get();
    const RigidBlockState* b = test::findBlock(s, "follower");
    ASSERT_NE(b, nullptr);
    target(s.header.stamp.toSec() - t0, x, y, a);
    worst = std::max(worst, std::hypot(b->pose.position.x - x, b->pose.position.y - y));
    worst_angle =
        std::max(worst_angle, std::abs(std::remainder(yaw(b->pose.orientation) - a, 2 * M_PI)));
    ++checked;
  }
  std::printf("follower: worst %.2f mm, %.4f rad over %d samples\n", 1e3 * worst, worst_angle,
              checked);
  EXPECT_GT(checked, 20);
  EXPECT_LT(worst, 0.002);
  EXPECT_LT(worst_angle, 0.01);
}

// ~get_obstacle_state in the domain's frame (its corner at (-0.2, 0), on /tf_static) shifts the
// pose by the corner; the static post is on /tf_static; unknown names and frames are refused.
TEST(Robot, StateInAReferenceFrameAndStaticFrames) {
  test::NodeClient& n = *g_node;
  ASSERT_TRUE(
      waitFor([&] { return n.tf.canTransform("world", "mpm_sdem/domain", ros::Time(0)); }, 20));
  ASSERT_TRUE(n.tf.canTransform("world", "mpm_sdem/post", ros::Time(0)));
  const auto post = n.tf.lookupTransform("world", "mpm_sdem/post", ros::Time(0));
  EXPECT_NEAR(post.transform.translation.x, 0.15, 1e-6);
  EXPECT_NEAR(post.transform.translation.y, 0.1, 1e-6);
  mpm_sdem::GetObstacleState g;
  g.request.name = "blade";
  g.request.reference_frame = "mpm_sdem/domain";
  g = n.call("get_obstacle_state", g);
  ASSERT_TRUE(g.response.success) << g.response.message;
  EXPECT_EQ(g.response.header.frame_id, "mpm_sdem/domain");
  EXPECT_NEAR(g.response.pose.position.x, g.response.state.pose.position.x + 0.2, 1e-9);
  EXPECT_NEAR(g.response.pose.position.y, g.response.state.pose.position.y, 1e-9);
  EXPECT_NEAR(yaw(g.response.pose.orientation), M_PI / 2, 1e-6);
  g.request.reference_frame = "no_such_frame";
  g = n.call("get_obstacle_state", g);
  EXPECT_FALSE(g.response.success);
  EXPECT_NE(g.response.message.find("no_such_frame"), std::string::npos) << g.response.message;
  g.request.name = "nobody";
  g.request.reference_frame = "";
  EXPECT_FALSE(n.call("get_obstacle_state", g).response.success);
}

// Started paused, nothing has stepped: a listener that subscribes now still gets the cloud, the
// outlines and the terrain (latched), the terrain being the flat bed's top (0.04 m, exact: a
// lattice line). The gazebo names unpause, pause and reset; the 2D convention is on the
// parameter server.
TEST(Robot, PausedStartServesLateListenersAndGazeboNames) {
  test::NodeClient& n = *g_node;
  ASSERT_TRUE(waitFor([&] { return n.stats.has(); }, 20));
  EXPECT_TRUE(n.stats.get().paused);
  test::Latest<sensor_msgs::PointCloud2> terrain(n.nh, test::kNs + "terrain");
  test::Latest<visualization_msgs::MarkerArray> markers(n.nh, test::kNs + "markers");
  ASSERT_TRUE(waitFor([&] { return n.cloud.has() && terrain.has() && markers.has(); }, 10))
      << "cloud " << n.cloud.has() << ", terrain " << terrain.has() << ", markers "
      << markers.has();
  const sensor_msgs::PointCloud2 c = terrain.get();
  ASSERT_EQ(c.width, 40u);  // 0.4 m in 1 cm columns
  int columns = 0;
  for (sensor_msgs::PointCloud2ConstIterator<float> it(c, "y"); it != it.end(); ++it, ++columns)
    EXPECT_NEAR(*it, 0.04, 1e-6) << "column " << columns;
  EXPECT_EQ(markers.get().markers.front().action, visualization_msgs::Marker::DELETEALL);
  EXPECT_EQ(markers.get().markers.back().header.frame_id, "world");
  std::string plane;
  EXPECT_TRUE(n.nh.getParam(test::kNs + "convention/plane", plane));
  EXPECT_NE(plane.find("plane strain"), std::string::npos);
  double thickness = 0;
  EXPECT_TRUE(n.nh.getParam(test::kNs + "convention/thickness_m", thickness));
  EXPECT_EQ(thickness, 1.0);

  std_srvs::Empty e;
  n.call("unpause_physics", e);
  ASSERT_TRUE(waitFor([&] { return !n.stats.get().paused && n.stats.get().step > 10; }, 10));
  n.call("pause_physics", e);
  ASSERT_TRUE(waitFor([&] { return n.stats.get().paused; }, 5));
  n.call("reset_simulation", e);
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step == 0; }, 5));
}

int main(int argc, char** argv) {
  return test::runNodeTests(argc, argv, "test_node_robot", g_node);
}
