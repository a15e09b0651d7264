/// \file
/// How the step is chosen (seed 000 eq. 51) and which term chose it.
#pragma once

#include <limits>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// How the step is chosen (scene section `time`).
struct TimeStepDef {
  bool automatic = true;  ///< CFL bound, re-evaluated every step
  Real fixed = 0;         ///< s, when !automatic
  Real cfl = 0.3;         ///< kappa_1 of seed 000 eq. 51: dt = cfl * h / max(c_p + |v_p|)
  Real max = std::numeric_limits<Real>::infinity();  ///< s, upper bound on the automatic step
  /// kappa_2 of seed 000 eq. 51: dt <= 2 pi kappa_2 sqrt(m_min / k_n) for every spring contact,
  /// m_min the lightest mass on either side (an IMP spring acts on one light material point).
  Real contact_factor = 0.1;
  /// FEM bodies: false, one step per material step (their element step times kappa_1 bounds
  /// it); true, multi-rate: substeps of at most kappa_1 times the element step within the
  /// material's step (FemBodies::setMaxSubstep).
  bool fem_subcycled = false;
};

/// Which term set the time step.
/// kElement: the FEM bodies' elements (FemBodies::elementStep times kappa_1).
/// kViscous: a fluid's viscous diffusion (h^2 / (2 nu) times kappa_1).
/// kSph: the SPH particles' signal speed over the smoothing length (detail::sphSignalSpeed).
enum class StepLimit { kFixed, kCfl, kContact, kElement, kViscous, kSph, kMax };
/// The term's name as outputs print it ("cfl", "contact", ...).
const char* stepLimitName(StepLimit limit);

/// A stable step and the term that set it.
struct TimeStepChoice {
  Real dt = 0;                          ///< s
  StepLimit limit = StepLimit::kFixed;  ///< the term that set it
  /// This choice, or (dt, limit) when dt is shorter.
  void takeShorter(Real other_dt, StepLimit other_limit) {
    if (other_dt < dt) *this = {other_dt, other_limit};
  }
};

}  // namespace mpm_sdem
