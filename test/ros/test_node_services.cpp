// rostest: the node's topics, tf and services against a running node (node_services.test).
#include <gtest/gtest.h>
#include <mpm_sdem/ListObstacles.h>
#include <mpm_sdem/ObstacleCommand.h>
#include <mpm_sdem/RemoveObstacle.h>
#include <mpm_sdem/SetObstacleState.h>
#include <mpm_sdem/SpawnObstacle.h>
#include <mpm_sdem/StepSimulation.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "ros_helpers.hpp"

using namespace mpm_sdem;
using test::findBlock;
using test::waitFor;

namespace {

using Node = test::NodeClient;
using test::square;
Node* g_node = nullptr;

}  // namespace

TEST(Node, PublishesCloudBlocksAndTf) {
  Node& n = *g_node;
  ASSERT_TRUE(waitFor([&] { return n.cloud.has() && n.blocks.has() && n.stats.has(); }, 20));
  const sensor_msgs::PointCloud2 c = n.cloud.get();
  EXPECT_EQ(c.height, 1u);
  EXPECT_EQ(c.width, 640u);  // node_bed.yaml: 40 x 4 cells x 4 points, no decimation
  EXPECT_EQ(c.header.frame_id, "world");
  std::vector<std::string> fields;
  for (const auto& f : c.fields) fields.push_back(f.name);
  EXPECT_EQ(fields, (std::vector<std::string>{"x", "y", "z", "vx", "vy", "speed", "pressure",
                                              "von_mises", "material", "kind"}));
  RigidBlockState box;
  ASSERT_TRUE(n.block("box", box));
  EXPECT_EQ(box.body_type, RigidBlockState::DYNAMIC);
  ASSERT_TRUE(
      waitFor([&] { return n.tf.canTransform("world", "mpm_sdem/box", ros::Time(0)); }, 10));
  // The box rests on the bed: the material carries its weight (0.04 m square at 500 kg/m^3,
  // rounding included: 0.8 kg/m, 7.85 N/m), which only IMP contacts can supply. It drops 8.5 mm
  // and rings on the soft bed first: the force swings by up to 30% before 0.3 s and stays within
  // 1.5% of the weight after 0.5 s (the runner on node_bed.yaml), so read it once it rests.
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > 0.6; }, 20));
  ASSERT_TRUE(n.block("box", box));
  EXPECT_GT(box.contact_count, 0u);
  EXPECT_NEAR(box.coupling_force.y, 0.8 * 9.81, 0.1 * 0.8 * 9.81);
}

TEST(Node, SpawnedBlockAppearsFallsOntoTheMaterialAndIsRemoved) {
  Node& n = *g_node;
  SpawnObstacle s = square("dropper", 0.25, 0.12, 0.015, SpawnObstacle::Request::DYNAMIC);
  s = n.call("spawn_obstacle", s);
  ASSERT_TRUE(s.response.success) << s.response.message;
  RigidBlockState b;
  ASSERT_TRUE(waitFor([&] { return n.block("dropper", b); }, 5));
  ASSERT_TRUE(
      waitFor([&] { return n.tf.canTransform("world", "mpm_sdem/dropper", ros::Time(0)); }, 5));
  // It falls about 6 cm onto the bed and the material pushes back.
  ASSERT_TRUE(waitFor([&] { return n.block("dropper", b) && b.contact_count > 0; }, 20))
      << "the spawned block never touched the material";
  ASSERT_TRUE(waitFor([&] { return n.block("dropper", b) && b.coupling_force.y > 0; }, 5));
  EXPECT_LT(b.pose.position.y, 0.12);
  RemoveObstacle r;
  r.request.name = "dropper";
  r = n.call("remove_obstacle", r);
  ASSERT_TRUE(r.response.success) << r.response.message;
  ASSERT_TRUE(waitFor([&] { return !n.block("dropper", b); }, 5));
}

TEST(Node, KinematicBlockMovesWithTheCommandedTwist) {
  Node& n = *g_node;
  SpawnObstacle s = square("blade", 0.2, 0.15, 0.01, SpawnObstacle::Request::KINEMATIC);
  s = n.call("spawn_obstacle", s);
  ASSERT_TRUE(s.response.success) << s.response.message;
  SetObstacleState set;
  set.request.name = "blade";
  set.request.set_twist = true;
  set.request.twist.linear.x = 0.05;
  set = n.call("set_obstacle_state", set);
  ASSERT_TRUE(set.response.success) << set.response.message;
  // x(t2) - x(t1) = v (t2 - t1) between two published states, pose and stamp from the same
  // message (Box2D integrates a kinematic body exactly up to its single precision: 1e-6 m).
  struct Sample {
    double t = 0;
    RigidBlockState b;
  };
  auto sample = [&](Sample& out) {
    const BlockStates s = n.blocks.get();
    const RigidBlockState* b = findBlock(s, "blade");
    if (b) out = {s.header.stamp.toSec(), *b};
    return b != nullptr;
  };
  Sample s1, s2;
  ASSERT_TRUE(waitFor([&] { return sample(s1) && s1.b.twist.linear.x > 0.04; }, 5));
  ASSERT_TRUE(waitFor([&] { return sample(s2) && s2.t > s1.t + 0.3; }, 10));
  EXPECT_NEAR(s2.b.twist.linear.x, 0.05, 1e-6);
  EXPECT_NEAR(s2.b.pose.position.y, 0.15, 1e-6);
  EXPECT_NEAR(s2.b.pose.position.x - s1.b.pose.position.x, 0.05 * (s2.t - s1.t), 1e-6);
  // The streamed command reverses it.
  ObstacleCommand cmd;
  cmd.name = "blade";
  cmd.twist.linear.x = -0.05;
  n.cmd.publish(cmd);
  ASSERT_TRUE(waitFor([&] { return sample(s1) && s1.b.twist.linear.x < -0.04; }, 5));
  ASSERT_TRUE(waitFor([&] { return sample(s2) && s2.t > s1.t + 0.2; }, 10));
  EXPECT_NEAR(s2.b.pose.position.x - s1.b.pose.position.x, -0.05 * (s2.t - s1.t), 1e-6);
  RemoveObstacle r;
  r.request.name = "blade";
  EXPECT_TRUE(n.call("remove_obstacle", r).response.success);
}

TEST(Node, PauseStepResumeReset) {
  Node& n = *g_node;
  ASSERT_TRUE(n.trigger("pause"));
  // Paused: the step count stays where the pause left it.
  ros::WallDuration(0.3).sleep();
  const SimStats paused = n.stats.get();
  EXPECT_TRUE(paused.paused);
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(n.stats.get().step, paused.step);
  StepSimulation step;
  step.request.steps = 25;
  step = n.call("step", step);
  ASSERT_TRUE(step.response.success) << step.response.message;
  // Answered at once: the loop takes the steps after the answer.
  EXPECT_EQ(step.response.step, paused.step);
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step == paused.step + 25; }, 5));
  EXPECT_GT(n.stats.get().sim_time, paused.sim_time);
  ros::WallDuration(0.3).sleep();
  EXPECT_EQ(n.stats.get().step, paused.step + 25) << "stepped past the steps asked for";
  ASSERT_TRUE(n.trigger("resume"));
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step > paused.step + 200; }, 10));
  // Reset: back to the scene's start, spawned blocks gone.
  SpawnObstacle s = square("temporary", 0.2, 0.15, 0.01, SpawnObstacle::Request::STATIC);
  s = n.call("spawn_obstacle", s);
  ASSERT_TRUE(s.response.success) << s.response.message;
  const double before = n.stats.get().sim_time;
  ASSERT_TRUE(n.trigger("reset"));
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time < 0.5 * before; }, 5));
  ListObstacles list;
  list = n.call("list_obstacles", list);
  ASSERT_TRUE(list.response.success) << list.response.message;
  ASSERT_EQ(list.response.states.blocks.size(), 2u);
  EXPECT_EQ(list.response.states.blocks[0].name, "post");
  EXPECT_EQ(list.response.states.blocks[1].name, "box");
}

int main(int argc, char** argv) {
  return test::runNodeTests(argc, argv, "test_node_services", g_node);
}
