// rostest: the interfaces other robot components use (robot_*.test, one behaviour each) against
// the node on test/data/robot_bed.yaml: per-obstacle wrenches and held loads, cmd_vel, tf
// following, state queries, /tf_static, late listeners while paused, gazebo-style names.
#include <geometry_msgs/Twist.h>
#include <geometry_msgs/WrenchStamped.h>
#include <gtest/gtest.h>
#include <mpm_sdem/ApplyObstacleWrench.h>
#include <mpm_sdem/ClearObstacleWrenches.h>
#include <mpm_sdem/GetObstacleState.h>
#include <mpm_sdem/RemoveObstacle.h>
#include <mpm_sdem/SetObstacleState.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <std_srvs/Empty.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <thread>
#include <utility>
#include <vector>

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

  // A caller looping on requests: at most 1000 loads held (each step adds them all), then
  // refused until cleared. The caller keeps one connection, as a looping client does: 1001
  // one-off calls open 1001 connections, and on a loaded machine one of them failed to connect
  // (CI: 999 held, the service never saw the call).
  a.request.name = "box";
  a.request.wrench = geometry_msgs::Wrench();
  a.request.duration = -1;
  ros::ServiceClient looping =
      n.nh.serviceClient<mpm_sdem::ApplyObstacleWrench>(test::kNs + "apply_obstacle_wrench", true);
  int held = 0, answered = 0;
  for (int k = 0; k < 1001; ++k) {
    mpm_sdem::ApplyObstacleWrench r = a;
    if (!looping.call(r)) continue;
    ++answered;
    held += r.response.success;
  }
  EXPECT_EQ(answered, 1001);
  EXPECT_EQ(held, 1000);
  mpm_sdem::ClearObstacleWrenches c;
  c.request.name = "box";
  c = n.call("clear_obstacle_wrenches", c);
  EXPECT_TRUE(c.response.success);
  EXPECT_EQ(c.response.message, "cleared 1000 loads");
  EXPECT_TRUE(n.call("apply_obstacle_wrench", a).response.success);
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
  test::publishRepeatedly(cmd, t, 20, 0.05);
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
// the follower is where the frame was ~follow_tf_delay (0.1 s) before, within 0.2 mm and
// 0.002 rad (the frame moves 1 mm and 0.004 rad between samples).
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
    if (now.toSec() - t0 < 1.0) continue;  // on the interpolated path (0.1 s behind)
    const BlockStates s = n.blocks.get();
    const RigidBlockState* b = test::findBlock(s, "follower");
    ASSERT_NE(b, nullptr);
    target(s.header.stamp.toSec() - t0 - 0.1, x, y, a);
    worst = std::max(worst, std::hypot(b->pose.position.x - x, b->pose.position.y - y));
    worst_angle =
        std::max(worst_angle, std::abs(std::remainder(yaw(b->pose.orientation) - a, 2 * M_PI)));
    ++checked;
  }
  std::printf("follower: worst %.2f mm, %.4f rad over %d samples\n", 1e3 * worst, worst_angle,
              checked);
  EXPECT_GT(checked, 20);
  EXPECT_LT(worst, 0.0002);
  EXPECT_LT(worst_angle, 0.002);
}

// A frame that stops holds its block where it stopped: a follower is where its frame was
// ~follow_tf_delay before, between two samples, never past them (one run on at the frame's last
// speed would overshoot, then pull back, unloading the sand it held). The follower (2 x 2 cm) is
// pressed into the bed at 5 cm/s, its bottom to 1.5 cm deep, by its frame sampled at 30 Hz and at
// 100 Hz of simulated time, then held; four runs at each rate, ~reset between. Asserted: the
// block never passes the frame's lowest pose (by 10 um: the poses' rounding), and the load it
// holds 0.4-0.6 s after the stop is the same within 2% over the four runs at each rate (measured:
// the same to 0.01 N/m, 185.16 N/m at 30 Hz and 183.68 N/m at 100 Hz). At 5 Hz, slower than the
// delay, a warning says so, and the block still never passes its frame.
TEST(Robot, FollowerStopsWhereItsFrameStopsAndHoldsItsLoad) {
  test::NodeClient& n = *g_node;
  const double y_stop = 0.037;  // its bottom (y - 1 cm - 2 mm rounding) 1.5 cm into the bed
  const double t_stop = 0.3 + (0.10 - y_stop) / 0.05;
  auto height = [&](double t) { return std::max(y_stop, 0.10 - 0.05 * std::max(0.0, t - 0.3)); };
  std::mutex m;
  double lowest = 1, load = 0;
  int loads = 0;
  ros::Subscriber blocks =
      n.nh.subscribe<BlockStates>(test::kNs + "blocks", 100, [&](const BlockStates::ConstPtr& s) {
        const RigidBlockState* b = test::findBlock(*s, "follower");
        std::lock_guard<std::mutex> l(m);
        if (b) lowest = std::min(lowest, b->pose.position.y);
      });
  ros::Subscriber wrench = n.nh.subscribe<geometry_msgs::WrenchStamped>(
      test::kNs + "obstacles/follower/wrench", 100,
      [&](const geometry_msgs::WrenchStamped::ConstPtr& w) {
        const double t = w->header.stamp.toSec();
        std::lock_guard<std::mutex> l(m);
        if (t > t_stop + 0.4 && t < t_stop + 0.6) load += w->wrench.force.y, ++loads;
      });
  tf2_ros::TransformBroadcaster tf;
  test::RosoutLog log(n.nh);
  // 5 Hz, slower than ~follow_tf_delay (0.1 s): one run, warned of, the block still never past.
  for (const double rate : {30.0, 100.0, 5.0}) {
    std::vector<double> held;
    for (int run = 0; run < (rate > 10 ? 4 : 1); ++run) {
      ASSERT_TRUE(n.trigger("reset"));
      ros::WallDuration(0.2).sleep();  // messages of the run before have arrived
      {
        std::lock_guard<std::mutex> l(m);
        lowest = 1, load = 0, loads = 0;
      }
      // The frame sampled at multiples of 1/rate of simulated time, as a controller on sim time
      // samples it (the same samples in every run; sent as each comes due).
      double last = -1;
      const ros::WallTime give_up = ros::WallTime::now() + ros::WallDuration(30);
      while (ros::Time::now().toSec() < t_stop + 0.7 && ros::WallTime::now() < give_up) {
        const double due = std::floor(ros::Time::now().toSec() * rate) / rate;
        if (due > last) {
          last = due;
          geometry_msgs::TransformStamped ts;
          ts.header.stamp.fromSec(due);
          ts.header.frame_id = "world";
          ts.child_frame_id = "target";
          ts.transform.translation.y = height(due);
          ts.transform.rotation.w = 1;
          tf.sendTransform(ts);
        }
        ros::WallDuration(0.002).sleep();
      }
      ros::WallDuration(0.2).sleep();
      std::lock_guard<std::mutex> l(m);
      ASSERT_GT(loads, 3) << "no wrench while held (run " << run << " at " << rate << " Hz)";
      held.push_back(load / loads);
      std::printf("tf at %.0f Hz, run %d: lowest %.4f mm past the frame, held %.2f N/m\n", rate,
                  run, 1e3 * (y_stop - lowest), held.back());
      EXPECT_GT(lowest, y_stop - 1e-5) << "the block ran past its frame (" << rate << " Hz)";
    }
    if (rate < 10) {
      const std::string warning = log.find("samples come");
      EXPECT_NE(warning.find("frame target's samples come 0.2 s apart"), std::string::npos)
          << warning;
      break;
    }
    EXPECT_EQ(log.count("samples come"), 0) << "a warning at " << rate << " Hz";
    const auto [lo, hi] = std::minmax_element(held.begin(), held.end());
    EXPECT_GT(*lo, 5) << "the sand does not bear the follower";
    std::string runs;
    for (const double f : held) runs += " " + std::to_string(f);
    EXPECT_LT(*hi - *lo, 0.02 * *lo) << "held loads (N/m) at " << rate << " Hz:" << runs;
  }
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
  // A frame of 1 MB, or of 300,000 good names: refused with a reply of a few lines, and no
  // longer log lines.
  test::RosoutLog log(n.nh);
  g.request.name = "blade";
  for (const std::string& frame : {std::string(1 << 20, 'f'), [] {
                                     std::string f = "a";
                                     for (int k = 0; k < 300000; ++k) f += "/a";
                                     return f;
                                   }()}) {
    g.request.reference_frame = frame;
    g = n.call("get_obstacle_state", g);
    EXPECT_FALSE(g.response.success);
    EXPECT_LT(g.response.message.size(), 300u) << g.response.message.substr(0, 300);
  }
  ros::WallDuration(0.5).sleep();
  EXPECT_LT(log.longest(), 1000u);
  // Topics only for what the scene has: no FEM bodies here, so no ~fem_mesh or ~fem_nodes.
  ros::master::V_TopicInfo topics;
  ASSERT_TRUE(ros::master::getTopics(topics));
  for (const ros::master::TopicInfo& t : topics)
    EXPECT_EQ(t.name.find(test::kNs + "fem_"), std::string::npos) << t.name;
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

namespace {

mpm_sdem::ApplyObstacleWrench::Response load(test::NodeClient& n, double fy, double torque,
                                             double duration) {
  mpm_sdem::ApplyObstacleWrench a;
  a.request.name = "box";
  a.request.wrench.force.y = fy;
  a.request.wrench.torque.z = torque;
  a.request.duration = duration;
  return n.call("apply_obstacle_wrench", a).response;
}

void clearLoads(test::NodeClient& n) {
  mpm_sdem::ClearObstacleWrenches c;
  c.request.name = "box";
  EXPECT_TRUE(n.call("clear_obstacle_wrenches", c).response.success);
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

}  // namespace

// Held loads on the box (0.8 kg/m), judged while paused so that nothing moves: every load the
// issue threw it with (1e4 to 1e300 N/m: 1.25e4 m/s^2 and more) and a torque of 100 N m/m
// (1.3e4 m/s^2 at its corners) are refused, naming the bound; 7000 N/m for 10 ms is held (8750
// m/s^2, 87.5 m/s) but 2000 N/m more on top of it is not; 1000 N/m for 1 s would add 1250 m/s,
// for 0.5 s 625. Then three times its weight upward, held until cleared, carries it out through
// the top of the domain: the node pauses, naming the box and the load, and ~reset recovers.
TEST(Robot, HeldLoadsAreBoundedAndABlockPushedOutPauses) {
  test::NodeClient& n = *g_node;
  test::RosoutLog log(n.nh);
  ASSERT_TRUE(waitFor([&] { return n.stats.has(); }, 20));
  ASSERT_TRUE(n.stats.get().paused);
  // ~blocks is not sent while paused; ~get_obstacle_state answers.
  auto boxHeight = [&n] {
    mpm_sdem::GetObstacleState g;
    g.request.name = "box";
    g = n.call("get_obstacle_state", g);
    EXPECT_TRUE(g.response.success) << g.response.message;
    return g.response.pose.position.y;
  };
  const double y0 = boxHeight();
  for (double f : {1e4, 1e6, 1e30, 1e38, 1e300}) {
    const auto r = load(n, f, 0, 1e-3);
    EXPECT_FALSE(r.success) << f << " N/m";
    EXPECT_TRUE(contains(r.message, "m/s^2")) << r.message;
  }
  auto r = load(n, 0, 100, 1e-3);
  EXPECT_FALSE(r.success);
  EXPECT_TRUE(contains(r.message, "m/s^2")) << r.message;
  r = load(n, 7000, 0, 0.01);
  EXPECT_TRUE(r.success) << r.message;
  r = load(n, 2000, 0, 0.01);
  EXPECT_FALSE(r.success);
  EXPECT_TRUE(contains(r.message, "already held on it")) << r.message;
  clearLoads(n);
  r = load(n, 1000, 0, 1.0);
  EXPECT_FALSE(r.success);
  // 1253 m/s: the box is 0.798 kg/m, its corners rounded.
  EXPECT_TRUE(contains(r.message, "could add 125")) << r.message;
  EXPECT_TRUE(contains(r.message, "at most 1000 m/s")) << r.message;
  EXPECT_TRUE(load(n, 1000, 0, 0.5).success);
  clearLoads(n);

  r = load(n, 3 * kBoxWeight, 0, -1);
  ASSERT_TRUE(r.success) << r.message;
  ASSERT_TRUE(n.trigger("resume"));
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step > 0 && n.stats.get().paused; }, 20))
      << "the node did not pause when the box left the domain";
  const std::string why = log.find("left the domain");
  EXPECT_TRUE(contains(why, "block 'box'")) << why;
  EXPECT_TRUE(contains(why, "~apply_obstacle_wrench on 'box'")) << why;
  // Out through the top (0.2 m) and no further than a step or two past it.
  const double out = boxHeight();
  EXPECT_GT(out, 0.2);
  EXPECT_LT(out, 0.201);
  ASSERT_TRUE(n.trigger("reset"));
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step == 0; }, 5));
  EXPECT_EQ(boxHeight(), y0);
  ASSERT_TRUE(n.trigger("resume")) << "the state was sound: ~resume works after the reset";
}

// Kinematic blocks stop at the domain's walls however they are driven: the blade under a cmd_vel
// of 1 m/s up (its own x), an ~obstacle_cmd of 999 m/s right and a ~set_obstacle_state twist of
// 999 m/s left (a pose outside is refused: bad_obstacle_state.test); a follower whose frame
// jumps 1e6 m closes in at ~follow_tf_max_speed (5 m/s), with a warning naming the frame, and
// stops at the right wall. The node keeps running throughout.
TEST(Robot, KinematicBlocksStopAtTheWallsAndFollowersAtTheirSpeed) {
  test::NodeClient& n = *g_node;
  test::RosoutLog log(n.nh);
  ros::Publisher cmd =
      n.nh.advertise<geometry_msgs::Twist>(test::kNs + "obstacles/blade/cmd_vel", 1);
  ASSERT_TRUE(waitFor([&] { return cmd.getNumSubscribers() > 0 && n.blocks.has(); }, 20));
  geometry_msgs::Twist t;
  t.linear.x = 1;
  test::publishRepeatedly(cmd, t, 20, 0.05);
  RigidBlockState blade;
  ASSERT_TRUE(n.block("blade", blade));
  // Turned 90 degrees, 1 cm tall (its size holds the rounding): its centre stops 5 mm below the
  // top, to Box2D's single precision.
  EXPECT_NEAR(blade.pose.position.y, 0.2 - 0.005, 1e-6);
  EXPECT_NEAR(blade.twist.linear.y, 0, 1e-9);
  EXPECT_TRUE(contains(log.find("stops at the domain's wall"), "'blade'"));
  ObstacleCommand c;
  c.name = "blade";
  c.twist.linear.x = 999;
  n.cmd.publish(c);
  ASSERT_TRUE(waitFor([&] { return n.block("blade", blade) && blade.pose.position.x > 0.1; }, 10));
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(n.block("blade", blade));
  EXPECT_NEAR(blade.pose.position.x, 0.2 - 0.015, 1e-6);  // 3 cm wide
  EXPECT_NEAR(blade.twist.linear.x, 0, 1e-9);
  // ~set_obstacle_state's twist: 999 m/s left, to the left wall (-0.2 m).
  mpm_sdem::SetObstacleState set;
  set.request.name = "blade";
  set.request.set_twist = true;
  set.request.twist.linear.x = -999;
  ASSERT_TRUE(n.call("set_obstacle_state", set).response.success) << set.response.message;
  ASSERT_TRUE(waitFor([&] { return n.block("blade", blade) && blade.pose.position.x < 0; }, 10));
  ros::WallDuration(0.3).sleep();
  ASSERT_TRUE(n.block("blade", blade));
  EXPECT_NEAR(blade.pose.position.x, -0.2 + 0.015, 1e-6);
  EXPECT_NEAR(blade.twist.linear.x, 0, 1e-9);

  tf2_ros::TransformBroadcaster tf;
  auto send = [&](double x) {
    geometry_msgs::TransformStamped ts;
    ts.header.stamp = ros::Time::now();
    ts.header.frame_id = "world";
    ts.child_frame_id = "target";
    ts.transform.translation.x = x;
    ts.transform.translation.y = 0.15;
    ts.transform.rotation.w = 1;
    tf.sendTransform(ts);
  };
  for (int k = 0; k < 50; ++k, ros::WallDuration(0.02).sleep()) send(0);
  RigidBlockState follower;
  ASSERT_TRUE(n.block("follower", follower));
  EXPECT_NEAR(follower.pose.position.x, 0, 1e-3);
  double fastest = 0;
  for (int k = 0; k < 100; ++k, ros::WallDuration(0.02).sleep()) {
    send(1e6);
    if (n.block("follower", follower))
      fastest = std::max(fastest, std::hypot(follower.twist.linear.x, follower.twist.linear.y));
  }
  ASSERT_TRUE(n.block("follower", follower));
  EXPECT_GT(fastest, 1);
  EXPECT_LT(fastest, 5 * (1 + 1e-6));
  EXPECT_NEAR(follower.pose.position.x, 0.2 - 0.01, 1e-6);  // 2 cm wide
  EXPECT_TRUE(contains(log.find("frame target moved"), "~follow_tf_max_speed")) << "no warning";
  EXPECT_TRUE(contains(log.find("(following target)"), "stops at the domain's wall"));
  EXPECT_FALSE(n.stats.get().paused);
}

// Warnings are throttled in wall time and the first comes at once: the follower's frame is never
// broadcast, so once resumed it holds still and says so in its first simulated second (ROS
// time, counted from 0 under /use_sim_time, held the first back for 5 simulated s), then once
// per 5 s of wall time, however fast the simulation runs.
TEST(Robot, FirstWarningAtOnceThenThrottledInWallTime) {
  test::NodeClient& n = *g_node;
  test::RosoutLog log(n.nh);
  ASSERT_TRUE(waitFor([&] { return n.stats.has(); }, 20));
  ASSERT_TRUE(n.stats.get().paused);
  ros::WallDuration(1.0).sleep();  // the node's /rosout reaches the log
  ASSERT_EQ(log.count("holds still"), 0);
  ASSERT_TRUE(n.trigger("resume"));
  ASSERT_TRUE(waitFor([&] { return log.count("holds still") > 0; }, 10)) << "no warning";
  EXPECT_LT(n.stats.get().sim_time, 1.0);
  ros::WallDuration(5.5).sleep();
  EXPECT_EQ(log.count("holds still"), 2) << "at 0 and 5 s of wall time";
}

// ~robot_links: [tool] (test/data/tool.urdf on robot_description, robot_urdf.test): the link's
// section by the plane (2 x 6 cm) is spawned as a kinematic block named after it once its frame
// arrives on tf, and follows the frame down into the bed, its wrench from 0 in the air to the
// bed's bearing load (asserted above 5 N/m; it reads about 1.2 kN/m with the blade's bottom 3 cm
// into the bed and 1 cm above its sticky floor).
TEST(Robot, UrdfLinkFollowsItsFrameIntoTheSand) {
  test::NodeClient& n = *g_node;
  test::Latest<geometry_msgs::WrenchStamped> wrench(n.nh, test::kNs + "obstacles/tool/wrench");
  test::RosoutLog log(n.nh);
  std::atomic<bool> stop{false}, tilt{false};
  // The frame at (-0.04, 0.10) until 0.5 s of simulation, then down at 5 cm/s to 0.04; sent
  // before the node has a clock (stamps 0), as robot_state_publisher's would be. At the end,
  // tilted by 10 deg about x (out of the plane).
  auto height = [](double t) { return std::max(0.04, 0.10 - 0.05 * std::max(0.0, t - 0.5)); };
  std::thread broadcaster([&] {
    tf2_ros::TransformBroadcaster tf;
    ros::Time last;
    bool sent = false;
    for (; !stop && ros::ok(); ros::WallDuration(0.02).sleep()) {
      geometry_msgs::TransformStamped ts;
      ts.header.stamp = ros::Time::now();
      if (sent && ts.header.stamp == last) continue;  // tf2 warns of a repeated stamp
      last = ts.header.stamp;
      sent = true;
      ts.header.frame_id = "world";
      ts.child_frame_id = "tool";
      ts.transform.translation.x = -0.04;
      ts.transform.translation.y = height(ts.header.stamp.toSec());
      ts.transform.rotation.w = tilt ? std::cos(M_PI / 36) : 1;
      ts.transform.rotation.x = tilt ? std::sin(M_PI / 36) : 0;
      tf.sendTransform(ts);
    }
  });
  RigidBlockState tool;
  const bool up =
      waitFor([&] { return n.stats.get().sim_time > 0.3 && n.block("tool", tool); }, 30);
  if (up) {
    EXPECT_NEAR(tool.pose.position.x, -0.04, 2e-3);
    EXPECT_NEAR(tool.pose.position.y, 0.10, 2e-3);
    ASSERT_TRUE(waitFor([&] { return wrench.count() > 0; }, 10));
    EXPECT_LT(std::hypot(wrench.get().wrench.force.x, wrench.get().wrench.force.y), 0.5);
    EXPECT_EQ(wrench.get().header.frame_id, "mpm_sdem/tool");
  }
  const bool down = up && waitFor([&] { return n.stats.get().sim_time > 2.3; }, 30);
  if (down) {
    ASSERT_TRUE(n.block("tool", tool));
    EXPECT_NEAR(tool.pose.position.y, 0.04, 2e-3);
    EXPECT_GT(wrench.get().wrench.force.y, 5) << "the sand does not bear the tool";
    std::printf("tool: %.2f N/m up at %.3f m (bottom 3 cm into the bed)\n",
                wrench.get().wrench.force.y, tool.pose.position.y);
    // A link's block follows the robot: ~remove_obstacle refuses it, and it stays.
    mpm_sdem::RemoveObstacle remove;
    remove.request.name = "tool";
    remove = n.call("remove_obstacle", remove);
    EXPECT_FALSE(remove.response.success);
    EXPECT_NE(remove.response.message.find("robot link 'tool'"), std::string::npos)
        << remove.response.message;
    EXPECT_TRUE(n.block("tool", tool));
    // Tilted out of the plane, the frame no longer has the section the block was cut from.
    EXPECT_EQ(log.count("keeps that section"), 0);
    tilt = true;
    EXPECT_TRUE(waitFor([&] { return log.count("keeps that section") > 0; }, 10));
    const std::string warning = log.find("keeps that section");
    EXPECT_NE(warning.find("frame tool has tilted 10.0 deg"), std::string::npos) << warning;
  }
  stop = true;
  broadcaster.join();
  ASSERT_TRUE(up) << "no block 'tool' by 0.3 s of simulation";
  ASSERT_TRUE(down) << "the simulation did not reach 2.3 s";
}

namespace {

// The cloud's points higher than `y` (m): sand lifted above the bed.
int pointsAbove(const sensor_msgs::PointCloud2& cloud, double y) {
  int n = 0;
  for (sensor_msgs::PointCloud2ConstIterator<float> py(cloud, "y"); py != py.end(); ++py)
    n += *py > y;
  return n;
}

}  // namespace

// The excavator demo (launch/excavator_dig.launch): urdf/excavator.urdf through
// robot_state_publisher, its bucket a mesh's convex hull found by package://, its joints driven
// by scripts/excavator_dig.py, whose path starts when the node lists the links (at t0, the first
// ~blocks with the bucket). Above the sand (every load stamped before t0 + 0.9 s: the teeth, 6 cm
// clear until t0 + 0.6 s, then descend 13 cm a second and are still 2 cm clear) the bucket carries
// nothing and no sand stands above the 15 cm bed; while its teeth are dragged about 6-7 cm deep
// (t0 + 2 to t0 + 3.2 s) its load is at least half of a blade's passive force at that depth
// (McKyes' level-surface value for excavator_blade.yaml's sand, 14,715 N/m^3 x 0.06^2 m^2 x
// 3.015 = 160 N/m at 6 cm; 216 N/m at 7 cm), and by t0 + 3.2 s the drag has heaped sand more
// than 2 cm above the bed's surface.
TEST(Robot, ExcavatorDigsTheSand) {
  test::NodeClient& n = *g_node;
  test::Latest<geometry_msgs::WrenchStamped> wrench(n.nh, test::kNs + "obstacles/bucket/wrench");
  test::Latest<sensor_msgs::PointCloud2> cloud(n.nh, test::kNs + "particles");
  auto load = [&] { return std::hypot(wrench.get().wrench.force.x, wrench.get().wrench.force.y); };
  // Every load while the bucket is above the sand, as it comes: the bed asleep runs faster than
  // the dig needs, so the latest wrench when the test looks may already be the dig's. From
  // ~blocks, connected since this test started: the bucket's own wrench topic appears only when
  // its link spawns, and its first messages can go out before the test has connected to it.
  std::mutex above_mutex;
  double t0 = -1;  // s, when the bucket first appears (the dig's time zero)
  double above = 0;
  int above_count = 0;
  ros::Subscriber above_sub =
      n.nh.subscribe<BlockStates>(test::kNs + "blocks", 1000, [&](const BlockStates::ConstPtr& m) {
        const RigidBlockState* b = test::findBlock(*m, "bucket");
        if (!b) return;
        const std::lock_guard<std::mutex> l(above_mutex);
        if (t0 < 0) t0 = m->header.stamp.toSec();
        if (m->header.stamp.toSec() >= t0 + 0.9) return;
        above = std::max(above, std::hypot(b->coupling_force.x + b->block_force.x,
                                           b->coupling_force.y + b->block_force.y));
        ++above_count;
      });
  auto start = [&] {
    const std::lock_guard<std::mutex> l(above_mutex);
    return t0;
  };
  RigidBlockState bucket, stick;
  ASSERT_TRUE(waitFor(
      [&] { return n.block("bucket", bucket) && n.block("stick", stick) && start() >= 0; }, 60))
      << "the bucket and the stick are not blocks";
  const double t_start = start();
  // The scene ends at 6 s: the drag needs the links by 2.8 s (they came at 0.04-0.47 s here, at
  // 0.78 s in one CI run).
  ASSERT_LT(t_start, 2.8) << "the links spawned at " << t_start
                          << " s: robot_state_publisher's tf reached the node too late";
  ASSERT_TRUE(
      waitFor([&] { return n.stats.get().sim_time > t_start + 0.4 && cloud.count() > 0; }, 60));
  const int heaped_before = pointsAbove(cloud.get(), 0.17);
  EXPECT_EQ(heaped_before, 0);
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > t_start + 0.9; }, 60));
  double before = 0;
  {
    const std::lock_guard<std::mutex> l(above_mutex);
    before = above;
    ASSERT_GT(above_count, 0) << "no state of the bucket above the sand reached the test";
  }
  EXPECT_LT(before, 1.0) << "the bucket is loaded above the sand";
  double peak = 0;
  ASSERT_TRUE(waitFor(
      [&] {
        const double t = n.stats.get().sim_time;
        if (t > t_start + 2.0 && wrench.count() > 0) peak = std::max(peak, load());
        return t > t_start + 3.2;
      },
      120))
      << "the simulation did not reach t0 + 3.2 s";
  const int heaped = pointsAbove(cloud.get(), 0.17);
  std::printf(
      "bucket: in the simulation at %.3f s; %.2f N/m above the sand, %.0f N/m at most while "
      "dragged; points more than 2 cm above the bed: %d, then %d\n",
      t_start, before, peak, heaped_before, heaped);
  EXPECT_GT(peak, 108) << "the sand barely resists the bucket";
  EXPECT_GT(heaped, 40) << "the dig moved no sand";
}

// The closed-loop example (launch/blade_force_control.launch, scripts/blade_force_controller.py,
// set point 100 N/m): the blade sinks from 1 cm above the sand until the sand's horizontal force
// on it reaches the set point, then holds it while the heap ahead grows. Settled: from 3 s to
// 6 s of simulation, the force averaged over each second (100 of the node's wrenches; a single
// step's load is noisy) within 10% of the set point, and over the 3 s within 2% (the integral
// action). Not over each 0.5 s: the sand's load swings faster than the loop's 5 rad/s can
// follow (under the 10 rad/s filter), and 0.5 s means reached 89.7 N/m in one of four runs
// (the node's timing against the controller's differs from run to run); the 1 s means of
// those runs are 96.1 to 101.9 N/m, their 3 s means 99.5 to 99.8.

TEST(Robot, BladeForceControllerSettlesAtTheSetPoint) {
  test::NodeClient& n = *g_node;
  const double set_point = 100.0;
  std::mutex m;
  std::vector<std::pair<double, double>> samples;  // (simulated time, force against the motion)
  ros::Subscriber sub = n.nh.subscribe<geometry_msgs::WrenchStamped>(
      test::kNs + "obstacles/blade/wrench", 200,
      [&](const geometry_msgs::WrenchStamped::ConstPtr& w) {
        std::lock_guard<std::mutex> l(m);
        samples.emplace_back(w->header.stamp.toSec(), -w->wrench.force.x);
      });
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > 6.0; }, 120))
      << "the simulation did not reach 6 s";
  std::lock_guard<std::mutex> l(m);
  auto mean = [&](double from, double to) {
    double sum = 0;
    int count = 0;
    for (const auto& [t, f] : samples)
      if (t >= from && t < to) sum += f, ++count;
    EXPECT_GT(count, 40 * (to - from)) << "too few wrenches from " << from << " s";
    std::printf("blade force %.2f-%.2f s: %.1f N/m (%d wrenches)\n", from, to, sum / count, count);
    return sum / count;
  };
  for (double from = 3.0; from < 6.0 - 1e-9; from += 1.0)
    EXPECT_NEAR(mean(from, from + 1.0), set_point, 0.1 * set_point) << "from " << from << " s";
  EXPECT_NEAR(mean(3.0, 6.0), set_point, 0.02 * set_point);
}

int main(int argc, char** argv) {
  return test::runNodeTests(argc, argv, "test_node_robot", g_node);
}
