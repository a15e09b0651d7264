#include "mpm_sdem/core/thread_tuner.hpp"

#include <omp.h>

#include <algorithm>

namespace mpm_sdem {

// It starts on one thread, the count no other process can stall, and tries more after
// kFirstTrial: the default scene's first second ran 23% faster in the node than from two
// threads (docs/robustness.md, Threads on a busy machine).
ThreadTuner::ThreadTuner(int max_threads) : max_(std::max(1, max_threads)), best_(1), current_(1) {}

void ThreadTuner::beforeStep() {
  if (omp_get_max_threads() != current_) omp_set_num_threads(current_);
}

namespace {

// Means, not medians: a loaded core shows as a few steps stalled for 100 ms among fast ones, and
// it is their total that costs.
double mean(const std::vector<double>& v) {
  double sum = 0;
  for (double x : v) sum += x;
  return sum / v.size();
}

}  // namespace

void ThreadTuner::afterStep(double seconds) {
  if (trial_) {
    trial_times_.push_back(seconds);
    trial_seconds_ += seconds;
    const int n = static_cast<int>(trial_times_.size());
    const bool long_enough = n >= kTrialSteps && trial_seconds_ >= kTrialSeconds;
    // A count that is clearly slower (a loaded core) ends its trial within three steps.
    const bool hopeless = (n == 1 && seconds > 10 * best_seconds_) ||
                          (n >= 3 && mean(trial_times_) > 2 * best_seconds_);
    if (long_enough || hopeless) endTrial();
    return;
  }
  recent_.push_back(seconds);
  recent_sum_ += seconds;
  while (static_cast<int>(recent_.size()) > kTrialSteps &&
         recent_sum_ - recent_.front() >= kReferenceSeconds) {
    recent_sum_ -= recent_.front();
    recent_.pop_front();
  }
  since_trial_ += seconds;
  if (since_trial_ >= (tried_ ? kPeriod : kFirstTrial) && max_ > 1) startTrial();
}

void ThreadTuner::startTrial() {
  best_seconds_ = recent_sum_ / recent_.size();
  const int up = std::min(max_, 2 * best_), down = std::max(1, best_ / 2);
  if (up == best_) trial_up_ = false;
  if (down == best_) trial_up_ = true;
  current_ = trial_up_ ? up : down;
  trial_up_ = !trial_up_;
  trial_ = true;
  trial_times_.clear();
  trial_seconds_ = 0;
}

void ThreadTuner::endTrial() {
  // A switch is checked soon by a trial of the count it left (a noisy window is undone).
  const bool faster = mean(trial_times_) < kGain * best_seconds_;
  if (faster) {
    best_ = current_;
    recent_.clear();  // the reference is now the new count's
    recent_sum_ = 0;
  }
  current_ = best_;
  trial_ = false;
  tried_ = !faster;
  since_trial_ = 0;
}

}  // namespace mpm_sdem
