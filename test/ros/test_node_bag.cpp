// rostest (node_bag.test): the node's bag against the headless runner's for the same scene, and
// bags left by SIGINT and SIGKILL.
#include <gtest/gtest.h>
#include <mpm_sdem/BlockStates.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <map>

#include "ros_helpers.hpp"

namespace fs = std::filesystem;
using mpm_sdem::test::waitFor;

namespace {

std::string param(const std::string& name) {
  std::string v;
  if (!ros::param::get("~" + name, v)) ADD_FAILURE() << "missing ~" << name;
  return v;
}

std::map<std::string, long> topicCounts(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::map<std::string, long> counts;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) ++counts[m.getTopic()];
  return counts;
}

std::vector<mpm_sdem::BlockStates> blockStates(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::vector<mpm_sdem::BlockStates> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag))
    if (auto s = m.instantiate<mpm_sdem::BlockStates>()) out.push_back(*s);
  return out;
}

// Starts the node in a child process recording to bag; returns its pid.
pid_t startRecordingNode(const std::string& name, const std::string& bag) {
  const pid_t pid = fork();
  if (pid == 0) {
    const std::string scene = "_scene:=" + param("scene");
    const std::string b = "_bag:=" + bag;
    const std::string n = "__name:=" + name;
    execl(MPM_SDEM_NODE, MPM_SDEM_NODE, n.c_str(), scene.c_str(), b.c_str(), "_record:=true",
          "_real_time_factor:=1.0", "_threads:=1", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

}  // namespace

TEST(Bag, NodeBagHasTheTopicsAndMatchesTheHeadlessRunner) {
  const std::string node_bag = param("bag");
  ASSERT_TRUE(waitFor([&] { return fs::exists(node_bag); }, 120))
      << node_bag << " never appeared: the node did not finish and close its bag";
  // The same scene and overrides through the runner, one thread like the node.
  const std::string runner_bag = node_bag + ".runner.bag";
  const std::string cmd = std::string(MPM_SDEM_RUNNER) + " " + param("scene") +
                          " --set time.end=0.3 --threads 1 --quiet --out " + node_bag +
                          ".runner_out --bag " + runner_bag + " 2>/dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;

  // 0.3 s at the default rates: the scene and /tf_static (the domain and the static post) once,
  // checkpoints at 1 Hz (t = 0) and at the end,
  // clouds at 10 Hz (0 to 0.3 s: 4), states at 100 Hz (31): blocks, poses, outlines, stats, the
  // dynamic box on /tf and each block's wrench.
  const auto counts = topicCounts(node_bag);
  const std::map<std::string, long> expected = {{"/mpm_sdem/scene", 1},
                                                {"/mpm_sdem/checkpoint", 2},  // at 0 and the end
                                                {"/tf_static", 1},
                                                {"/mpm_sdem/particles", 4},
                                                {"/mpm_sdem/blocks", 31},
                                                {"/mpm_sdem/block_poses", 31},
                                                {"/mpm_sdem/markers", 31},
                                                {"/mpm_sdem/stats", 31},
                                                {"/mpm_sdem/obstacles/box/wrench", 31},
                                                {"/mpm_sdem/obstacles/post/wrench", 31},
                                                {"/tf", 31}};
  EXPECT_EQ(counts, expected);
  EXPECT_EQ(topicCounts(runner_bag), expected);

  // Same steps: the same bytes in every message but the stats (wall-clock figures).
  EXPECT_EQ(mpm_sdem::test::differingTopics(node_bag, runner_bag), std::vector<std::string>{});
  // And as numbers, for a readable failure.
  const auto a = blockStates(node_bag), b = blockStates(runner_bag);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) {
    ASSERT_EQ(a[k].header.stamp, b[k].header.stamp) << k;
    ASSERT_EQ(a[k].blocks.size(), b[k].blocks.size());
    for (std::size_t i = 0; i < a[k].blocks.size(); ++i) {
      EXPECT_NEAR(a[k].blocks[i].pose.position.x, b[k].blocks[i].pose.position.x, 1e-12);
      EXPECT_NEAR(a[k].blocks[i].pose.position.y, b[k].blocks[i].pose.position.y, 1e-12);
      EXPECT_NEAR(a[k].blocks[i].pose.orientation.z, b[k].blocks[i].pose.orientation.z, 1e-12);
    }
  }
  fs::remove_all(node_bag + ".runner_out");
  fs::remove(runner_bag);
}

TEST(Bag, SigintLeavesAClosedReadableBag) {
  const std::string bag = param("bag") + ".sigint.bag";
  const pid_t pid = startRecordingNode("sigint_recorder", bag);
  ASSERT_TRUE(waitFor([&] { return fs::exists(bag + ".active"); }, 20));
  ros::WallDuration(2.0).sleep();  // about 2 s of simulation at real time
  ASSERT_EQ(kill(pid, SIGINT), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  ASSERT_TRUE(fs::exists(bag)) << "no closed bag after SIGINT";
  EXPECT_FALSE(fs::exists(bag + ".active"));
  const auto counts = topicCounts(bag);
  EXPECT_GE(counts.at("/sigint_recorder/particles"), 10);  // 2 s at 10 Hz, give or take
  EXPECT_GE(counts.at("/sigint_recorder/blocks"), 100);
  fs::remove(bag);
}

TEST(Bag, SigkillLeavesABagThatRosbagReindexRecovers) {
  const std::string bag = param("bag") + ".sigkill.bag";
  const pid_t pid = startRecordingNode("sigkill_recorder", bag);
  ASSERT_TRUE(waitFor([&] { return fs::exists(bag + ".active"); }, 20));
  // Past the first chunk (768 KiB before compression: about 2.5 s of this scene's clouds of 640
  // points at 10 Hz plus its states at 100 Hz, at real time).
  ros::WallDuration(4.0).sleep();
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  ASSERT_TRUE(fs::exists(bag + ".active"));
  EXPECT_FALSE(fs::exists(bag)) << "a killed recording must not look complete";
  const std::string cmd = "rosbag reindex --output-dir=" + fs::path(bag).parent_path().string() +
                          " " + bag + ".active >/dev/null 2>&1 || true";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const auto counts = topicCounts(bag + ".active");
  EXPECT_GE(counts.at("/sigkill_recorder/blocks"), 50) << "the chunks written before the kill";
  fs::remove(bag + ".active");
  fs::remove(bag + ".orig.active");
}

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_node_bag");
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
