#include "robot_links.hpp"

#include <netdb.h>
#include <poll.h>
#include <ros/network.h>
#include <ros/package.h>
#include <ros/ros.h>
#include <sys/socket.h>
#include <tf2_eigen/tf2_eigen.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "mpm_sdem/core/limits.hpp"
#include "throttle.hpp"

namespace mpm_sdem::node {

namespace {

// Whether something accepts a connection at the XML-RPC uri within half a second.
bool answers(const std::string& uri) {
  std::string host;
  std::uint32_t port = 0;
  if (!ros::network::splitURI(uri, host, port)) return false;
  addrinfo hints{}, *found = nullptr;
  hints.ai_socktype = SOCK_STREAM;
  if (getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0) return false;
  bool up = false;
  for (addrinfo* a = found; a && !up; a = a->ai_next) {
    const int fd = socket(a->ai_family, a->ai_socktype | SOCK_NONBLOCK, a->ai_protocol);
    if (fd < 0) continue;
    if (connect(fd, a->ai_addr, a->ai_addrlen) == 0) {
      up = true;
    } else if (errno == EINPROGRESS) {
      pollfd p{fd, POLLOUT, 0};
      int error = 0;
      socklen_t size = sizeof error;
      up = poll(&p, 1, 500) == 1 && getsockopt(fd, SOL_SOCKET, SO_ERROR, &error, &size) == 0 &&
           error == 0;
    }
    close(fd);
  }
  freeaddrinfo(found);
  return up;
}

// The launches on this master that have ended: roslaunch (roscore too) registers each under
// /roslaunch/uris and never removes it, and an ended one no longer answers there.
std::vector<std::string> endedLaunches() {
  XmlRpc::XmlRpcValue uris;
  std::vector<std::string> ended;
  if (!ros::param::get("/roslaunch/uris", uris) ||
      uris.getType() != XmlRpc::XmlRpcValue::TypeStruct)
    return ended;
  for (auto& [key, uri] : uris)
    if (uri.getType() == XmlRpc::XmlRpcValue::TypeString && !answers(std::string(uri)))
      ended.push_back(key);
  return ended;
}

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
  // The master keeps parameters across launches, and no record of who set one or when. The rule:
  // a description is current while every launch on this master still runs (this one, roscore,
  // another that brought up the robot); once one has ended, it may be that launch's robot, left
  // behind, and the node warns, saying how to clear it. A launch run twice on one master gets the
  // warning the second time even when it set the description again: a stale robot is never
  // read without a word.
  const std::vector<std::string> ended = endedLaunches();
  if (ended.empty()) {
    ROS_INFO(
        "~robot_links: the robot description is parameter '%s' (%zu bytes), set by a launch "
        "that still runs (no launch on this master has ended)",
        key.c_str(), text.size());
  } else {
    ROS_WARN(
        "~robot_links: the robot description parameter '%s' (%zu bytes) may be left from before: "
        "%zu launch(es) on this master have ended (/roslaunch/uris/%s%s), and the master keeps "
        "no record of which one set it. If this launch did not set it, it is an earlier robot: "
        "`rosparam delete %s` and launch again, or set ~robot_description_file",
        key.c_str(), text.size(), ended.size(), ended.front().c_str(),
        ended.size() > 1 ? ", ..." : "", key.c_str());
  }
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
