// rostest: bad requests, one class per .test file (each its own master and node, so that no case
// depends on another's leftovers). Every bad request is refused or ignored with a message, and
// after each the node is alive, publishing and advancing (expectAdvancing).
#include <gtest/gtest.h>
#include <mpm_sdem/ListObstacles.h>
#include <mpm_sdem/RemoveObstacle.h>
#include <mpm_sdem/SetObstacleState.h>
#include <mpm_sdem/StepSimulation.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <unistd.h>
#include <visualization_msgs/Marker.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <thread>

#include "ros_helpers.hpp"

using namespace mpm_sdem;
using test::waitFor;

namespace {

using Node = test::NodeClient;
Node* g_node = nullptr;
const double kNan = std::numeric_limits<double>::quiet_NaN();
const double kInf = std::numeric_limits<double>::infinity();

// The node answers a service, publishes ~stats and ~particles, and its step count and
// simulated time both move on within a few seconds.
void expectAdvancing(Node& n, const std::string& after) {
  ASSERT_TRUE(waitFor([&] { return n.stats.has() && n.cloud.has(); }, 20)) << after;
  const SimStats s0 = n.stats.get();
  const long clouds = n.cloud.count();
  ListObstacles list;
  ASSERT_TRUE(ros::service::call(test::kNs + "list_obstacles", list)) << "dead after " << after;
  EXPECT_TRUE(list.response.success) << after;
  EXPECT_TRUE(waitFor(
      [&] {
        const SimStats s = n.stats.get();
        return s.step > s0.step + 10 && s.sim_time > s0.sim_time && n.cloud.count() > clouds;
      },
      10))
      << "not advancing after " << after;
  EXPECT_TRUE(std::isfinite(n.stats.get().total_energy)) << after;
}

struct Bad {
  std::string why;     // what is wrong
  std::string reason;  // expected in the message
};

void expectRefused(bool success, const std::string& message, const Bad& bad) {
  EXPECT_FALSE(success) << bad.why;
  EXPECT_NE(message.find(bad.reason), std::string::npos)
      << bad.why << ": '" << message.substr(0, 300) << "'";
  EXPECT_LT(message.size(), 1000u) << bad.why << ": the message echoes the input";
}

// Runs `cmd`, which writes its output to `log` (started with `args`): it must exit with status 1
// within its timeout, its output holding `reason`.
void expectExitNaming(const std::string& cmd, const std::filesystem::path& log,
                      const std::string& args, const std::string& reason);

// The processes a refusal test starts, two at a time (each only reads its parameters and
// exits: no OpenMP work, and their logs and node names are their own).
struct Refusal {
  std::string cmd, log, args, reason;
};
void expectAllExitNaming(const std::vector<Refusal>& cases) {
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i = next++; i < cases.size(); i = next++)
      expectExitNaming(cases[i].cmd, cases[i].log, cases[i].args, cases[i].reason);
  };
  std::thread other(work);
  work();
  other.join();
}

void expectExitNaming(const std::string& cmd, const std::filesystem::path& log,
                      const std::string& args, const std::string& reason) {
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status)) << args;
  EXPECT_EQ(WEXITSTATUS(status), 1) << args << " (124: it hung)";
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find(reason), std::string::npos) << args << ": " << text;
}

}  // namespace

TEST(Requests, BadSpawnsAreRefused) {
  Node& n = *g_node;
  expectAdvancing(n, "start");
  const SpawnObstacle ok = test::square("fine", 0.2, 0.15, 0.01, SpawnObstacle::Request::DYNAMIC);
  std::vector<std::pair<Bad, SpawnObstacle>> cases;
  auto add = [&](const std::string& why, const std::string& reason, auto change) {
    SpawnObstacle s = ok;
    change(s.request);
    cases.push_back({{why, reason}, s});
  };
  using Req = SpawnObstacle::Request;
  add("NaN pose", "pose", [](Req& r) { r.pose.x = kNan; });
  add("infinite twist", "twist", [](Req& r) { r.twist.angular.z = kInf; });
  add("twist of 1e15 m/s", "at most 1000 m/s", [](Req& r) { r.twist.linear.x = 1e15; });
  add("spin of 1e30 rad/s", "at most 1000 m/s", [](Req& r) { r.twist.angular.z = 1e30; });
  add("static block with a twist", "a static block does not move", [](Req& r) {
    r.body_type = Req::STATIC;
    r.twist.linear.x = 0.1;
  });
  add("density 1e300 (float overflow in Box2D)", "density", [](Req& r) { r.density = 1e300; });
  add("density 1e-300 (zero step)", "density", [](Req& r) { r.density = 1e-300; });
  add("dynamic without density", "density", [](Req& r) { r.density = 0; });
  add("restitution above 1", "restitution", [](Req& r) { r.restitution = 1.5; });
  add("friction 1e300", "friction", [](Req& r) { r.friction = 1e300; });
  add("zero rounding", "rounding", [](Req& r) { r.rounding = 0; });
  add("rounding 1e300", "rounding", [](Req& r) { r.rounding = 1e300; });
  add("vertex at 1e300 m", "vertices", [](Req& r) { r.vertices[1].x = 1e300; });
  add("9 vertices", "at most 8", [](Req& r) {
    r.vertices.resize(9);
    for (int k = 0; k < 9; ++k) {
      r.vertices[k].x = 0.01 * std::cos(2 * M_PI * k / 9);
      r.vertices[k].y = 0.01 * std::sin(2 * M_PI * k / 9);
    }
  });
  add("non-convex", "vertices", [](Req& r) {
    r.vertices[2].x = -0.004;
    r.vertices[2].y = -0.004;
  });
  add("collinear vertex", "vertices", [](Req& r) { r.vertices[2].x = r.vertices[2].y = 0; });
  add("NaN disk radius", "disk_radius", [](Req& r) {
    r.vertices.clear();
    r.disk_radius = kNan;
  });
  add("name clash", "exists", [](Req& r) { r.name = "post"; });
  add("empty name", "must not be empty", [](Req& r) { r.name = ""; });
  add("name with a space", "a ROS name and tf frame", [](Req& r) { r.name = "block 1"; });
  add("name a path", "a ROS name and tf frame", [](Req& r) { r.name = "../../etc/passwd"; });
  add("name with a newline", "a ROS name and tf frame", [](Req& r) { r.name = "a\nb"; });
  add("10 MB name", "at most 64 characters", [](Req& r) { r.name = std::string(10 << 20, 'a'); });
  add("outside the domain", "outside the domain", [](Req& r) { r.pose.x = 0.395; });
  add("inside the material", "overlaps the material", [](Req& r) { r.pose.y = 0.03; });
  add("overlapping block 'post'", "overlaps block 'post'", [](Req& r) {
    r.pose.x = 0.35;
    r.pose.y = 0.1;
  });
  add("unknown body type", "body_type", [](Req& r) { r.body_type = 7; });
  for (const auto& [bad, req] : cases) {
    const SpawnObstacle r = n.call("spawn_obstacle", req);
    expectRefused(r.response.success, r.response.message, bad);
    expectAdvancing(n, bad.why);
  }
  ListObstacles list = n.call("list_obstacles", ListObstacles());
  EXPECT_EQ(list.response.states.blocks.size(), 2u) << "a refused spawn left a block behind";
}

TEST(Requests, BadStateChangesAreRefused) {
  Node& n = *g_node;
  expectAdvancing(n, "start");
  std::vector<std::pair<Bad, SetObstacleState>> cases;
  auto add = [&](const std::string& why, const std::string& reason, auto change) {
    SetObstacleState s;
    s.request.name = "box";
    change(s.request);
    cases.push_back({{why, reason}, s});
  };
  using Req = SetObstacleState::Request;
  add("nothing to set", "nothing to do", [](Req&) {});
  add("no such block", "no block named", [](Req& r) {
    r.name = "nonexistent";
    r.set_twist = true;
  });
  add("10 MB name", "at most 64 characters", [](Req& r) {
    r.name = std::string(10 << 20, 'b');
    r.set_twist = true;
  });
  add("twist of a static block", "a static block does not move", [](Req& r) {
    r.name = "post";
    r.set_twist = true;
    r.twist.linear.x = 0.1;
  });
  for (double v : {1e15, 1e30}) {
    add("twist " + std::to_string(v) + " m/s (dt 1e-77 s)", "at most 1000 m/s", [v](Req& r) {
      r.set_twist = true;
      r.twist.linear.x = v;
    });
  }
  add("NaN twist", "twist", [](Req& r) {
    r.set_twist = true;
    r.twist.angular.z = kNan;
  });
  add("NaN pose", "pose", [](Req& r) {
    r.set_pose = true;
    r.pose.x = kNan;
  });
  add("pose outside the domain", "outside the domain", [](Req& r) {
    r.set_pose = true;
    r.pose.x = 5;
    r.pose.y = 0.1;
  });
  add("onto block 'post'", "overlaps block 'post'", [](Req& r) {
    r.set_pose = true;
    r.pose.x = 0.35;
    r.pose.y = 0.1;
  });
  add("good pose with a bad twist", "at most 1000 m/s", [](Req& r) {
    r.set_pose = true;
    r.pose.x = 0.2;
    r.pose.y = 0.15;
    r.set_twist = true;
    r.twist.linear.y = -1e20;
  });
  for (const auto& [bad, req] : cases) {
    const SetObstacleState r = n.call("set_obstacle_state", req);
    expectRefused(r.response.success, r.response.message, bad);
    expectAdvancing(n, bad.why);
  }
  // A refused request changed nothing: the box still rests on the bed.
  RigidBlockState box;
  ASSERT_TRUE(n.block("box", box));
  EXPECT_NEAR(box.pose.position.x, 0.1, 0.01);
  EXPECT_LT(box.pose.position.y, 0.08);
  for (const std::string& name : {std::string("nonexistent"), std::string(10 << 20, 'c')}) {
    RemoveObstacle rm;
    rm.request.name = name;
    rm = n.call("remove_obstacle", rm);
    expectRefused(rm.response.success, rm.response.message,
                  {"remove " + name.substr(0, 16), name.size() > 64 ? "at most 64" : "no block"});
    expectAdvancing(n, "remove " + name.substr(0, 16));
  }
}

TEST(Requests, BadStreamedCommandsAreIgnored) {
  Node& n = *g_node;
  expectAdvancing(n, "start");
  SpawnObstacle blade = test::square("blade", 0.2, 0.15, 0.01, SpawnObstacle::Request::KINEMATIC);
  ASSERT_TRUE(n.call("spawn_obstacle", blade).response.success);
  auto send = [&](const std::string& name, double vx, double w) {
    ObstacleCommand cmd;
    cmd.name = name;
    cmd.twist.linear.x = vx;
    cmd.twist.angular.z = w;
    n.cmd.publish(cmd);
  };
  const std::vector<std::pair<std::string, std::function<void()>>> cases{
      {"NaN twist", [&] { send("blade", kNan, 0); }},
      {"twist 1e15 m/s", [&] { send("blade", 1e15, 0); }},
      {"spin 1e30 rad/s", [&] { send("blade", 0, 1e30); }},
      {"static block", [&] { send("post", 0.1, 0); }},
      {"10 MB name", [&] { send(std::string(10 << 20, 'd'), 0.1, 0); }},
      {"no such block", [&] { send("nonexistent", 0.1, 0); }},
      {"5000 commands at once", [&] {
         for (int k = 0; k < 5000; ++k) send("blade", 1e15, 0);
       }}};
  for (const auto& [why, act] : cases) {
    act();
    expectAdvancing(n, why);
    RigidBlockState b;
    ASSERT_TRUE(n.block("blade", b));
    EXPECT_EQ(b.twist.linear.x, 0) << why << ": a bad command moved the blade";
    EXPECT_EQ(b.twist.angular.z, 0) << why;
  }
}

TEST(Requests, StepAnswersAtOnceAndPauseCancelsIt) {
  Node& n = *g_node;
  expectAdvancing(n, "start");
  auto step = [&](uint32_t steps) {
    StepSimulation s;
    s.request.steps = steps;
    return n.call("step", s);
  };
  StepSimulation r = step(5);
  expectRefused(r.response.success, r.response.message, {"step while running", "while paused"});
  r = step(0);
  expectRefused(r.response.success, r.response.message, {"zero steps", "1 to 1000000"});
  ASSERT_TRUE(n.trigger("pause"));
  ros::WallDuration(0.3).sleep();
  const SimStats paused = n.stats.get();
  const auto t0 = std::chrono::steady_clock::now();
  r = step(1000000);
  const double answer_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_TRUE(r.response.success) << r.response.message;
  EXPECT_LT(answer_s, 1.0) << "~step 1000000 must answer at once";
  EXPECT_EQ(r.response.step, paused.step);
  // While it steps, services answer and the count moves.
  ASSERT_TRUE(waitFor([&] { return n.stats.get().step > paused.step + 50; }, 10));
  const auto t1 = std::chrono::steady_clock::now();
  ListObstacles list = n.call("list_obstacles", ListObstacles());
  EXPECT_TRUE(list.response.success);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count(), 1.0);
  r = step(10);
  expectRefused(r.response.success, r.response.message, {"step while stepping", "~pause cancels"});
  // ~pause cancels the rest.
  std_srvs::Trigger pause = n.call("pause", std_srvs::Trigger());
  ASSERT_TRUE(pause.response.success);
  EXPECT_NE(pause.response.message.find("cancelled"), std::string::npos) << pause.response.message;
  ros::WallDuration(0.3).sleep();
  const uint64_t stopped = n.stats.get().step;
  ros::WallDuration(0.5).sleep();
  EXPECT_EQ(n.stats.get().step, stopped) << "still stepping after ~pause";
  EXPECT_LT(stopped, paused.step + 1000000);
  ASSERT_TRUE(n.trigger("resume"));
  expectAdvancing(n, "resume after a cancelled ~step");
}

TEST(Requests, PausedNodeKeepsClockAndStats) {
  Node& n = *g_node;
  expectAdvancing(n, "start");
  {
    // While running, /clock (sent by a thread of its own, ClockPublisher) has every message in
    // order: one at the first step at or after each millisecond (rates/clock 1000 Hz), so two
    // are less than a step (0.278 ms, node_bed.yaml's contact bound) off 1 ms apart; a lost
    // message makes a gap of about 2 ms, a reordered one a negative gap.
    std::mutex m;
    std::vector<double> times;
    ros::Subscriber sub = n.nh.subscribe<rosgraph_msgs::Clock>(
        "/clock", 10000, [&](const rosgraph_msgs::Clock::ConstPtr& c) {
          std::lock_guard<std::mutex> l(m);
          times.push_back(c->clock.toSec());
        });
    ASSERT_TRUE(waitFor(
        [&] {
          std::lock_guard<std::mutex> l(m);
          return times.size() >= 500;
        },
        10))
        << "/clock did not come at its rate";
    sub.shutdown();
    std::lock_guard<std::mutex> l(m);
    const double dt = n.stats.get().dt;
    ASSERT_LT(dt, 0.5e-3) << "the bound below needs steps shorter than half the clock's period";
    for (std::size_t k = 1; k < times.size(); ++k) {
      const double gap = times[k] - times[k - 1];
      ASSERT_GT(gap, 1e-3 - dt) << "message " << k << " at " << times[k];
      ASSERT_LT(gap, 1e-3 + dt) << "message " << k << " at " << times[k];
    }
  }
  ASSERT_TRUE(n.trigger("pause"));
  ros::WallDuration(1.0).sleep();
  // A late listener gets ~stats at once (latched) and /clock keeps coming at the paused time.
  test::Latest<SimStats> late(n.nh, test::kNs + "stats");
  test::Latest<rosgraph_msgs::Clock> clock(n.nh, "/clock");
  ASSERT_TRUE(waitFor([&] { return late.has() && clock.count() >= 2; }, 3))
      << "nothing on ~stats or /clock while paused";
  EXPECT_TRUE(late.get().paused);
  EXPECT_NEAR(clock.get().clock.toSec(), late.get().sim_time, 1e-9);
  // The real-time factor leaves the pause out: paced at 1, it reads about 1 right after resuming
  // (counting the 3 s pause, the first message would read a fraction of it).
  ros::WallDuration(2.0).sleep();
  ASSERT_TRUE(n.trigger("resume"));
  ros::WallDuration(0.5).sleep();
  const double rtf = n.stats.get().real_time_factor;
  EXPECT_GT(rtf, 0.8);
  EXPECT_LT(rtf, 1.2);
}

// Parameters the node must refuse before it simulates: it exits non-zero with the parameter's
// name, leaving no file behind.
TEST(Requests, BadParametersStopTheNodeBeforeItSimulates) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("mpm_sdem_bad_params_" + std::to_string(getpid()));
  fs::create_directories(dir / "a_directory.bag");
  const std::string scene = std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/node_bed.yaml";
  const std::string tool = std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/tool.urdf";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"_threads:=100000", "~threads"},
      {"_threads:=-1", "~threads"},
      {"_tf_prefix:='a b'", "~tf_prefix"},
      {"_fixed_frame:=../world", "~fixed_frame"},
      {"_record:=true _bag:=" + (dir / "a_directory.bag").string(), "is a directory"},
      {"_record:=true _bag:=" + (dir / "no_such_dir" / "x.bag").string(), "does not exist"},
      {"_record:=true _bag:=" + (dir / "x.txt").string(), "must end in .bag"},
      {"_video:=" + dir.string(), "is a directory"},
      {"_video:=" + (dir / "x.gif").string(), "must end in .avi, .mp4, .mkv"},
      {"_scene:=/dev/zero", "not a regular file"},
      {"_scene:=" + dir.string(), "not a regular file"},
      {"_cmd_vel_timeout:=-1", "~cmd_vel_timeout"},
      {"_terrain/resolution:=-0.01", "~terrain/resolution"},
      {"_terrain/resolution:=1e-9", "more than 100000 columns"},
      {"_follow_tf_delay:=0", "~follow_tf_delay"},
      {"_follow_tf_time_constant:=0.05", "is now ~follow_tf_delay"},
      {"_vtk/interval:=0", "~vtk/interval"},
      {"_bag_checkpoint_rate:=-1", "~bag_checkpoint_rate"},
      {"_resume:=" + (dir / "none.bag").string(), "~resume " + (dir / "none.bag").string()},
      {"_resume:=" + dir.string(), "holds no checkpoint"},
      {"_vtk/dir:=/dev/null", "~vtk/dir: '/dev/null' exists and is not a directory"},
      // A dictionary or a list cannot be given as _name:=value: set on the server first (as a
      // launch file's rosparam does), "follow_tf=" or "robot_links=" marking it here.
      {"follow_tf={nobody: target}", "no block named 'nobody'"},
      {"follow_tf={post: target}", "'post' must be kinematic"},
      {"follow_tf={box: /target}", "~follow_tf/box: frame"},
      // ~robot_links: a link the description lacks, one without collision geometry, a missing mesh
      // (its package found, the file not; its package not found),
      // no description, a bad rounding (before tf or a step).
      {"robot_links=[nolink] _robot_description_file:=" + tool,
       "link 'nolink' is not in the robot description"},
      {"robot_links=[bare] _robot_description_file:=" + tool,
       "link 'bare' has no collision geometry"},
      {"robot_links=[mesh] _robot_description_file:=" + tool,
       "link 'mesh': its collision (package://mpm_sdem/none.stl) mesh '"},
      {"robot_links=[elsewhere] _robot_description_file:=" + tool,
       "link 'elsewhere': its collision mesh 'package://no_such_package/m.stl' is in package "
       "'no_such_package', which is not on the ROS package path"},
      {"robot_links=[tool]", "there is no robot description"},
      {"robot_links=tool", "~robot_links must be a list of link names"},
      {"_robot_rounding:=0", "~robot_rounding"}};
  int k = 0;
  std::vector<Refusal> runs;
  for (const auto& [args, reason] : cases) {
    const fs::path log = dir / ("log" + std::to_string(k++));
    const std::string name = "bad" + std::to_string(k);
    // "key=VALUE _rest": VALUE set on the server (rosparam), _rest as arguments.
    const bool dict = args.rfind("follow_tf=", 0) == 0 || args.rfind("robot_links=", 0) == 0;
    const std::size_t eq = args.find('='), space = std::min(args.find(" _"), args.size());
    const std::string set = dict ? "rosparam set /" + name + "/" + args.substr(0, eq) + " '" +
                                       args.substr(eq + 1, space - eq - 1) + "' && "
                                 : "";
    const std::string rest = dict ? args.substr(space) : args;
    const std::string cmd = set + "timeout 30 " + MPM_SDEM_NODE + " __name:=" + name +
                            " _scene:=" + scene + " " + rest + " >" + log.string() + " 2>&1";
    runs.push_back({cmd, log.string(), args, reason});
  }
  expectAllExitNaming(runs);
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    EXPECT_TRUE(name.rfind("log", 0) == 0 || name == "a_directory.bag") << "left behind: " << name;
  }
  fs::remove_all(dir);
}

// The example controller (scripts/blade_force_controller.py, the users' template) refuses a
// parameter out of its range at its start, naming it, before it commands anything.
TEST(Requests, BadParametersStopTheExampleController) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("mpm_sdem_bad_controller_" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string script =
      std::string(MPM_SDEM_SOURCE_DIR) + "/scripts/blade_force_controller.py";
  const std::vector<std::pair<std::string, std::string>> cases{
      {"_force:=0", "~force = 0: must be a number in (0, 100000]"},
      {"_force:=-50", "~force = -50"},
      {"_speed:=-0.1", "~speed = -0.1: must be a number in [0, 10]"},
      {"_max_depth_rate:=0", "~max_depth_rate = 0"},
      {"_kp:=-0.001", "~kp = -0.001"},
      {"_ki:=2", "~ki = 2"},
      {"_filter:=0", "~filter = 0"},
      {"_rate:=0", "~rate = 0"},
      {"_rate:=5000", "~rate = 5000"},
      {"_kp:=fast", "~kp = 'fast'"},
      {"_filter:=.nan", "~filter = nan"}};
  int k = 0;
  std::vector<Refusal> runs;
  for (const auto& [args, reason] : cases) {
    const fs::path log = dir / ("log" + std::to_string(k++));
    const std::string cmd = "timeout 30 /usr/bin/python3 " + script + " __name:=badc" +
                            std::to_string(k) + " " + args + " >" + log.string() + " 2>&1";
    runs.push_back({cmd, log.string(), args, reason});
  }
  expectAllExitNaming(runs);
  fs::remove_all(dir);
}

// ~reset does not start a new bag unless ~record_after_reset: one recording per run.
TEST(Requests, ResetsKeepOneRecording) {
  namespace fs = std::filesystem;
  Node& n = *g_node;
  std::string bag;
  ASSERT_TRUE(ros::param::get(test::kNs + "bag", bag));
  expectAdvancing(n, "start");
  ASSERT_TRUE(fs::exists(bag + ".active"));
  for (int k = 0; k < 5; ++k) {
    std_srvs::Trigger reset = n.call("reset", std_srvs::Trigger());
    ASSERT_TRUE(reset.response.success) << reset.response.message;
    if (k == 0) {
      EXPECT_NE(reset.response.message.find("recording of the run before it is closed"),
                std::string::npos)
          << reset.response.message;
    }
    expectAdvancing(n, "reset " + std::to_string(k));
  }
  EXPECT_TRUE(fs::exists(bag)) << "the first run's bag was not closed";
  int files = 0;
  for (const auto& e : fs::directory_iterator(fs::path(bag).parent_path()))
    files += e.path().filename().string().rfind(fs::path(bag).stem().string(), 0) == 0;
  EXPECT_EQ(files, 1) << "resets opened new recordings";
  fs::remove(bag);
}

// The FEM bodies' outputs (fem_outputs.test, on test/data/valid_fem.yaml: one barrier clamped at
// its foot): ~fem_nodes carries every node with its displacement, velocity, stress and body, the
// clamped ones not displaced; ~fem_mesh three points per triangle; both keep coming.
TEST(Requests, FemBodiesArePublished) {
  Node& n = *g_node;
  test::Latest<sensor_msgs::PointCloud2> nodes(n.nh, test::kNs + "fem_nodes");
  test::Latest<visualization_msgs::Marker> mesh(n.nh, test::kNs + "fem_mesh");
  ASSERT_TRUE(waitFor([&] { return nodes.count() >= 2 && mesh.count() >= 2; }, 30))
      << "no ~fem_nodes or ~fem_mesh";
  const sensor_msgs::PointCloud2 c = nodes.get();
  std::vector<std::string> fields;
  for (const auto& f : c.fields) fields.push_back(f.name);
  EXPECT_EQ(fields,
            (std::vector<std::string>{"x", "y", "z", "ux", "uy", "vx", "vy", "von_mises", "body"}));
  ASSERT_GT(c.width, 10u);
  int clamped = 0;
  sensor_msgs::PointCloud2ConstIterator<float> x(c, "x"), u(c, "ux"), s(c, "von_mises");
  for (; x != x.end(); ++x, ++u, ++s) {
    EXPECT_TRUE(std::isfinite(u[0]) && std::isfinite(u[1]) && std::isfinite(*s));
    EXPECT_GE(*s, 0.f);
    if (x[1] < 1e-4f) {  // the foot, clamped
      ++clamped;
      EXPECT_EQ(u[0], 0.f);
      EXPECT_EQ(u[1], 0.f);
    }
  }
  EXPECT_GE(clamped, 2);
  const visualization_msgs::Marker m = mesh.get();
  EXPECT_EQ(m.type, visualization_msgs::Marker::TRIANGLE_LIST);
  EXPECT_EQ(m.points.size() % 3, 0u);
  EXPECT_GT(m.points.size(), c.width);  // more triangle corners than nodes
  EXPECT_EQ(m.colors.size(), m.points.size());
  EXPECT_EQ(c.header.frame_id, "world");
}

int main(int argc, char** argv) {
  return test::runNodeTests(argc, argv, "test_node_requests", g_node);
}
