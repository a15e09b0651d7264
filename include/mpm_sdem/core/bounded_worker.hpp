/// \file
/// Jobs done in order by a thread of their own, at most a fixed number waiting: the recorders'
/// writers (the bag's messages, the video's frames), so that the simulation's thread only makes
/// the jobs. A full queue makes the caller wait, so no job is dropped; a job that throws stops
/// the worker, and its error is kept for the caller's thread (an exception must not leave the
/// worker: std::terminate would leave the bag unclosed).
#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace mpm_sdem {

template <class Job>
/// Jobs of type Job done in order on a thread of their own, at most capacity waiting (see the
/// file's comment).
class BoundedWorker {
 public:
  /// run(job) is called on the worker's thread, one job at a time, in the order queued.
  BoundedWorker(std::size_t capacity, std::function<void(Job&)> run)
      : capacity_(capacity), run_(std::move(run)), thread_([this] { loop(); }) {}
  ~BoundedWorker() { finish(); }
  BoundedWorker(const BoundedWorker&) = delete;
  BoundedWorker& operator=(const BoundedWorker&) = delete;

  /// Queues job, waiting while `capacity` jobs wait. False, and nothing queued, once a job has
  /// failed or finish() was called.
  bool push(Job job) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return queue_.size() < capacity_ || stopped(); });
    if (stopped()) return false;
    queue_.push_back(std::move(job));
    changed_.notify_all();
    return true;
  }
  /// Waits until every job queued is done. False when a job failed.
  bool drain() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return (queue_.empty() && running_ == 0) || !failure_.empty(); });
    return failure_.empty();
  }
  /// Does the jobs still queued (up to a failure) and ends the thread; idempotent.
  void finish() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      finishing_ = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }
  /// "" or the error of the job that stopped the worker.
  std::string failure() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return failure_;
  }

 private:
  bool stopped() const { return finishing_ || !failure_.empty(); }
  void loop() {
    std::unique_lock<std::mutex> lock(mutex_);
    for (;;) {
      changed_.wait(lock, [this] { return finishing_ || !queue_.empty(); });
      if (queue_.empty()) return;  // finishing, and every job done
      Job job = std::move(queue_.front());
      queue_.pop_front();
      ++running_;
      changed_.notify_all();
      lock.unlock();
      std::string error;
      bool failed = false;
      try {
        run_(job);
      } catch (const std::exception& e) {
        error = e.what();
        failed = true;
      }
      lock.lock();
      --running_;
      changed_.notify_all();
      if (failed) {
        failure_ = error.empty() ? "unknown error" : error;
        queue_.clear();
        changed_.notify_all();
        return;
      }
    }
  }

  const std::size_t capacity_;
  const std::function<void(Job&)> run_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> queue_;
  int running_ = 0;  ///< taken from the queue, not yet done
  bool finishing_ = false;
  std::string failure_;
  std::thread thread_;  ///< last: started once the rest is in place
};

}  // namespace mpm_sdem
