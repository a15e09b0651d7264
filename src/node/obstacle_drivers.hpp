// What moves obstacles between steps besides one-off requests (the loop calls beforeStep before
// every step):
// - loads held for a while (~apply_obstacle_wrench, gazebo's apply_body_wrench);
// - velocity commands on ~obstacles/<name>/cmd_vel, in the block's own axes like a robot base's,
//   that lapse to zero after ~cmd_vel_timeout of simulation time without a new one
//   (diff_drive_controller's rule);
// - kinematic blocks that follow a tf frame (~follow_tf: a robot's blade link): each step ends
//   with the block where its frame was ~follow_tf_delay before (tf's interpolation between its
//   samples), so it moves as the frame did, whenever the samples came, and never past it; its
//   fastest point no faster than ~follow_tf_max_speed (a frame that jumps is closed on at that
//   speed, with a warning naming it).
// And the domain's walls: every kinematic block, however it is driven, stops at them (its
// velocity towards a wall is cut, with a warning); a dynamic block that leaves the domain
// pauses the loop (SimLoop::advance).
// Blocks are held by id, so a removed block's drivers lapse with it.
#pragma once

#include <geometry_msgs/TransformStamped.h>
#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "commands.hpp"
#include "mpm_sdem/core/world.hpp"
#include "node_params.hpp"

namespace mpm_sdem::node {

class ObstacleDrivers {
 public:
  ObstacleDrivers(ros::NodeHandle& pnh, CommandQueue& queue, const NodeParams& params);

  // At start: throws std::runtime_error when a ~follow_tf block is missing from the scene or
  // not kinematic.
  void checkFollowers(const World& world) const;
  // Loop thread, whenever blocks come and go or the world is rebuilt (fresh: after a reset,
  // when ids from the old world mean nothing). Subscribes cmd_vel for each kinematic block; a
  // follower whose block is gone (removed by a request) stops following until one of its name
  // and kind is there again.
  void sync(const World& world, bool fresh = false);
  // Loop thread, before a step of h (s): adds the held loads, lapses old commands, steers the
  // followers, stops kinematic blocks at the domain's walls.
  void beforeStep(World& world, Real h);

  // Loop thread, from requests. A load's force (N/m) acts at point (block frame, m), in the
  // block's axes when in_block_frame, else the fixed frame's; torque in N m/m; for duration s
  // of simulation time (< 0: until cleared). Refused when the loads on the block would exceed
  // heldLoadsProblem's bounds (rigid/block_checks.hpp).
  Reply addLoad(World& world, const std::string& name, const Vec2& force, const Vec2& point,
                bool in_block_frame, Real torque, Real duration);
  Reply clearLoads(const World& world, const std::string& name);  // "" clears all

  // Loop thread: block `name` follows tf frame `frame` from now on (a robot's link,
  // robot_links.hpp), as a ~follow_tf entry does; sync() finds its block. `section`: the frame's
  // pose in ~fixed_frame when the block's outline was cut from it (a robot link's section by
  // the plane): a warning names the block when the frame leaves that pose's plane motions (tilts
  // out of the plane or moves along its normal), which the outline does not follow.
  void follow(const std::string& name, const std::string& frame,
              const Eigen::Isometry3d* section = nullptr);

  // The tf buffer (also for ~get_obstacle_state's reference frames).
  const tf2_ros::Buffer& tf() const { return tf_; }

 private:
  struct Load {
    BlockId id;
    Vec2 force, point;
    bool in_block_frame;
    Real torque, until;  // until: s of simulation time, infinite for "until cleared"
    Real acceleration;   // of the block's fastest point (loadAcceleration), m/s^2
  };
  struct Command {
    BlockId id;
    std::string name;
    ros::Subscriber sub;
    Real last = 0;  // simulation time of the last command
    bool moving = false;
  };
  struct Follower {
    std::string name, frame;
    BlockId id;
    Real reach = 0;  // m, of its block's outline from its frame origin (blockReach)
    // The frame's latest sample, for the warnings and when tf cannot interpolate.
    bool sampled = false;
    ros::Time stamp;
    Vec2 position = Vec2(0, 0);
    Real angle = 0;
    bool has_section = false;  // follow()'s section: its rotation and height
    Eigen::Quaterniond section_rotation = Eigen::Quaterniond::Identity();
    Real section_height = 0;
  };
  void onCmdVel(const std::string& name, const geometry_msgs::Twist& twist);
  // Sets the follower's twist for the step of h (s) that comes next.
  void steer(World& world, Follower& f, Real h);
  void warnIfOutOfPlane(const Follower& f, const geometry_msgs::TransformStamped& ts) const;
  // Cuts a kinematic block's velocity towards a wall it would cross in h (keepInsideDomain).
  void keepInside(World& world, int i, Real h);

  ros::NodeHandle pnh_;
  CommandQueue& queue_;
  const NodeParams& params_;
  std::vector<Load> loads_;
  std::vector<Command> commands_;
  std::vector<Follower> followers_;
  tf2_ros::Buffer tf_;
  tf2_ros::TransformListener listener_;
};

}  // namespace mpm_sdem::node
