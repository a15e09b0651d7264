// The simulation loop of the node: runs queued commands, steps the world, paces it to the wall
// clock if asked, publishes, records. Everything touching the world happens on this thread.
#pragma once

#include <ros/ros.h>

#include <chrono>
#include <csignal>
#include <memory>
#include <string>

#include "commands.hpp"
#include "mpm_sdem/render/render.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "node_params.hpp"
#include "publishers.hpp"

namespace mpm_sdem::node {

class Simulation {
 public:
  // Throws std::runtime_error when the bag or the video cannot be opened.
  Simulation(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params, Scene scene,
             std::string scene_text);
  ~Simulation();

  // Runs until ROS shuts down, stop becomes non-zero or the scene ends with end_action
  // shutdown; closes the recordings. Returns the process exit status.
  int run(const volatile std::sig_atomic_t& stop);
  CommandQueue& commands() { return commands_; }

  // For commands, on the loop thread.
  World& world() { return *world_; }
  const NodeParams& params() const { return params_; }
  Reply pause();
  Reply resume();
  Reply reset();
  // Takes n steps now (the simulation must be paused); false when the state became unstable.
  Reply step(long n);
  // After a spawn or remove: markers and the time step change.
  void blocksChanged();

 private:
  // One step and its outputs; false when the state became non-finite (the loop then pauses).
  bool advance();
  void openRecordings();
  void closeRecordings();
  void restartPacing();
  void pace();
  void logProgress(bool force);

  NodeParams params_;
  Scene scene_;
  std::string scene_text_;
  std::unique_ptr<World> world_;
  CommandQueue commands_;
  Publishers publishers_;
  std::unique_ptr<BagRecorder> bag_;
  std::unique_ptr<render::VideoRecorder> video_;
  TimeStepChoice dt_;
  bool paused_ = false;
  bool end_reached_ = false;
  bool unstable_ = false;
  bool shutdown_ = false;
  int resets_ = 0;
  using Clock = std::chrono::steady_clock;
  Clock::time_point pace_wall_, start_wall_, last_log_;
  Real pace_sim_ = 0;
};

}  // namespace mpm_sdem::node
