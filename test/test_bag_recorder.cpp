// BagRecorder writes on a thread of its own (the simulation only makes the messages and queues
// them): every message queued reaches the bag, in the order queued, and the bag is closed and
// renamed from .active when the recorder closes.
#include <gtest/gtest.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <cstdio>
#include <filesystem>
#include <map>

#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

// 0.1 s of the node's bed scene with the states sampled at every step (10 kHz asks more than
// the steps give) and a checkpoint every 0.01 s: many more messages than the queue holds
// (kQueued, 256), made faster than one thread writes them. Read back: as many as were queued
// (2,641 messages), each topic's times increasing, the last states at the run's end, and no
// .active file left.
TEST(BagRecorder, EveryMessageQueuedReachesTheBagInOrder) {
  const Scene scene = loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/node_bed.yaml");
  World world(scene.world);
  const std::string path =
      (std::filesystem::temp_directory_path() / "mpm_sdem_test_bag_recorder.bag").string();
  std::filesystem::remove(path);
  RecordDef def;
  def.state_rate = 1e4;
  def.cloud_rate = 1e3;
  def.checkpoint_rate = 100;
  long queued = 0;
  {
    BagRecorder bag(path, def, "scene text", scene.state_text);
    conversions::StatsInput stats;
    bag.record(world, stats);
    while (world.time() < 0.1 - 1e-12) {
      stepStable(world, 0.1);
      bag.record(world, stats);
    }
    bag.close();
    queued = bag.messageCount();
    EXPECT_GT(queued, static_cast<long>(4 * BagRecorder::kQueued));
  }
  EXPECT_FALSE(std::filesystem::exists(path + ".active"));
  rosbag::Bag read(path, rosbag::bagmode::Read);
  rosbag::View view(read);
  EXPECT_EQ(static_cast<long>(view.size()), queued);
  std::printf("%ld messages queued, %u in the bag\n", queued, view.size());
  std::map<std::string, ros::Time> last;
  for (const rosbag::MessageInstance& m : view) {
    auto it = last.find(m.getTopic());
    if (it != last.end()) {
      EXPECT_LE(it->second, m.getTime()) << m.getTopic();  // /tf_static twice at t = 0
      it->second = m.getTime();
    } else {
      last.emplace(m.getTopic(), m.getTime());
    }
  }
  EXPECT_NEAR(last.at("/mpm_sdem/stats").toSec(), world.time(), 1e-9);
  EXPECT_NEAR(last.at("/mpm_sdem/checkpoint").toSec(), world.time(), 1e-9);
}
