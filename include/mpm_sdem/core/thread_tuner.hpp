/// \file
/// Chooses the OpenMP thread count of a long run from measured step times. While another process
/// loads a core, every parallel region waits for the thread that shares it with that process: the
/// default scene ran at 0.006-0.06 x real time on two threads against 1.2 x on one. So
/// the tuner starts on one thread, keeps the fastest count it has measured and, every kPeriod
/// seconds, tries the next smaller or larger count for a few steps (the first, and the one after
/// a switch, after kFirstTrial s), and switches when that is at least 15% faster. A trial that is
/// clearly slower ends early, so a bad count costs little.
#pragma once

#include <deque>
#include <vector>

namespace mpm_sdem {

/// Chooses the OpenMP thread count from measured step times (see the file's comment).
class ThreadTuner {
 public:
  static constexpr double kFirstTrial = 0.5;        ///< s of stepping before the first trial
  static constexpr double kPeriod = 5;              ///< s of stepping between trials
  static constexpr double kTrialSeconds = 0.2;      ///< a trial's length (at least kTrialSteps)
  static constexpr double kReferenceSeconds = 0.5;  ///< the best count's latest steps, compared
  static constexpr int kTrialSteps = 10;            ///< the fewest steps a trial takes
  static constexpr double kGain = 0.85;  ///< a trial must take under this fraction of the time

  /// max_threads: the most to use (1 keeps one thread and never tries another count); it starts
  /// on one.
  explicit ThreadTuner(int max_threads);
  /// Sets the OpenMP thread count for the coming step.
  void beforeStep();
  /// The wall time the step took (s).
  void afterStep(double seconds);
  /// The count the coming step runs on.
  int threads() const { return current_; }
  /// The fastest count measured so far.
  int best() const { return best_; }

 private:
  void startTrial();
  void endTrial();

  int max_, best_, current_;
  bool trial_ = false;
  bool trial_up_ = false;  ///< the next trial tries more threads
  bool tried_ = false;     ///< a trial has run since the start or the last switch
  /// The best count's latest step times, about kReferenceSeconds of them: the reference a trial is
  /// compared with, as close to it in time as possible (a run's first steps are slower).
  std::deque<double> recent_;
  double recent_sum_ = 0;
  double best_seconds_ = 0;  ///< mean of recent_ when the trial started
  std::vector<double> trial_times_;
  double trial_seconds_ = 0;
  double since_trial_ = 0;  ///< s of stepping since the last trial ended
};

}  // namespace mpm_sdem
