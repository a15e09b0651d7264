// Shared pieces of the node tests: waiting on a condition while callbacks run, latest messages.
#pragma once

#include <mpm_sdem/BlockStates.h>
#include <mpm_sdem/SimStats.h>
#include <ros/ros.h>

#include <chrono>
#include <functional>
#include <mutex>
#include <thread>

namespace mpm_sdem::test {

// Polls cond every 10 ms of wall time until it holds or timeout_s passes.
inline bool waitFor(const std::function<bool()>& cond, double timeout_s) {
  const auto end = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < end) {
    if (cond()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return cond();
}

// Keeps the last message of a topic (callbacks on an AsyncSpinner thread).
template <class M>
class Latest {
 public:
  Latest(ros::NodeHandle& nh, const std::string& topic)
      : sub_(nh.subscribe(topic, 100, &Latest::onMessage, this)) {}
  bool has() const {
    std::lock_guard<std::mutex> l(m_);
    return count_ > 0;
  }
  M get() const {
    std::lock_guard<std::mutex> l(m_);
    return msg_;
  }
  long count() const {
    std::lock_guard<std::mutex> l(m_);
    return count_;
  }

 private:
  void onMessage(const typename M::ConstPtr& msg) {
    std::lock_guard<std::mutex> l(m_);
    msg_ = *msg;
    ++count_;
  }
  mutable std::mutex m_;
  M msg_;
  long count_ = 0;
  ros::Subscriber sub_;
};

inline const mpm_sdem::RigidBlockState* findBlock(const mpm_sdem::BlockStates& s,
                                                  const std::string& name) {
  for (const auto& b : s.blocks)
    if (b.name == name) return &b;
  return nullptr;
}

}  // namespace mpm_sdem::test
