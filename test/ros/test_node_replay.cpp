// rostest: re-simulation and restart of node runs.
// - node_replay.test: the node records a run while a client commands its obstacles (a spawned
//   block, a held load, a velocity command, a teleport); mpm_sdem_run --replay-commands on the
//   same scene reproduces the node's bag message for message, and on a changed scene runs the
//   same commands to another result; resumed from the node's bag between its checkpoints, it
//   steps on under the node's commands to the same bag.
// - node_resume.test: a node started with ~resume from a runner's bag continues /clock, tf and
//   the bag from the time asked for (its bag's checkpoint before it, then the steps to it): its
//   bag equals the uninterrupted run's.
// - node_reconfigure.test: dynamic_reconfigure's ~set_parameters refuses a value past each
//   setting's bound, naming it as asked for, and accepts one on it; it changes gravity and the
//   real-time factor between steps; an out-of-range gravity is refused and the values in effect
//   come back; the gravity is a recorded command, so the runner replays the node's bag exactly.
#include <dynamic_reconfigure/Reconfigure.h>
#include <geometry_msgs/Twist.h>
#include <gtest/gtest.h>
#include <mpm_sdem/ApplyObstacleWrench.h>
#include <mpm_sdem/GetObstacleState.h>
#include <mpm_sdem/RecordedCommand.h>
#include <mpm_sdem/SetObstacleState.h>
#include <mpm_sdem/StepSimulation.h>
#include <rosgraph_msgs/Clock.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <limits>
#include <map>
#include <set>

#include "ros_helpers.hpp"

namespace fs = std::filesystem;
using namespace mpm_sdem;
using test::waitFor;

namespace {

test::NodeClient* g_node = nullptr;

std::string param(const std::string& name) {
  std::string v;
  if (!ros::param::get("~" + name, v)) ADD_FAILURE() << "missing ~" << name;
  return v;
}

int run(const std::string& cmd) {
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::vector<BlockStates> blockStates(const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::vector<BlockStates> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag))
    if (auto s = m.instantiate<BlockStates>()) out.push_back(*s);
  return out;
}

std::set<int> commandKinds(const std::string& path, long& count) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::set<int> kinds;
  count = 0;
  for (const rosbag::MessageInstance& m : rosbag::View(bag))
    if (auto c = m.instantiate<RecordedCommand>()) {
      kinds.insert(c->kind);
      ++count;
    }
  return kinds;
}

}  // namespace

TEST(Replay, TheRunnerReplaysTheNodesCommandsExactly) {
  test::NodeClient& n = *g_node;
  const std::string node_bag = param("bag");
  ros::Publisher cmd_vel =
      n.nh.advertise<geometry_msgs::Twist>(test::kNs + "obstacles/blade/cmd_vel", 1);
  ASSERT_TRUE(waitFor([&] { return cmd_vel.getNumSubscribers() > 0 && n.stats.has(); }, 20));
  // Started paused: a block spawned at t = 0, then 0.6 s of simulation at half real time while
  // the others come.
  SpawnObstacle rock = test::square("rock", -0.03, 0.1, 0.01, SpawnObstacle::Request::DYNAMIC);
  ASSERT_TRUE(n.call("spawn_obstacle", rock).response.success) << rock.response.message;
  ASSERT_TRUE(n.trigger("resume"));
  ros::WallDuration(0.1).sleep();
  ApplyObstacleWrench w;
  w.request.name = "box";
  w.request.wrench.force.x = 3;
  w.request.duration = 0.2;
  ASSERT_TRUE(n.call("apply_obstacle_wrench", w).response.success) << w.response.message;
  geometry_msgs::Twist t;
  t.linear.x = 0.05;
  test::publishRepeatedly(cmd_vel, t, 5, 0.03);
  SetObstacleState s;
  s.request.name = "rock";
  s.request.set_pose = true;
  s.request.pose.x = -0.05;
  s.request.pose.y = 0.15;
  EXPECT_TRUE(n.call("set_obstacle_state", s).response.success) << s.response.message;
  ASSERT_TRUE(waitFor([&] { return fs::exists(node_bag); }, 60))
      << node_bag << " never appeared: the node did not reach its end and close the bag";
  long count = 0;
  const std::set<int> kinds = commandKinds(node_bag, count);
  EXPECT_EQ(kinds, (std::set<int>{RecordedCommand::ADD_BLOCK, RecordedCommand::SET_POSE,
                                  RecordedCommand::SET_VELOCITY, RecordedCommand::ADD_LOAD}))
      << "the commands the node applied are all recorded";
  std::printf("the node recorded %ld commands\n", count);

  // The same scene through the runner with the node's commands: the same bag, but the stats.
  const std::string scene = param("scene");
  const std::string replay = node_bag + ".replay.bag";
  const std::string base = std::string(MPM_SDEM_RUNNER) + " " + scene +
                           " --set time.end=0.6 --threads 1 --quiet --replay-commands " + node_bag +
                           " --out " + node_bag + ".out";
  ASSERT_EQ(run(base + " --bag " + replay), 0);
  EXPECT_EQ(test::differingTopics(node_bag, replay), std::vector<std::string>{})
      << "topics whose messages differ between the node's run and its replay";
  // Resumed at 0.12 s from the node's bag (its checkpoints: t = 0 and the end) the runner steps
  // from t = 0 under the node's commands, then replays the rest (the held load's and the
  // velocity commands' come on both sides of 0.12 s): the same bag again.
  const std::string resumed = node_bag + ".resumed.bag";
  ASSERT_EQ(run(base + " --resume " + node_bag + "@0.12 --bag " + resumed), 0);
  EXPECT_EQ(test::differingTopics(node_bag, resumed), std::vector<std::string>{})
      << "topics whose messages differ between the node's run and its resumed replay";

  // A heavier box under the same commands: the blade moves as commanded, the box (pushed by
  // the same load, on the same sand) otherwise.
  const std::string changed = node_bag + ".heavier.bag";
  ASSERT_EQ(run(base + " --set blocks.box.density=4000 --bag " + changed), 0);
  const auto a = blockStates(node_bag), b = blockStates(changed);
  ASSERT_EQ(a.size(), b.size());
  const RigidBlockState *blade_a = test::findBlock(a.back(), "blade"),
                        *blade_b = test::findBlock(b.back(), "blade"),
                        *box_a = test::findBlock(a.back(), "box"),
                        *box_b = test::findBlock(b.back(), "box");
  ASSERT_TRUE(blade_a && blade_b && box_a && box_b && test::findBlock(b.back(), "rock"));
  EXPECT_EQ(blade_a->pose.position.y, blade_b->pose.position.y) << "commanded: the same";
  const double apart = std::hypot(box_a->pose.position.x - box_b->pose.position.x,
                                  box_a->pose.position.y - box_b->pose.position.y);
  EXPECT_GT(apart, 1e-4) << "a box 8 times heavier ends elsewhere under the same load";
  std::printf("the heavier box ends %.3g mm from where the node's did\n", 1e3 * apart);
  // mpm_sdem_compare reports the difference (and writes its plot).
  EXPECT_EQ(run(std::string(MPM_SDEM_COMPARE) + " " + node_bag + " " + changed + " > " + node_bag +
                ".compare.txt 2>&1"),
            0);
  for (const std::string& f : {replay, resumed, changed}) fs::remove(f);
  fs::remove_all(node_bag + ".out");
}

TEST(Resume, NodeContinuesClockTfAndBagFromACheckpoint) {
  test::NodeClient& n = *g_node;
  // The uninterrupted run, by the runner: checkpoints every 0.1 s.
  const std::string scene = param("scene"), dir = param("dir");
  fs::create_directories(dir);
  const std::string whole = dir + "/whole.bag", resumed = dir + "/resumed.bag";
  ASSERT_EQ(run(std::string(MPM_SDEM_RUNNER) + " " + scene +
                " --set time.end=0.4 --threads 1 --quiet --bag-checkpoint-rate 10 --bag " + whole +
                " --out " + dir + "/out"),
            0);
  // A node resumes it from its checkpoint at 0.2 s and runs to the end.
  test::Latest<rosgraph_msgs::Clock> clock(n.nh, "/clock");
  std::mutex m;
  double first_clock = -1;
  ros::Subscriber first = n.nh.subscribe<rosgraph_msgs::Clock>(
      "/clock", 100, [&](const rosgraph_msgs::Clock::ConstPtr& c) {
        std::lock_guard<std::mutex> l(m);
        if (first_clock < 0) first_clock = c->clock.toSec();
      });
  // Its parameters on the server (a list cannot be given on the command line).
  const std::string ns = "/mpm_sdem/";
  ros::param::set(ns + "scene", scene);
  ros::param::set(ns + "set", std::vector<std::string>{"time.end=0.4"});
  ros::param::set(ns + "resume", whole + "@0.25");
  ros::param::set(ns + "record", true);
  ros::param::set(ns + "bag", resumed);
  ros::param::set(ns + "end_action", std::string("shutdown"));
  ros::param::set(ns + "threads", 1);
  ros::param::set(ns + "bag_checkpoint_rate", 10.0);  // the runner's
  ros::param::set(ns + "start_paused", true);
  const pid_t pid = fork();
  if (pid == 0) {
    // Not this process's sockets (its ROS connections): the node makes its own.
    for (int fd = 3; fd < 1024; ++fd) close(fd);
    execl(MPM_SDEM_NODE, MPM_SDEM_NODE, "__name:=mpm_sdem", static_cast<char*>(nullptr));
    _exit(127);
  }
  // The node is stopped whatever happens below (it waits paused otherwise).
  struct Stop {
    pid_t pid;
    ~Stop() {
      if (waitpid(pid, nullptr, WNOHANG) == 0) kill(pid, SIGKILL);
    }
  } stop{pid};
  ASSERT_TRUE(waitFor([&] { return clock.has() && n.stats.has(); }, 30));
  {
    // Started paused within a step (0.3 ms) of 0.25 s: the bag's checkpoint at 0.2 s, then
    // the steps the runner took from there.
    std::lock_guard<std::mutex> l(m);
    EXPECT_LE(first_clock, 0.25);
    EXPECT_GT(first_clock, 0.25 - 3e-4);
    EXPECT_NEAR(n.stats.get().sim_time, first_clock, 1e-9);  // a stamp is whole ns
  }
  {
    // One step on, at the runner's sample of 0.25 s: the box where the uninterrupted run had it.
    StepSimulation one;
    one.request.steps = 1;
    ASSERT_TRUE(n.call("step", one).response.success) << one.response.message;
    ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > first_clock; }, 10));
    GetObstacleState g;
    g.request.name = "box";
    g = n.call("get_obstacle_state", g);
    ASSERT_TRUE(g.response.success) << g.response.message;
    EXPECT_GE(g.response.header.stamp.toSec(), 0.25);
    bool found = false;
    for (const BlockStates& s : blockStates(whole)) {
      if (s.header.stamp != g.response.header.stamp) continue;
      const RigidBlockState* box = test::findBlock(s, "box");
      ASSERT_TRUE(box);
      EXPECT_EQ(g.response.state.pose.position.x, box->pose.position.x);
      EXPECT_EQ(g.response.state.pose.position.y, box->pose.position.y);
      found = true;
    }
    EXPECT_TRUE(found) << "the whole run's states at 0.25 s";
  }
  EXPECT_TRUE(n.trigger("resume"));
  geometry_msgs::TransformStamped box;
  EXPECT_TRUE(waitFor(
      [&] {
        try {
          box = n.tf.lookupTransform("world", "mpm_sdem/box", ros::Time(0));
          return true;
        } catch (const tf2::TransformException&) {
          return false;
        }
      },
      10));
  EXPECT_GT(box.header.stamp.toSec(), 0.2) << "the box's frame goes on from the resumed state";
  int status = 0;
  ASSERT_EQ(waitpid(pid, &status, 0), pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  ASSERT_TRUE(fs::exists(resumed));
  EXPECT_EQ(test::differingTopics(whole, resumed), std::vector<std::string>{})
      << "topics whose messages differ between the uninterrupted run and the resumed one";
  fs::remove_all(dir);
}

namespace {

// What ~set_parameters answers: the values in force, by name, and why a change was refused.
struct Answer {
  std::map<std::string, double> values;  // the doubles, and cloud_decimation
  std::string refused;
};

Answer toAnswer(const dynamic_reconfigure::Config& c) {
  Answer a;
  for (const auto& d : c.doubles) a.values[d.name] = d.value;
  for (const auto& i : c.ints) a.values[i.name] = i.value;
  for (const auto& s : c.strs)
    if (s.name == "refused") a.refused = s.value;
  return a;
}

// ~set_parameters with the given values (cloud_decimation as an int, the rest as doubles).
Answer reconfigureAnswer(const std::map<std::string, double>& values) {
  dynamic_reconfigure::Reconfigure r;
  for (const auto& [name, value] : values) {
    if (name == "cloud_decimation") {
      dynamic_reconfigure::IntParameter i;
      i.name = name;
      i.value = static_cast<int>(value);
      r.request.config.ints.push_back(i);
      continue;
    }
    dynamic_reconfigure::DoubleParameter d;
    d.name = name;
    d.value = value;
    r.request.config.doubles.push_back(d);
  }
  EXPECT_TRUE(ros::service::call(test::kNs + "set_parameters", r));
  return toAnswer(r.response.config);
}

std::map<std::string, double> reconfigure(const std::map<std::string, double>& values) {
  return reconfigureAnswer(values).values;
}

}  // namespace

// Every setting's bounds (runtimeProblem's, World::gravityProblem's): a value just past one is
// refused, named as asked for (not clamped to the cfg's range, as dynamic_reconfigure's server
// did: real_time_factor -1 ran as fast as possible), with the value in force answered and
// published on ~parameter_updates; a value on the bound is accepted. Runs first, while the node
// is paused, and puts every value back.
TEST(Reconfigure, EachBoundRefusesWithTheValueAskedFor) {
  test::NodeClient& n = *g_node;
  test::Latest<dynamic_reconfigure::Config> updates(n.nh, test::kNs + "parameter_updates");
  ASSERT_TRUE(ros::service::waitForService(test::kNs + "set_parameters", ros::Duration(20)));
  ASSERT_TRUE(waitFor([&] { return n.stats.has() && updates.has(); }, 20));
  const std::map<std::string, double> start = reconfigure({});
  const double inf = std::numeric_limits<double>::infinity();
  struct Bound {
    std::string name;
    double refused;   // just past the bound
    const char* as;   // how the refusal prints it
    double accepted;  // on the bound (or, for an open one, just inside)
  };
  const Bound bounds[] = {
      {"real_time_factor", -1, "real_time_factor -1", 0},
      {"real_time_factor", inf, "real_time_factor inf", 1e6},
      {"particles_rate", -1, "particles_rate -1", 0},
      {"particles_rate", inf, "particles_rate inf", 1e6},
      {"blocks_rate", -5, "blocks_rate -5", 0},
      {"blocks_rate", inf, "blocks_rate inf", 1e6},
      {"stats_rate", -0.5, "stats_rate -0.5", 0},
      {"stats_rate", inf, "stats_rate inf", 1e6},
      {"image_rate", -1, "image_rate -1", 0},
      {"image_rate", inf, "image_rate inf", 1e6},
      {"terrain_rate", -1, "terrain_rate -1", 0},
      {"terrain_rate", inf, "terrain_rate inf", 1e6},
      {"clock_rate", -1, "clock_rate -1", 0},
      {"clock_rate", inf, "clock_rate inf", 1e6},
      {"cloud_decimation", 0, "cloud_decimation 0", 1},
      {"cloud_decimation", -3, "cloud_decimation -3", 1000},
      {"cmd_vel_timeout", -1, "cmd_vel_timeout -1", 0},
      {"cmd_vel_timeout", inf, "cmd_vel_timeout inf", 1e6},
      {"follow_tf_delay", 0, "follow_tf_delay 0", 1e-6},
      {"follow_tf_delay", 5.5, "follow_tf_delay 5.5", 5},
      {"follow_tf_max_speed", 0, "follow_tf_max_speed 0", 1e-6},
      {"follow_tf_max_speed", 1000.5, "follow_tf_max_speed 1000.5", 1000},
      {"gravity_x", 10000.5, "gravity_x 10000.5", 10000},
      {"gravity_y", -20000, "gravity_y -20000", -10000},
      {"gravity_y", inf, "gravity_y inf", -10000},
  };
  for (const Bound& b : bounds) {
    SCOPED_TRACE(b.as);
    // gravity_x's bound with gravity_y at 0 and the other way round: the magnitude is bounded.
    if (b.name == "gravity_x") {
      ASSERT_EQ(reconfigureAnswer({{"gravity_y", 0}}).refused, "");
    }
    if (b.name == "gravity_y") {
      ASSERT_EQ(reconfigureAnswer({{"gravity_x", 0}}).refused, "");
    }
    const Answer before = reconfigureAnswer({});
    const Answer a = reconfigureAnswer({{b.name, b.refused}});
    EXPECT_EQ(a.values, before.values) << "a refused change leaves every value in force";
    EXPECT_NE(a.refused.find(std::string("refused ") + b.as + ":"), std::string::npos) << a.refused;
    // The server publishes what it answered: the value in force, and the refusal.
    EXPECT_TRUE(waitFor([&] { return toAnswer(updates.get()).refused == a.refused; }, 5));
    EXPECT_EQ(toAnswer(updates.get()).values, before.values);
    const Answer ok = reconfigureAnswer({{b.name, b.accepted}});
    EXPECT_EQ(ok.refused, "") << "the value on the bound is accepted";
    EXPECT_EQ(ok.values.at(b.name), b.accepted);
    reconfigure(start);
  }
  // Back to the start: the next test begins from the node's own values.
  EXPECT_EQ(reconfigure({}), start);
  EXPECT_EQ(reconfigureAnswer({}).refused, "");
}

TEST(Reconfigure, GravityAndPacingChangeBetweenStepsAndReplay) {
  test::NodeClient& n = *g_node;
  const std::string node_bag = param("bag");
  ASSERT_TRUE(ros::service::waitForService(test::kNs + "set_parameters", ros::Duration(20)));
  ASSERT_TRUE(waitFor([&] { return n.stats.has(); }, 20));
  // The server starts with the values the node runs with: its parameter and the scene's gravity.
  std::map<std::string, double> now = reconfigure({});
  EXPECT_EQ(now["real_time_factor"], 0.5);
  EXPECT_EQ(now["gravity_x"], 0.0);
  EXPECT_EQ(now["gravity_y"], -9.81);
  // Accepted while paused: applied before the first step.
  now = reconfigure({{"gravity_x", 2.0}, {"gravity_y", -5.0}, {"real_time_factor", 1.0}});
  EXPECT_EQ(now["gravity_x"], 2.0);
  EXPECT_EQ(now["gravity_y"], -5.0);
  EXPECT_EQ(now["real_time_factor"], 1.0);
  // Each component in its range, the vector past 1e4 m/s^2: refused, the values in effect back.
  now = reconfigure({{"gravity_x", 9000.0}, {"gravity_y", -9000.0}});
  EXPECT_EQ(now["gravity_x"], 2.0);
  EXPECT_EQ(now["gravity_y"], -5.0);
  ASSERT_TRUE(n.trigger("resume"));
  ASSERT_TRUE(waitFor([&] { return n.stats.get().sim_time > 0.3; }, 30));
  // A change while running: applied between two steps.
  reconfigure({{"gravity_y", -12.0}});
  ASSERT_TRUE(waitFor([&] { return fs::exists(node_bag); }, 60))
      << node_bag << " never appeared: the node did not reach its end and close the bag";
  // Both changes of gravity are in the bag, at their times, after those of the bounds' test
  // (all before the first step).
  std::vector<double> gravity_y;
  {
    rosbag::Bag bag(node_bag, rosbag::bagmode::Read);
    for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
      const auto c = m.instantiate<RecordedCommand>();
      if (!c || c->kind != RecordedCommand::SET_GRAVITY) continue;
      gravity_y.push_back(c->vector.y);
      if (c->vector.y != -12.0) {
        EXPECT_EQ(c->time, 0.0) << "applied before the first step";
      }
    }
  }
  ASSERT_GE(gravity_y.size(), 2u);
  EXPECT_EQ(std::vector<double>(gravity_y.end() - 2, gravity_y.end()),
            (std::vector<double>{-5.0, -12.0}));
  // The runner under the node's commands: the same bag, but the stats.
  const std::string replay = node_bag + ".replay.bag";
  ASSERT_EQ(run(std::string(MPM_SDEM_RUNNER) + " " + param("scene") +
                " --set time.end=0.6 --threads 1 --quiet --replay-commands " + node_bag +
                " --out " + node_bag + ".out --bag " + replay),
            0);
  EXPECT_EQ(test::differingTopics(node_bag, replay), std::vector<std::string>{})
      << "topics whose messages differ between the node's run and its replay";
  fs::remove(replay);
  fs::remove_all(node_bag + ".out");
}

int main(int argc, char** argv) {
  return test::runNodeTests(argc, argv, "test_node_replay", g_node);
}
