#include "robot_links.hpp"

#include <ros/package.h>
#include <ros/ros.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mpm_sdem/core/limits.hpp"
#include "throttle.hpp"

namespace mpm_sdem::node {

namespace {

// The URDF text, from the file or the parameter.
std::string description(const ros::NodeHandle& nh, const NodeParams& p) {
  if (!p.robot_description_file.empty()) {
    std::ifstream in(p.robot_description_file);
    std::ostringstream text;
    text << in.rdbuf();
    if (!in || text.str().empty())
      throw std::runtime_error("parameter ~robot_description_file: cannot read '" +
                               p.robot_description_file + "'");
    return text.str();
  }
  std::string key, text;
  if (!nh.searchParam(p.robot_description_param, key) || !nh.getParam(key, text) || text.empty())
    throw std::runtime_error(
        "~robot_links is set but there is no robot description: set the parameter '" +
        p.robot_description_param +
        "' (as robot_state_publisher reads it) or ~robot_description_file");
  // The master keeps parameters across launches, so this may be an earlier launch's robot: say
  // which one is read and how to clear it (the master gives no time a parameter was set).
  ROS_INFO(
      "~robot_links: the robot description is parameter '%s' (%zu bytes); one left on this "
      "master by an earlier launch is read too: `rosparam delete %s` clears it, or set "
      "~robot_description_file",
      key.c_str(), text.size(), key.c_str());
  return text;
}

// A mesh's URI as rviz and gazebo read it: package://<package>/<file> under the package's
// directory on the ROS package path, anything else as robot::meshFilePath takes it.
std::string meshPath(const std::string& uri) {
  const std::string scheme = "package://";
  if (uri.compare(0, scheme.size(), scheme) != 0) return robot::meshFilePath(uri);
  const std::string rest = uri.substr(scheme.size());
  const std::size_t slash = rest.find('/');
  const std::string package = rest.substr(0, slash);
  const std::string directory = ros::package::getPath(package);
  if (directory.empty())
    throw robot::RobotError("mesh '" + uri + "' is in package '" + package +
                            "', which is not on the ROS package path");
  return directory + (slash == std::string::npos ? "" : rest.substr(slash));
}

robot::RobotObstaclesDef definition(const NodeParams& p, const std::string& link) {
  robot::RobotObstaclesDef def;
  def.links = {link};
  def.rounding = p.robot_rounding;
  def.friction = p.robot_friction;
  return def;
}

}  // namespace

RobotLinks::RobotLinks(const ros::NodeHandle& nh, const NodeParams& params) : params_(params) {
  if (params.robot_links.empty()) return;
  try {
    robot_ = std::make_unique<robot::RobotDescription>(description(nh, params), meshPath);
    for (const std::string& link : params.robot_links) {
      robot_->check(definition(params, link));
      links_.push_back({link, false, {}});
    }
  } catch (const robot::RobotError& e) {
    throw std::runtime_error(std::string("~robot_links: ") + e.what());
  }
}

bool RobotLinks::spawnArrived(World& world, ObstacleDrivers& drivers) {
  bool added = false;
  for (Link& link : links_) {
    if (link.failed) continue;
    // Its first block is named after it (robot_obstacles.hpp): there means spawned.
    if (world.blocks() && !world.blocks()->find(link.name).isNull()) continue;
    const tf2_ros::Buffer& tf = drivers.tf();
    if (!tf.canTransform(params_.fixed_frame, link.name, ros::Time(0))) {
      if (world.time() > params_.robot_tf_timeout)
        MPM_SDEM_WARN_THROTTLE(5,
                               "~robot_links: link '%s' is not in the simulation yet: no transform "
                               "%s -> %s (is robot_state_publisher running, the robot joined to "
                               "%s?)",
                               link.name.c_str(), params_.fixed_frame.c_str(), link.name.c_str(),
                               params_.fixed_frame.c_str());
      continue;
    }
    std::vector<robot::LinkBlock> blocks;
    Eigen::Isometry3d section = Eigen::Isometry3d::Identity();  // the link's pose, cut here
    try {
      blocks = robot_->obstacles(definition(params_, link.name), [&](const std::string& l) {
        const Eigen::Isometry3d pose =
            tf2::transformToEigen(tf.lookupTransform(params_.fixed_frame, l, ros::Time(0)));
        if (l == link.name) section = pose;
        return pose;
      });
    } catch (const std::exception& e) {  // RobotError, tf2's
      ROS_ERROR("~robot_links: %s; it is left out", e.what());
      link.failed = true;
      continue;
    }
    std::vector<BlockId> ids;
    for (const robot::LinkBlock& b : blocks) {
      // Where the robot is, overlapping the material or not (it is not asked, it is there);
      // its values, its name, the domain and the other blocks as for any obstacle.
      if (const Problem p = world.placementProblem(b.block, true); !p.empty()) {
        ROS_ERROR("~robot_links: link '%s' makes no block: %s; it is left out", link.name.c_str(),
                  p.text().c_str());
        link.failed = true;
        break;
      }
      ids.push_back(world.addBlock(b.block));
      drivers.follow(b.block.name, link.name, &section);
      ROS_INFO(
          "~robot_links: link '%s' is block '%s' (%zu core vertices, rounding %.4g m) from "
          "t = %.4f s",
          link.name.c_str(), b.block.name.c_str(), b.block.core.size(), b.block.rounding,
          world.time());
    }
    // A section so small that its springs' stable step would stop the clock (spawn_obstacle's
    // check).
    if (const TimeStepChoice dt = world.chooseTimeStep();
        !link.failed && !ids.empty() && !(dt.dt >= limits::kMinTimeStep)) {
      ROS_ERROR(
          "~robot_links: link '%s' is left out: with it the time step would fall to %g s "
          "(%s term); give it a larger collision solid",
          link.name.c_str(), dt.dt, stepLimitName(dt.limit));
      link.failed = true;
    }
    if (link.failed) {
      for (const BlockId& id : ids) world.removeBlock(id);
    } else {
      added = added || !ids.empty();
      link.blocks.clear();
      for (const robot::LinkBlock& b : blocks) link.blocks.push_back(b.block.name);
    }
  }
  return added;
}

std::string RobotLinks::linkOf(const std::string& block) const {
  for (const Link& link : links_)
    if (std::find(link.blocks.begin(), link.blocks.end(), block) != link.blocks.end())
      return link.name;
  return "";
}

}  // namespace mpm_sdem::node
