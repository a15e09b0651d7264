/// \file
/// Wall-clock time spent in each stage of the step (Box2D's b2Profile, accumulated).
#pragma once

#include <chrono>
#include <vector>

#include "mpm_sdem/core/step_stages.hpp"

namespace mpm_sdem {

/// Wall time spent in each stage of the step (s) and the steps counted.
struct Profile {
  double seconds[static_cast<int>(Stage::kCount)] = {};  ///< per stage
  /// Whether the stage ran since the start: time_step, and every stage of each step the world
  /// composed (World::composeStep). Outputs list these alone, in step order.
  bool used[static_cast<int>(Stage::kCount)] = {};
  long steps = 0;  ///< steps timed
  /// All stages together (s).
  double total() const;
  /// The stages that ran, in step order.
  std::vector<Stage> usedStages() const;
  /// The stages of one owner together (s): the coupling's, the bodies', the SPH region's, ...
  double ownerSeconds(StageOwner owner) const;
  /// This profile less an earlier one of the same run (the stages used are this one's).
  Profile since(const Profile& earlier) const;
};

/// Adds the wall time from its construction to its destruction to one stage of a Profile.
class StageTimer {
 public:
  /// Starts timing stage into profile.
  StageTimer(Profile& profile, Stage stage)
      : slot_(profile.seconds[static_cast<int>(stage)]), start_(Clock::now()) {}
  ~StageTimer() { slot_ += std::chrono::duration<double>(Clock::now() - start_).count(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  using Clock = std::chrono::steady_clock;
  double& slot_;
  Clock::time_point start_;
};

}  // namespace mpm_sdem
