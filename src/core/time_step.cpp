#include "mpm_sdem/core/time_step.hpp"

namespace mpm_sdem {

const char* stepLimitName(StepLimit limit) {
  switch (limit) {
    case StepLimit::kFixed:
      return "fixed";
    case StepLimit::kCfl:
      return "cfl";
    case StepLimit::kContact:
      return "contact";
    case StepLimit::kElement:
      return "element";
    case StepLimit::kViscous:
      return "viscous";
    case StepLimit::kSph:
      return "sph";
    case StepLimit::kMax:
      return "max";
  }
  return "?";
}

}  // namespace mpm_sdem
