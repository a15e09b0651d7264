/// \file
/// Damping of the linear spring contacts (block-block penalty springs, IMP springs) from the
/// restitution a scene asks for, the explicit time step such a contact allows, and its impulse
/// over a step integrated in closed form (which allows any step).
#pragma once

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Normal restitution of a linear spring-dashpot contact that cannot pull (the force
/// max(k x + c x', 0) of seed 000 eq. 43 with a dashpot c = 2 zeta sqrt(k m)): the ratio of the
/// speeds at which the force ends and at which the overlap began, in closed form for any
/// zeta >= 0. It falls from 1 at zeta = 0 through exp(-2) = 0.135 at zeta = 1 towards 0 as zeta
/// grows (about 1 / (4 zeta^2)).
Real clippedRestitution(Real zeta);

/// The inverse of clippedRestitution: the damping ratio that gives restitution e, for e in (0, 1]
/// (throws std::invalid_argument outside). The dashpot is 2 ratio sqrt(k m) for the effective
/// mass m of the contact.
Real restitutionDampingRatio(Real e);

/// Stable explicit step for n equal springs k acting in parallel on a mass m and damped together
/// with ratio zeta (their dashpots add up to 2 zeta sqrt(n k m)): pi * kappa_2 times the critical
/// step (2 / w) (sqrt(1 + zeta^2) - zeta), w = sqrt(n k / m), of symplectic Euler with the
/// damping force taken explicitly. With n = 1 and no damping it is seed 000 eq. 51's
/// 2 pi kappa_2 sqrt(m / k).
Real contactTimeStep(Real m, Real k, Real zeta, int n, Real kappa2);

/// The impulse (N s per metre of thickness, >= 0) that such a contact gives a free pair of reduced
/// mass m over a step dt, integrated exactly: m x'' = -max(k x + c x', 0) from the overlap x
/// (m; <= 0 when apart) and its rate x' (m/s; > 0 approaching) at the start of the step. A pair
/// still apart starts touching when x reaches 0 within the step; the force ends when it would
/// pull. The impulse is m (x'(start of contact) - x'(end of the step or of contact)), so at any
/// dt it stops at most what approaches and gives back at most what the spring stored.
Real clippedSpringImpulse(Real m, Real k, Real c, Real overlap, Real rate, Real dt);

/// The rate x'(t) of the free damped oscillator x'' = -w2 x - 2 zw x' (w2 = k / m, zw = c / (2 m),
/// both >= 0) from x(0) = x and x'(0) = u, in closed form for any t: the spring may pull.
Real dampedOscillatorRate(Real w2, Real zw, Real x, Real u, Real t);

/// The spring and dashpot per unit mass (1/s^2, 1/s) with which symplectic Euler at step h
/// (v += h a, then x += h v: Box2D's and the MPM's) lands exactly on the oscillator
/// x'' = -w2 x - 2 zw x' at every step, however large h: both tend to w2 and 2 zw as h -> 0.
struct ExactStepSpring {
  Real stiffness = 0;  ///< 1/s^2
  Real damping = 0;    ///< 1/s
};
/// The spring and dashpot per unit mass for the oscillator w2, zw at step h (above).
ExactStepSpring exactStepSpring(Real w2, Real zw, Real h);

}  // namespace mpm_sdem
