// Shared pieces of the node tests: waiting on a condition while callbacks run, latest messages.
#pragma once

#include <gtest/gtest.h>
#include <mpm_sdem/BlockStates.h>
#include <mpm_sdem/ObstacleCommand.h>
#include <mpm_sdem/SimStats.h>
#include <mpm_sdem/SpawnObstacle.h>
#include <ros/ros.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Log.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <algorithm>
#include <chrono>
#include <functional>
#include <map>
#include <mutex>
#include <thread>
#include <vector>

namespace mpm_sdem::test {

// Polls cond every 10 ms of wall time until it holds or timeout_s passes.
inline bool waitFor(const std::function<bool()>& cond, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (cond()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return cond();
}

// Publishes msg count times, period_s of wall time apart (a stream of commands).
template <class M>
void publishRepeatedly(const ros::Publisher& pub, const M& msg, int count, double period_s) {
  for (int k = 0; k < count; ++k) {
    pub.publish(msg);
    ros::WallDuration(period_s).sleep();
  }
}

// Keeps the last message of a topic (callbacks on an AsyncSpinner thread).
template <class M>
class Latest {
 public:
  Latest(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe(topic, 100, &Latest::onMessage, this)) {}
  bool has() const {
    std::lock_guard<std::mutex> l(m_);
    return count_ > 0;
  }
  M get() const {
    std::lock_guard<std::mutex> l(m_);
    return msg_;
  }
  long count() const {
    std::lock_guard<std::mutex> l(m_);
    return count_;
  }

 private:
  void onMessage(const typename M::ConstPtr& msg) {
    std::lock_guard<std::mutex> l(m_);
    msg_ = *msg;
    ++count_;
  }
  mutable std::mutex m_;
  M msg_;
  long count_ = 0;
  ros::Subscriber sub_;
};

// Every message logged to /rosout since construction (callbacks on an AsyncSpinner thread).
class RosoutLog {
 public:
  explicit RosoutLog(ros::NodeHandle& nh)
      : sub_(nh.subscribe("/rosout", 1000, &RosoutLog::add, this)) {}
  // How many messages of at least this level hold text.
  int count(const std::string& text, std::uint8_t level = rosgraph_msgs::Log::DEBUG) const {
    std::lock_guard<std::mutex> l(m_);
    int n = 0;
    for (const rosgraph_msgs::Log& m : logs_)
      n += m.level >= level && m.msg.find(text) != std::string::npos;
    return n;
  }
  // The first message holding text, or "".
  std::string find(const std::string& text) const {
    std::lock_guard<std::mutex> l(m_);
    for (const rosgraph_msgs::Log& m : logs_)
      if (m.msg.find(text) != std::string::npos) return m.msg;
    return "";
  }
  std::size_t longest() const {
    std::lock_guard<std::mutex> l(m_);
    std::size_t n = 0;
    for (const rosgraph_msgs::Log& m : logs_) n = std::max(n, m.msg.size());
    return n;
  }

 private:
  void add(const rosgraph_msgs::Log::ConstPtr& m) {
    std::lock_guard<std::mutex> l(m_);
    logs_.push_back(*m);
  }
  mutable std::mutex m_;
  std::vector<rosgraph_msgs::Log> logs_;
  ros::Subscriber sub_;
};

inline const mpm_sdem::RigidBlockState* findBlock(const mpm_sdem::BlockStates& s,
                                                  const std::string& name) {
  for (const auto& b : s.blocks)
    if (b.name == name) return &b;
  return nullptr;
}

inline const std::string kNs = "/mpm_sdem/";

// Every message of a bag as its serialized bytes, by topic, in order; but the stats, which carry
// wall-clock figures (real-time factor, stage times). Two runs that computed the same recorded
// the same bytes.
inline std::map<std::string, std::vector<std::vector<std::uint8_t>>> physicsMessages(
    const std::string& path) {
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  std::map<std::string, std::vector<std::vector<std::uint8_t>>> out;
  for (const rosbag::MessageInstance& m : rosbag::View(bag)) {
    if (m.getDataType() == "mpm_sdem/SimStats") continue;
    std::vector<std::uint8_t> bytes(m.size());
    ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
    m.write(stream);
    out[m.getTopic()].push_back(std::move(bytes));
  }
  return out;
}

// Topics whose messages differ between two bags' physicsMessages (empty: none).
inline std::vector<std::string> differingTopics(const std::string& a, const std::string& b) {
  const auto ma = physicsMessages(a), mb = physicsMessages(b);
  std::vector<std::string> out;
  for (const auto& [topic, messages] : ma)
    if (!mb.count(topic) || mb.at(topic) != messages) out.push_back(topic);
  for (const auto& [topic, messages] : mb)
    if (!ma.count(topic)) out.push_back(topic);
  return out;
}

// A client of the node under test: its topics, tf and services.
struct NodeClient {
  ros::NodeHandle nh;
  Latest<BlockStates> blocks{nh, kNs + "blocks"};
  Latest<SimStats> stats{nh, kNs + "stats"};
  Latest<sensor_msgs::PointCloud2> cloud{nh, kNs + "particles"};
  ros::Publisher cmd = nh.advertise<ObstacleCommand>(kNs + "obstacle_cmd", 10);
  tf2_ros::Buffer tf;
  tf2_ros::TransformListener listener{tf};

  template <class S>
  S call(const std::string& name, S srv) {
    EXPECT_TRUE(ros::service::waitForService(kNs + name, ros::Duration(10)));
    EXPECT_TRUE(ros::service::call(kNs + name, srv)) << name;
    return srv;
  }
  bool trigger(const std::string& name) {
    std_srvs::Trigger t;
    return call(name, t).response.success;
  }
  // The block's latest state; false when it is not there.
  bool block(const std::string& name, RigidBlockState& out) {
    const BlockStates s = blocks.get();
    const RigidBlockState* b = findBlock(s, name);
    if (b) out = *b;
    return b != nullptr;
  }
};

// A square block of half side half (m) at (x, y), rounding 2 mm, density 500 kg/m^3.
inline SpawnObstacle square(const std::string& name, double x, double y, double half,
                            uint8_t type) {
  SpawnObstacle s;
  s.request.name = name;
  for (auto [vx, vy] : {std::pair{-half, -half}, {half, -half}, {half, half}, {-half, half}}) {
    geometry_msgs::Point p;
    p.x = vx;
    p.y = vy;
    s.request.vertices.push_back(p);
  }
  s.request.rounding = 0.002;
  s.request.pose.x = x;
  s.request.pose.y = y;
  s.request.body_type = type;
  s.request.density = 500;
  s.request.friction = 0.5;
  s.request.restitution = 0.5;
  return s;
}

// The main of a node test: gtest, ROS on two spinner threads, and one client of the node under
// test (node) for the whole run.
inline int runNodeTests(int argc, char** argv, const char* name, NodeClient*& node) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, name);
  ros::AsyncSpinner spinner(2);
  spinner.start();
  NodeClient client;
  node = &client;
  const int status = RUN_ALL_TESTS();
  spinner.stop();
  return status;
}

}  // namespace mpm_sdem::test
