// Independent runs of one test side by side. ctest runs one test at a time (scripts/test), and a
// small world gains nothing from a second thread (the thrown disk of test_rolling: 16.3 s on two
// threads, 16.8 s on one), so a test of several runs runs them at once, one per core, each world
// on one thread (its OpenMP regions run on the thread that steps it). A world computes the same
// bits on any number of threads (test_threads), so the results are those of the runs one after
// another.
#pragma once

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <thread>
#include <vector>

namespace mpm_sdem::test {

// f(0), ..., f(n - 1), on as many threads as the machine has cores, each taking the next i as it
// comes free; the results in order of i. An exception thrown by any call is thrown again here
// once all have ended. With MPM_SDEM_TEST_SERIAL set in the environment the calls run one after
// another on the calling thread (to check that they compute the same).
template <class R, class F>
std::vector<R> runAll(int n, F f) {
  std::vector<R> out(n);
  std::vector<std::exception_ptr> errors(n);
  std::atomic<int> next{0};
  auto work = [&] {
    omp_set_num_threads(1);  // this thread's worlds step on it alone
    for (int i = next++; i < n; i = next++) {
      try {
        out[i] = f(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  if (std::getenv("MPM_SDEM_TEST_SERIAL")) {
    for (int i = 0; i < n; ++i) out[i] = f(i);
    return out;
  }
  const int threads = std::max(1, std::min<int>(n, std::thread::hardware_concurrency()));
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(work);
  for (std::thread& t : pool) t.join();
  for (const std::exception_ptr& e : errors)
    if (e) std::rethrow_exception(e);
  return out;
}

}  // namespace mpm_sdem::test
