// dynamic_reconfigure for what a user changes while the node runs (cfg/Node.cfg): the real-time
// factor, the publishing rates, the obstacle drivers' settings and gravity. The callback (on
// ROS's thread) checks a change as a request is checked (runtimeProblem, World::gravityProblem):
// a refused change is logged with the reason and the values asked for, and the values in effect
// go back to the client with that message in `refused`; an accepted one is queued, and the loop
// applies it between two steps (SimLoop::applySettings). The callback never waits for the loop, so
// the loop may send new values at any time (~reset brings back the scene's gravity).
#pragma once

#include <dynamic_reconfigure/server.h>
#include <mpm_sdem/NodeConfig.h>
#include <ros/node_handle.h>

#include <boost/thread/recursive_mutex.hpp>
#include <string>

#include "commands.hpp"
#include "mpm_sdem/core/types.hpp"
#include "node_params.hpp"

namespace mpm_sdem::node {

// The settings dynamic_reconfigure changes.
struct RuntimeSettings {
  NodeParams params;   // of which only runtimeProblem's fields change
  Vec2 gravity{0, 0};  // m/s^2
};

class Reconfigure {
 public:
  // Serves settings, the values the node runs with, on ~set_parameters; accepted changes go to
  // queue.
  Reconfigure(const ros::NodeHandle& pnh, CommandQueue& queue, const RuntimeSettings& settings);
  // Loop thread: the values in effect changed otherwise (a reset); clients are told.
  void publish(const RuntimeSettings& settings);

 private:
  void onChange(mpm_sdem::NodeConfig& config, std::uint32_t level);

  CommandQueue& queue_;
  // The server's own lock: it holds it while it calls onChange, and publish takes it too.
  boost::recursive_mutex mutex_;
  RuntimeSettings current_;  // the values accepted last (under mutex_)
  std::string refused_;      // why the last change was refused; "" once one is accepted
  dynamic_reconfigure::Server<mpm_sdem::NodeConfig> server_;
};

}  // namespace mpm_sdem::node
