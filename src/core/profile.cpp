#include "mpm_sdem/core/profile.hpp"

namespace mpm_sdem {

const char* stageName(Stage stage) {
  switch (stage) {
    case Stage::kTimeStep:
      return "time_step";
    case Stage::kContact:
      return "contact";
    case Stage::kSort:
      return "sort";
    case Stage::kClearGrid:
      return "clear_grid";
    case Stage::kP2G:
      return "p2g";
    case Stage::kGridUpdate:
      return "grid_update";
    case Stage::kG2P:
      return "g2p";
    case Stage::kConstitutive:
      return "constitutive";
    case Stage::kVolumeFit:
      return "volume_fit";
    case Stage::kStress:
      return "stress_force";
    case Stage::kBodies:
      return "bodies";
    case Stage::kSph:
      return "sph";
    case Stage::kCount:
      break;
  }
  return "?";
}

double Profile::total() const {
  double t = 0;
  for (double s : seconds) t += s;
  return t;
}

}  // namespace mpm_sdem
