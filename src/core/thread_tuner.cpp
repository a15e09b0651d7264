#include "mpm_sdem/core/thread_tuner.hpp"

#include <omp.h>

#include <algorithm>

namespace mpm_sdem {

ThreadTuner::ThreadTuner(int max_threads)
    : max_(std::max(1, max_threads)), best_(max_), current_(max_) {}

void ThreadTuner::beforeStep() {
  if (omp_get_max_threads() != current_) omp_set_num_threads(current_);
}

void ThreadTuner::afterStep(double seconds) {
  window_seconds_ += seconds;
  window_steps_ += 1;
  if (trial_) {
    const double mean = window_seconds_ / window_steps_;
    const bool long_enough = window_steps_ >= kTrialSteps && window_seconds_ >= kTrialSeconds;
    if (long_enough || mean > 2 * best_seconds_) endTrial();
    return;
  }
  since_trial_ += seconds;
  if (since_trial_ >= kPeriod && max_ > 1) startTrial();
}

void ThreadTuner::startTrial() {
  best_seconds_ = window_seconds_ / window_steps_;
  const int up = std::min(max_, 2 * best_), down = std::max(1, best_ / 2);
  if (up == best_) trial_up_ = false;
  if (down == best_) trial_up_ = true;
  current_ = trial_up_ ? up : down;
  trial_up_ = !trial_up_;
  trial_ = true;
  window_seconds_ = window_steps_ = 0;
}

void ThreadTuner::endTrial() {
  if (window_seconds_ / window_steps_ < kGain * best_seconds_) best_ = current_;
  current_ = best_;
  trial_ = false;
  window_seconds_ = window_steps_ = since_trial_ = 0;
}

}  // namespace mpm_sdem
