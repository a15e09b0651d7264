// /clock sent from a thread of its own. Each message the simulation's thread published itself
// cost it about 27 us on this machine kind (roscpp wakes its poll thread through a pipe for every
// other node that follows /use_sim_time, rosout among them, and the node's own time thread): 5%
// of the default scene's loop at ROS's usual 1 kHz of simulated time. Here the simulation's
// thread only queues the times; this thread sends them in order once per millisecond of wall
// time, so a listener's time lags the node's other topics by at most that. No message is
// dropped: /clock keeps its rate in simulated time (`rates/clock`). After 0.1 s of wall time
// without a message (a paused or stopped run) the thread sleeps until the next one, which then
// wakes it: an idle node's thread wakes for its messages only. Not BoundedWorker (the recorders'
// writer thread): its push wakes the worker for every job, the system call saved here. The queue
// holds about a millisecond of messages: ros::Publisher::publish does not block.
#pragma once

#include <ros/ros.h>

#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

namespace mpm_sdem::node {

class ClockPublisher {
 public:
  explicit ClockPublisher(ros::NodeHandle& nh);  // advertises /clock
  ~ClockPublisher();                             // sends what is queued, then ends the thread
  ClockPublisher(const ClockPublisher&) = delete;
  ClockPublisher& operator=(const ClockPublisher&) = delete;

  // Queues t for /clock (no system call while messages come: the thread finds it at its next
  // millisecond).
  void post(const ros::Time& t);

 private:
  void loop();

  ros::Publisher pub_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::vector<ros::Time> queued_;
  bool stopping_ = false;
  bool asleep_ = false;  // idle: the next post() wakes the thread
  std::thread thread_;   // last: started once the rest is in place
};

}  // namespace mpm_sdem::node
