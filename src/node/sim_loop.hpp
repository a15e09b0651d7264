// The simulation loop of the node: runs queued commands, steps the world through its Simulation
// (sim/simulation.hpp: the guards and the recordings as outputs), paces it to the wall clock if
// asked, publishes. Everything touching the world happens on this thread.
#pragma once

#include <ros/ros.h>

#include <chrono>
#include <csignal>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "mpm_sdem/core/real_time_meter.hpp"
#include "mpm_sdem/render/render.hpp"
#include "mpm_sdem/ros/bag_output.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "mpm_sdem/sim/simulation.hpp"
#include "mpm_sdem/vtk/vtk_output.hpp"
#include "node_params.hpp"
#include "obstacle_drivers.hpp"
#include "publishers.hpp"
#include "reconfigure.hpp"
#include "robot_links.hpp"

namespace mpm_sdem::node {

class SimLoop {
 public:
  // Throws std::runtime_error when the bag or the video cannot be opened.
  SimLoop(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params, Scene scene,
          std::string scene_text);
  ~SimLoop();

  // Runs until ROS shuts down, stop becomes non-zero or the scene ends with end_action
  // shutdown; closes the recordings. Returns the process exit status.
  int run(const volatile std::sig_atomic_t& stop);
  CommandQueue& commands() { return commands_; }

  // For commands, on the loop thread.
  World& world() { return *world_; }
  const NodeParams& params() const { return params_; }
  const RobotLinks& robotLinks() const { return robot_links_; }
  ObstacleDrivers& drivers() { return drivers_; }
  Reply pause();  // also cancels the steps ~step asked for
  Reply resume();
  Reply reset();
  // Queues n steps, taken by the loop between commands while paused; answers at once.
  Reply step(long n);
  // After a spawn, a remove or a move: the time step, the per-obstacle topics and /tf_static
  // follow.
  void blocksChanged();
  // A request that changed the world (said in the error if the state then fails).
  void noteRequest(const std::string& what);
  // dynamic_reconfigure's settings (reconfigure.hpp), checked by its callback: applied now.
  Reply applySettings(const RuntimeSettings& settings);

 private:
  // One step and its outputs; false when the state became non-finite or the step collapsed
  // (the loop then pauses).
  bool advance();
  // A new world's step loop (at the start and on a reset), its recordings attached and started.
  void startRun();
  void fail(const std::string& what, Real dt);
  // A sound state with a block outside the domain: paused, saying what to do.
  void pauseOutside(const std::string& what);
  // With end_action shutdown, a pause for a problem (fail, pauseOutside) ends the run instead:
  // such a run is a script's, and no one will call ~resume (a headless run waited for ever).
  // Logs why and sets the exit status; false with any other end_action.
  bool endInsteadOfPausing(const std::string& why);
  conversions::StatsInput status() const;
  void publishWhilePaused();
  void openRecordings();
  void closeRecordings();
  // ~resume: the checkpoint into the world; throws std::runtime_error saying why it cannot.
  void resumeFromCheckpoint();
  void restartPacing();
  void pace();
  void logProgress(bool force);
  RuntimeSettings settings() const;

  NodeParams params_;
  Scene scene_;
  std::string scene_text_;
  std::unique_ptr<World> world_;
  std::unique_ptr<Simulation> sim_;  // of world_: made again with it on a reset
  std::string resumed_bag_;  // the bag the run resumed from, continued by the first recording
  CommandQueue commands_;
  ObstacleDrivers drivers_;
  RobotLinks robot_links_;  // a robot description's links, spawned as their tf arrives
  Publishers publishers_;
  std::unique_ptr<Reconfigure> reconfigure_;  // made last: its callback queues commands
  // The recordings and their outputs (a failed one is dropped by sim_, closed here).
  std::unique_ptr<BagRecorder> bag_;
  std::unique_ptr<render::VideoRecorder> video_;
  std::unique_ptr<VtkSeries> vtk_;
  std::vector<std::unique_ptr<RunOutput>> outputs_;
  bool paused_ = false;
  bool end_reached_ = false;
  bool unstable_ = false;
  bool shutdown_ = false;
  int exit_status_ = 0;    // of run(): non-zero when endInsteadOfPausing ended it
  bool recording_ = true;  // false after a reset unless record_after_reset
  int resets_ = 0;
  long pending_steps_ = 0, asked_steps_ = 0;  // of a ~step request
  std::string last_request_;                  // "" since the start or the last reset
  using Clock = std::chrono::steady_clock;
  Clock::time_point pace_wall_, last_log_, last_idle_;
  Real pace_sim_ = 0;
  RealTimeMeter real_time_;
};

}  // namespace mpm_sdem::node
