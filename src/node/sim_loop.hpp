// The simulation loop of the node: runs queued commands, steps the world, paces it to the wall
// clock if asked, publishes, records. Everything touching the world happens on this thread.
#pragma once

#include <ros/ros.h>

#include <chrono>
#include <csignal>
#include <memory>
#include <string>

#include "commands.hpp"
#include "mpm_sdem/core/real_time_meter.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/thread_tuner.hpp"
#include "mpm_sdem/render/render.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"
#include "node_params.hpp"
#include "obstacle_drivers.hpp"
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

 private:
  // One step and its outputs; false when the state became non-finite or the step collapsed
  // (the loop then pauses).
  bool advance();
  void fail(const std::string& what, Real dt);
  // A sound state with a block outside the domain: paused, saying what to do.
  void pauseOutside(const std::string& what);
  conversions::StatsInput status() const;
  void publishWhilePaused();
  void openRecordings();
  void closeRecordings();
  // ~resume: the checkpoint into the world; throws std::runtime_error saying why it cannot.
  void resumeFromCheckpoint();
  // The world's commands to the bag (its first recording, or after a reset).
  void logCommands();
  // A frame of the ParaView series; a frame that cannot be written ends the series, not the run.
  void writeVtk();
  void restartPacing();
  void pace();
  void logProgress(bool force);

  NodeParams params_;
  Scene scene_;
  std::string scene_text_;
  std::unique_ptr<World> world_;
  std::string resumed_bag_;  // the bag the run resumed from, continued by the first recording
  CommandQueue commands_;
  ObstacleDrivers drivers_;
  Publishers publishers_;
  std::unique_ptr<BagRecorder> bag_;
  std::unique_ptr<render::VideoRecorder> video_;
  std::unique_ptr<VtkSeries> vtk_;
  SampleClock vtk_clock_;
  TimeStepChoice dt_;
  std::unique_ptr<Stepper> stepper_;  // of world_: made again with it on a reset
  bool paused_ = false;
  bool end_reached_ = false;
  bool unstable_ = false;
  bool shutdown_ = false;
  bool recording_ = true;  // false after a reset unless record_after_reset
  int resets_ = 0;
  long pending_steps_ = 0, asked_steps_ = 0;  // of a ~step request
  std::string last_request_;                  // "" since the start or the last reset
  using Clock = std::chrono::steady_clock;
  Clock::time_point pace_wall_, last_log_, last_idle_;
  Real pace_sim_ = 0;
  RealTimeMeter real_time_;
  std::unique_ptr<ThreadTuner> tuner_;  // with threads: 0
};

}  // namespace mpm_sdem::node
