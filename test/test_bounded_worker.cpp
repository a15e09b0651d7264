// BoundedWorker (the recorders' writer threads): every job queued is done once, in order, also
// when the queue is full and the caller waits; a job that throws stops the worker, drops what is
// still queued and reports its error to the caller; finish() does what is queued first.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mpm_sdem/core/bounded_worker.hpp"

using namespace mpm_sdem;

// 200 jobs through a queue of 3, each slower than queuing it: the caller waits on a full queue
// (3 jobs waiting behind the one being done, never more), none is lost or reordered.
TEST(BoundedWorker, DoesEveryJobInOrderThroughAFullQueue) {
  std::vector<int> done;
  std::atomic<int> pushed{0};
  std::size_t most_waiting = 0;
  BoundedWorker<int> worker(3, [&](int& job) {
    std::this_thread::sleep_for(std::chrono::microseconds(50));
    most_waiting = std::max(most_waiting, static_cast<std::size_t>(pushed - job - 1));
    done.push_back(job);
  });
  for (int k = 0; k < 200; ++k) {
    ASSERT_TRUE(worker.push(k));
    ++pushed;
  }
  ASSERT_TRUE(worker.drain());
  ASSERT_EQ(done.size(), 200u);
  for (int k = 0; k < 200; ++k) EXPECT_EQ(done[k], k);
  EXPECT_EQ(most_waiting, 3u);  // full at times, never fuller (without the wait: 199)
  EXPECT_EQ(worker.failure(), "");
}

// The job that throws: its message is kept, the jobs after it are not done, push and drain say
// so instead of waiting, and finish() returns.
TEST(BoundedWorker, AFailedJobStopsTheWorkerAndTellsTheCaller) {
  std::vector<int> done;
  BoundedWorker<int> worker(8, [&](int& job) {
    if (job == 2) throw std::runtime_error("disk full");
    done.push_back(job);
  });
  for (int k = 0; k < 5; ++k) worker.push(k);
  EXPECT_FALSE(worker.drain());
  EXPECT_EQ(worker.failure(), "disk full");
  EXPECT_FALSE(worker.push(9));
  worker.finish();
  EXPECT_EQ(done, (std::vector<int>{0, 1}));
}

// finish() with jobs still queued: all done before it returns, nothing accepted after.
TEST(BoundedWorker, FinishDoesTheQueuedJobsFirst) {
  std::vector<int> done;
  BoundedWorker<int> worker(16, [&](int& job) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
    done.push_back(job);
  });
  for (int k = 0; k < 10; ++k) worker.push(k);
  worker.finish();
  EXPECT_EQ(done.size(), 10u);
  EXPECT_FALSE(worker.push(10));
  worker.finish();  // idempotent
  EXPECT_EQ(done.size(), 10u);
}
