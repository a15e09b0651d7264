// Everything the node publishes, each at its own rate in simulation time and only when someone
// listens (tf always): ~particles, ~blocks, ~block_poses, tf, ~markers, ~force_arrows,
// ~terrain, ~obstacles/<name>/wrench, ~stats, ~image, /clock. Static blocks and the domain's
// frame go on /tf_static whenever the blocks change. The latched topics (particles, markers,
// arrows, terrain, stats, FEM) are also sent on every forced publication (start, pause,
// commands), listened to or not, so that a viewer that connects while the node is paused
// (rviz after a start_paused launch) gets the current state at once.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <vector>

#include "clock_publisher.hpp"
#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/ros/conversions.hpp"
#include "node_params.hpp"

namespace mpm_sdem::node {

class Publishers {
 public:
  // Topics only for what the world has: ~fem_mesh and ~fem_nodes with FEM bodies (none can be
  // added while running).
  Publishers(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params,
             const std::string& scene_text, const World& world);

  // After a step: publishes what is due at the world's time. force: everything now (after a
  // command while paused, so that listeners see its effect). status: the step, pause and
  // real-time factor for ~stats (its profile is taken here, per message).
  void publish(const World& world, const conversions::StatsInput& status, bool force = false);
  // While paused, every half second: /clock at the world's time and ~stats.
  void publishIdle(const World& world, const conversions::StatsInput& status);
  // The set of blocks changed (spawn, remove, reset, a static block moved): the per-obstacle
  // topics follow, /tf_static is re-sent.
  void blocksChanged(const World& world);
  // "" or why ~terrain cannot be drawn for this world (too many columns).
  Problem terrainProblem(const World& world) const;
  // Restart the rate schedules at the world's time (after a reset).
  void restart(const World& world);
  // Each channel's schedule at the parameters' rates, due at once: at the start, and when
  // dynamic_reconfigure changed them.
  void setRates();

 private:
  struct Channel {
    ros::Publisher pub;
    SampleClock clock;
    bool latched = false;  // a forced publication goes out without listeners
    // Due at t (and advances the schedule); listeners required unless always.
    bool due(Real t, bool force, bool always = false);
  };
  struct Obstacle {
    std::string name;
    ros::Publisher wrench;  // ~obstacles/<name>/wrench
    // Its listeners, counted by roscpp's connect callbacks: asking roscpp looks the topic up
    // among all the node's topics by name, a thousand of them with a thousand obstacles.
    std::shared_ptr<std::atomic<int>> listeners;
  };

  const NodeParams& params_;
  ros::NodeHandle pnh_;
  Channel particles_, blocks_, poses_, stats_, image_, clock_, fem_, fem_nodes_, markers_, arrows_,
      terrain_;
  ros::Publisher scene_;
  std::vector<Obstacle> obstacles_;
  tf2_ros::TransformBroadcaster tf_;
  // The static frames sent: new ones are added to the latched message; when one goes or moves,
  // the broadcaster is replaced, so that its message holds only the blocks there are.
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> tf_static_;
  std::map<std::string, geometry_msgs::Transform> static_sent_;
  Real arrow_scale_ = 0;                          // m per N/m
  std::vector<Real> heights_;                     // ~terrain's columns, reused
  std::unique_ptr<ClockPublisher> clock_thread_;  // /clock's messages; null without /use_sim_time
  sensor_msgs::PointCloud2 cloud_, fem_cloud_, terrain_cloud_;
  cv::Mat frame_;
  void publishClock(const std_msgs::Header& header);
  void publishBlocks(const World& world, const std_msgs::Header& header, bool force);
  void publishTerrain(const World& world, const std_msgs::Header& header);
  Real terrainColumn(const World& world) const;  // m
  int terrainColumns(const World& world) const;
  void publishStats(const World& world, const conversions::StatsInput& status,
                    const std_msgs::Header& header);
  // For the per-stage times in ~stats: the profile at the last message.
  Profile stats_profile_;
};

}  // namespace mpm_sdem::node
