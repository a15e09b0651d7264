// Records a run into a rosbag with the rosbag C++ API, stamped with simulation time; needs no
// master, so the node and the headless runner write the same bags. Like `rosbag record`, the bag
// is written as <path>.active and renamed to <path> when closed: a file without the suffix is
// complete, and one left with it (a killed process) can be recovered with `rosbag reindex`.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "mpm_sdem/core/bounded_worker.hpp"
#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/ros/conversions.hpp"

namespace rosbag {
class Bag;
}

namespace mpm_sdem {

struct RecordDef {
  // Hz of simulation time: ~particles. 10, not the live topic's 30: clouds are most of a bag
  // (the excavator demo's 7,200 points at 30 Hz: 7.7 of its 16 MB per simulated second before
  // compression), and a replay or a comparison needs no more.
  double cloud_rate = 10;
  double state_rate = 100;  // Hz: ~blocks, ~block_poses, /tf, ~stats
  // Hz: ~checkpoint, the whole state (mpm_sdem/Checkpoint), to resume from; 0: only the one
  // written at the end (checkpoint()).
  double checkpoint_rate = 1;
  int cloud_decimation = 1;      // every n-th material point
  std::string ns = "/mpm_sdem";  // topic namespace (the node's name when the node records)
  std::string fixed_frame = "world";
  std::string tf_prefix = "mpm_sdem";  // block frames: <tf_prefix>/<name>, as the node's
};

// "" or why a bag cannot be written there (limits::outputFileProblem: a .bag file).
Problem bagPathProblem(const std::string& path);

// Messages are made on the caller's thread (they read the world) and written by a thread of the
// recorder's own, as `rosbag record` does: rosbag seeks and writes the file for every message,
// a system call each, which the simulation does not wait for. At most kQueued messages wait; a
// full queue makes the caller wait, so none is dropped. A write's error is thrown on the caller's
// thread at its next call.
class BagRecorder {
 public:
  // Throws std::runtime_error with the reason when the file cannot be opened. scene_text is the
  // scene file's text, written once on <ns>/scene (std_msgs/String, latched); state_text the
  // scene's Scene::state_text, which the checkpoints carry.
  BagRecorder(const std::string& path, const RecordDef& def, const std::string& scene_text,
              const std::string& state_text);
  ~BagRecorder();
  BagRecorder(const BagRecorder&) = delete;
  BagRecorder& operator=(const BagRecorder&) = delete;

  // Writes what is due at the world's current time: a cloud every 1/cloud_rate s (with the FEM
  // bodies' nodes, <ns>/fem_nodes, and triangles, <ns>/fem_mesh, when there are any) and the states
  // every 1/state_rate s of simulation time (both at the first call): <ns>/blocks,
  // <ns>/block_poses, the outlines for rviz (<ns>/markers), /tf of the moving blocks, each block's
  // <ns>/obstacles/<name>/wrench and <ns>/stats. stats supplies what the world does not know
  // (time step, real-time factor, stage times). And <ns>/checkpoint every 1/checkpoint_rate s
  // (saveCheckpoint, which may rebuild Box2D's bodies: hence the world is not const).
  void record(World& world, const conversions::StatsInput& stats);
  // A checkpoint now, whatever the schedule (the end of a run), unless one of this time is in.
  void checkpoint(World& world);
  // A command the world applied (World::setCommandLog), on <ns>/commands.
  void command(const WorldCommand& command);
  // A resumed run's bag: first every message of bag up to time t (the checkpoint the run
  // resumes from and what came before it; commands applied at t came after the checkpoint and
  // are left out), then this run's from after t, as if the run had never stopped.
  // Throws std::runtime_error when bag cannot be read.
  void continueFrom(const std::string& bag, Real t);
  // /tf_static (the domain's frame and the static blocks, latched on playback): written at the
  // first record() and again after blocks are added or removed.
  void blocksChanged(const World& world);
  // Closes the bag and renames it to its final name; idempotent.
  void close();

  const std::string& path() const { return path_; }
  long messageCount() const { return messages_; }

  static constexpr std::size_t kQueued = 256;

 private:
  // Queues msg for topic at time t. latched: marks the connection so that `rosbag play` latches
  // it, as the node does live.
  template <class M>
  void write(const std::string& topic, Real t, M msg, bool latched = false);
  void enqueue(std::function<void(rosbag::Bag&)> write);
  void drain();                                 // waits until every queued message is in the file
  [[noreturn]] void throwWriteFailure() const;  // the writer's error, on the caller's thread

  std::unique_ptr<rosbag::Bag> bag_;
  bool open_ = false;
  RecordDef def_;
  std::string path_;
  std::string state_text_;
  SampleClock clouds_, states_, checkpoints_;
  Real last_checkpoint_ = -1;  // s
  long messages_ = 0;
  bool started_ = false;
  sensor_msgs::PointCloud2 cloud_, fem_cloud_;  // filled in place, copied into the queue
  // Writes the queued messages; last: stopped before the bag is closed.
  std::unique_ptr<BoundedWorker<std::function<void(rosbag::Bag&)>>> writer_;
};

}  // namespace mpm_sdem
