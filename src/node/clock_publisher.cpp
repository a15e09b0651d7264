#include "clock_publisher.hpp"

#include <rosgraph_msgs/Clock.h>

#include <chrono>

namespace mpm_sdem::node {

// The outgoing queue holds a second of /clock at its 1 kHz: a listener whose connection stalls
// for a few milliseconds (a busy machine) gets every message late rather than losing some. With
// 10, CI once saw a 4 ms gap (three messages dropped by the publisher).
constexpr uint32_t kClockQueue = 1000;

ClockPublisher::ClockPublisher(ros::NodeHandle& nh)
    : pub_(nh.advertise<rosgraph_msgs::Clock>("/clock", kClockQueue)),
      thread_([this] { loop(); }) {}

ClockPublisher::~ClockPublisher() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void ClockPublisher::post(const ros::Time& t) {
  std::lock_guard<std::mutex> lock(mutex_);
  queued_.push_back(t);
  if (asleep_) wake_.notify_one();
}

void ClockPublisher::loop() {
  std::vector<ros::Time> sending;
  rosgraph_msgs::Clock message;
  constexpr int kIdlePeriods = 100;  // 0.1 s without a message: sleep until one comes
  int idle = 0;
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    // A period, not a wake-up per message: waking this thread would cost the simulation's
    // thread the system call this class saves it.
    const bool sleep = idle >= kIdlePeriods;
    if (!sleep) {
      wake_.wait_for(lock, std::chrono::milliseconds(1), [this] { return stopping_; });
    } else {
      asleep_ = true;
      wake_.wait(lock, [this] { return stopping_ || !queued_.empty(); });
      asleep_ = false;
    }
    // Woken by a message (a paused run's, every 0.5 s), one empty period sends it back to sleep.
    idle = queued_.empty() ? idle + 1 : sleep ? kIdlePeriods - 1 : 0;
    sending.swap(queued_);
    const bool last = stopping_;
    lock.unlock();
    for (const ros::Time& t : sending) {
      message.clock = t;
      pub_.publish(message);
    }
    sending.clear();
    if (last) return;
    lock.lock();
  }
}

}  // namespace mpm_sdem::node
