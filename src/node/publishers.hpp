// Everything the node publishes, each at its own rate in simulation time and only when someone
// listens (tf always): ~particles, ~blocks, ~block_poses, tf, ~markers, ~stats, ~image, /clock.
#pragma once

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>

#include <chrono>

#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/ros/conversions.hpp"
#include "node_params.hpp"

namespace mpm_sdem::node {

class Publishers {
 public:
  Publishers(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params,
             const std::string& scene_text);

  // After a step: publishes what is due at the world's time. force: everything now (after a
  // command while paused, so that listeners see its effect). status: the step, pause and
  // real-time factor for ~stats (its profile is taken here, per message).
  void publish(const World& world, const conversions::StatsInput& status, bool force = false);
  // While paused, every half second: /clock at the world's time and ~stats.
  void publishIdle(const World& world, const conversions::StatsInput& status);
  // The set of blocks changed (spawn, remove, reset): markers are re-sent.
  void blocksChanged(const World& world);
  // Restart the rate schedules at the world's time (after a reset).
  void restart(const World& world);

 private:
  struct Channel {
    ros::Publisher pub;
    SampleClock clock;
    // Due at t (and advances the schedule); listeners required unless always.
    bool due(Real t, bool force, bool always = false);
  };

  const NodeParams& params_;
  Channel particles_, blocks_, poses_, stats_, image_, clock_, fem_, fem_nodes_;
  ros::Publisher markers_, scene_;
  tf2_ros::TransformBroadcaster tf_;
  bool use_sim_time_ = false;
  sensor_msgs::PointCloud2 cloud_, fem_cloud_;
  cv::Mat frame_;
  void publishClock(const std_msgs::Header& header);
  void publishStats(const World& world, const conversions::StatsInput& status,
                    const std_msgs::Header& header);
  // For the per-stage times in ~stats: the profile at the last message.
  Profile stats_profile_;
};

}  // namespace mpm_sdem::node
