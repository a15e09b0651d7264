// A robot's links as obstacles (like gazebo_ros's spawn_model -urdf): each link in ~robot_links
// becomes the kinematic blocks of its collision solids cut by the simulation plane (the x-y
// plane of ~fixed_frame; robot/robot_obstacles.hpp), spawned where tf has the link when its
// transform first arrives (with /use_sim_time, robot_state_publisher's transforms come only once
// this node's clock runs), following the link's frame (~follow_tf's rule) with their wrench on
// ~obstacles/<block>/wrench like any obstacle's; spawned again after a reset.
#pragma once

#include <ros/node_handle.h>
#include <tf2_ros/buffer.h>

#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/robot/robot_obstacles.hpp"
#include "node_params.hpp"
#include "obstacle_drivers.hpp"

namespace mpm_sdem::node {

class RobotLinks {
 public:
  // Reads the description (~robot_description_file, or the parameter
  // ~robot_description_param looked up as robot_state_publisher does) and checks the links
  // (in it, with box, cylinder or sphere collisions); throws std::runtime_error naming the link
  // or the parameter. Nothing to do without ~robot_links.
  RobotLinks(const ros::NodeHandle& nh, const NodeParams& params);

  // Loop thread, between steps and while paused: spawns the links whose blocks are not in the
  // world and whose transforms have arrived; true when it added blocks (the caller's
  // blocksChanged then). A link whose solids miss the plane, whose blocks the world refuses or
  // with which the step would fall below limits::kMinTimeStep is named in an error and left out;
  // one whose transform is late is named in a warning after ~robot_tf_timeout s.
  bool spawnArrived(World& world, ObstacleDrivers& drivers);

  // The link whose block `block` is ("" when it is no link's): such a block follows the robot
  // and is spawned again while its link is in ~robot_links, so ~remove_obstacle refuses it.
  std::string linkOf(const std::string& block) const;

 private:
  struct Link {
    std::string name;
    bool failed = false;
    std::vector<std::string> blocks;  // the names of its blocks, once spawned
  };
  const NodeParams& params_;
  std::unique_ptr<robot::RobotDescription> robot_;
  std::vector<Link> links_;
};

}  // namespace mpm_sdem::node
