#include "mpm_sdem/core/profile.hpp"

namespace mpm_sdem {

double Profile::total() const {
  double t = 0;
  for (double s : seconds) t += s;
  return t;
}

std::vector<Stage> Profile::usedStages() const {
  std::vector<Stage> stages;
  for (int k = 0; k < static_cast<int>(Stage::kCount); ++k)
    if (used[k]) stages.push_back(static_cast<Stage>(k));
  return stages;
}

double Profile::ownerSeconds(StageOwner owner) const {
  double t = 0;
  for (int k = 0; k < static_cast<int>(Stage::kCount); ++k)
    if (stageInfo(static_cast<Stage>(k)).owner == owner) t += seconds[k];
  return t;
}

Profile Profile::since(const Profile& earlier) const {
  Profile d = *this;
  for (int k = 0; k < static_cast<int>(Stage::kCount); ++k) d.seconds[k] -= earlier.seconds[k];
  d.steps -= earlier.steps;
  return d;
}

}  // namespace mpm_sdem
