// The node's services and command topic (the per-obstacle cmd_vel topics: obstacle_drivers.hpp).
// Each callback checks the request on its own (numbers
// finite, shape acceptable, names given), refuses a bad one with success=false and a message,
// and queues a good one for the loop, which checks it against the world (name clash, unknown
// name, domain, overlap) before applying it between steps.
#pragma once

#include <mpm_sdem/ApplyObstacleWrench.h>
#include <mpm_sdem/ClearObstacleWrenches.h>
#include <mpm_sdem/GetObstacleState.h>
#include <mpm_sdem/ListObstacles.h>
#include <mpm_sdem/ObstacleCommand.h>
#include <mpm_sdem/RemoveObstacle.h>
#include <mpm_sdem/SetObstacleState.h>
#include <mpm_sdem/SpawnObstacle.h>
#include <mpm_sdem/StepSimulation.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>
#include <std_srvs/Trigger.h>

#include <vector>

#include "commands.hpp"

namespace mpm_sdem::node {

class Services {
 public:
  Services(ros::NodeHandle& pnh, CommandQueue& queue);

 private:
  bool spawn(mpm_sdem::SpawnObstacle::Request& req, mpm_sdem::SpawnObstacle::Response& res);
  bool remove(mpm_sdem::RemoveObstacle::Request& req, mpm_sdem::RemoveObstacle::Response& res);
  bool setState(mpm_sdem::SetObstacleState::Request& req,
                mpm_sdem::SetObstacleState::Response& res);
  bool list(mpm_sdem::ListObstacles::Request& req, mpm_sdem::ListObstacles::Response& res);
  bool step(mpm_sdem::StepSimulation::Request& req, mpm_sdem::StepSimulation::Response& res);
  bool getState(mpm_sdem::GetObstacleState::Request& req,
                mpm_sdem::GetObstacleState::Response& res);
  bool applyWrench(mpm_sdem::ApplyObstacleWrench::Request& req,
                   mpm_sdem::ApplyObstacleWrench::Response& res);
  bool clearWrenches(mpm_sdem::ClearObstacleWrenches::Request& req,
                     mpm_sdem::ClearObstacleWrenches::Response& res);
  void obstacleCommand(const mpm_sdem::ObstacleCommand::ConstPtr& msg);

  CommandQueue& queue_;
  std::vector<ros::ServiceServer> servers_;
  ros::Subscriber command_sub_;
};

}  // namespace mpm_sdem::node
