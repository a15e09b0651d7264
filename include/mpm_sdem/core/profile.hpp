// Wall-clock time spent in each named stage of the step (Box2D's b2Profile, accumulated).
#pragma once

#include <chrono>

namespace mpm_sdem {

enum class Stage : int {
  kTimeStep,
  kContact,
  kClearGrid,
  kP2G,
  kGridUpdate,
  kG2P,
  kConstitutive,
  kBlocks,
  kCount
};

const char* stageName(Stage stage);

struct Profile {
  double seconds[static_cast<int>(Stage::kCount)] = {};
  long steps = 0;
  double total() const;
};

class StageTimer {
 public:
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
