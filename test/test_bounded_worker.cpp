// BoundedWorker (the recorders' writer threads): every job queued is done once, in order, also
// when the queue is full and the caller waits; a job that throws stops the worker, drops what is
// still queued and reports its error to the caller; finish() does what is queued first.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "mpm_sdem/core/bounded_worker.hpp"

using namespace mpm_sdem;

// A producer thread pushes 200 jobs through a queue of 3 while the first job is held: it must
// stop after 4 pushes (the held job and 3 waiting) until the job is let go; then every job is
// done once, in order, never more than 3 waiting.
TEST(BoundedWorker, DoesEveryJobInOrderThroughAFullQueue) {
  std::vector<int> done;
  std::atomic<int> begun{0};   // push(k) called
  std::atomic<int> pushed{0};  // push(k) returned
  std::atomic<bool> hold{true};
  int most_waiting = 0;
  BoundedWorker<int> worker(3, [&](int& job) {
    while (hold) std::this_thread::sleep_for(std::chrono::milliseconds(1));
    // While job runs, push(begun - 1) may still wait, but push(begun - 2) has returned: jobs
    // job + 1 .. begun - 2 are queued. Counting from `pushed` instead races (the worker may
    // take a job before its push() returns) and could go below zero.
    most_waiting = std::max(most_waiting, begun - job - 2);
    done.push_back(job);
  });
  std::thread producer([&] {
    for (int k = 0; k < 200; ++k) {
      ++begun;
      if (!worker.push(k)) return;
      ++pushed;
    }
  });
  while (pushed < 4) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(pushed, 4);  // the producer waits on the full queue (without the wait: 200)
  hold = false;
  producer.join();
  ASSERT_TRUE(worker.drain());
  ASSERT_EQ(done.size(), 200u);
  for (int k = 0; k < 200; ++k) EXPECT_EQ(done[k], k);
  EXPECT_LE(most_waiting, 3);
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
