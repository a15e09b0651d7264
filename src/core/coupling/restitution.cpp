#include "mpm_sdem/core/coupling/restitution.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace mpm_sdem {

// The overlap x obeys x'' + 2 zeta w x' + w^2 x = 0 from x = 0, x' = v0 > 0, and the contact
// ends when the force k x + c x' (proportional to w x + 2 zeta x') reaches zero, before the
// overlap does; from then on nothing acts, so e = -x'(end) / v0. Both regimes give
// e = exp(-zeta w t_end), the factor in front of the exponential being exactly 1:
//  - zeta < 1, s = sqrt(1 - zeta^2): x = v0 / (w s) exp(-zeta w t) sin(theta), theta = w s t.
//    The force vanishes at tan(theta) = -2 zeta s / (1 - 2 zeta^2), i.e. at
//    theta = pi - atan2(2 zeta s, 1 - 2 zeta^2) = 2 atan2(s, zeta) (cos = 2 zeta^2 - 1,
//    sin = 2 zeta s), where x' = v0 exp(-zeta theta / s) (cos theta - zeta / s sin theta) and the
//    bracket is -1. The half-angle form has no cancellation as zeta -> 1 (theta / s -> 2).
//  - zeta > 1, q = sqrt(zeta^2 - 1): x is a difference of exp(w (-zeta +- q) t); the force
//    vanishes at w t = 2 atanh(q / zeta) / q, where again x' = -v0 exp(-zeta w t).
//  - zeta = 1: the limit of both, w t = 2 and e = exp(-2).
// Without the clipping (force allowed to pull until x = 0) the under-damped contact would end at
// theta = pi, the textbook e = exp(-zeta pi / s), which is lower: the clipped contact gives back
// the speed it still has when the dashpot would start to pull.
Real clippedRestitution(Real zeta) {
  if (!(zeta > 0)) return 1;
  if (zeta < 1) {
    const Real s = std::sqrt(1 - zeta * zeta);
    return std::exp(-2 * zeta * std::atan2(s, zeta) / s);
  }
  if (zeta == 1) return std::exp(Real(-2));
  const Real q = std::sqrt(zeta * zeta - 1);
  return std::exp(-2 * zeta * std::atanh(q / zeta) / q);
}

Real restitutionDampingRatio(Real e) {
  if (!(e > 0 && e <= 1))
    throw std::invalid_argument("restitution must be in (0, 1], got " + std::to_string(e));
  if (e == 1) return 0;
  // clippedRestitution falls monotonically from 1 to 0: bracket e, then bisect to round-off.
  Real lo = 0, hi = 1;
  while (clippedRestitution(hi) > e) {
    lo = hi;
    hi *= 2;
  }
  for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
    const Real mid = 0.5 * (lo + hi);
    (clippedRestitution(mid) > e ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Symplectic Euler (Box2D's, and the MPM's kick then drift) on x'' = -w^2 x - 2 zeta w x' has
// the amplification matrix of trace 2 - 2 zeta w h - (w h)^2 and determinant 1 - 2 zeta w h; it
// is stable while (w h)^2 + 4 zeta (w h) <= 4, i.e. w h <= 2 (sqrt(1 + zeta^2) - zeta).
Real contactTimeStep(Real m, Real k, Real zeta, int n, Real kappa2) {
  const Real w = std::sqrt(n * k / m);
  return M_PI * kappa2 * 2 / w * (std::sqrt(1 + zeta * zeta) - zeta);
}

// With w = sqrt(k / m), zeta = c / (2 sqrt(k m)) and s2 = w^2 (1 - zeta^2) (either sign), every
// solution of the oscillator is exp(-zeta w t) (a C(t) + b S(t)) with C = cos, S = sin / sqrt(s2)
// when s2 > 0, cosh and sinh / sqrt(-s2) when s2 < 0, and C = 1, S = t at critical damping: the
// overlap with a = x0, b = x0' + zeta w x0, its rate with a = x0', b = -(zeta w x0' + w^2 x0),
// and the force k x + c x', which obeys the same equation, with a = f0,
// b = f0' + zeta w f0 = k x0' - c f0 / m + zeta w f0. Its first zero solves tan or tanh of
// sqrt(|s2|) t = -a sqrt(|s2|) / b, or t = -a / b; the tangent's root exists for any b (the
// force of an under-damped contact always ends), the others only for b < -a sqrt(|s2|).
Real clippedSpringImpulse(Real m, Real k, Real c, Real x, Real u, Real dt) {
  Real span = dt;
  if (x <= 0) {  // apart: contact starts when x = 0, if within the step
    if (!(u > 0) || x + u * span <= 0) return 0;
    span += x / u;
    x = 0;
  }
  const Real f0 = k * x + c * u;
  // Separating faster than the spring pushes (or touching at rest): it never acts.
  if (!(f0 > 0 || (f0 == 0 && u > 0))) return 0;
  const Real w = std::sqrt(k / m), zw = c / (2 * m), s2 = w * w - zw * zw;
  const Real b = k * u - c * f0 / m + zw * f0;
  // The force's first zero, if before the end of the step.
  Real t = span;
  if (s2 > 0) {
    const Real s = std::sqrt(s2);
    t = std::fmin(t, std::atan2(f0 * s, -b) / s);
  } else if (s2 < 0) {
    const Real s = std::sqrt(-s2);
    if (-b > f0 * s) t = std::fmin(t, std::atanh(f0 * s / -b) / s);
  } else if (b < 0) {
    t = std::fmin(t, -f0 / b);
  }
  return m * (u - dampedOscillatorRate(w * w, zw, x, u, t));
}

namespace {

// exp(-zeta w t) C(t) and exp(-zeta w t) S(t) of the oscillator (above, s2 = w2 - zw^2); the
// hyperbolic ones as sums of decaying exponentials (s < zeta w), which cannot overflow however
// stiff or damped the oscillator.
std::pair<Real, Real> decayedModes(Real w2, Real zw, Real t) {
  const Real s2 = w2 - zw * zw;
  if (s2 > 0) {
    const Real s = std::sqrt(s2), decay = std::exp(-zw * t);
    return {decay * std::cos(s * t), decay * std::sin(s * t) / s};
  }
  if (s2 < 0) {
    const Real s = std::sqrt(-s2);
    const Real slow = std::exp((s - zw) * t), fast = std::exp(-(s + zw) * t);
    // eS's relative round-off is eps / (s t) near critical damping.
    return {(slow + fast) / 2, (slow - fast) / (2 * s)};
  }
  const Real decay = std::exp(-zw * t);
  return {decay, decay * t};
}

}  // namespace

Real dampedOscillatorRate(Real w2, Real zw, Real x, Real u, Real t) {
  const auto [eC, eS] = decayedModes(w2, zw, t);
  return u * eC - (zw * u + w2 * x) * eS;
}

// The exact solution sampled every h obeys x_{n+1} = T x_n - D x_{n-1} with D = exp(-2 zeta w h)
// and T = 2 exp(-zeta w h) C(h) (the amplification's determinant and trace). Symplectic Euler,
// x_{n+1} - 2 x_n + x_{n-1} = -h^2 (w2' x_n + 2 zw' v_{n-1/2}) with v_{n-1/2} = (x_n - x_{n-1}) /
// h, obeys the same recurrence for w2' = (1 + D - T) / h^2 and 2 zw' = (1 - D) / h.
ExactStepSpring exactStepSpring(Real w2, Real zw, Real h) {
  ExactStepSpring e;
  // 1 - D without cancellation; 1 + D - T loses eps / (w h)^2 of its value, so below
  // (w h)^2 = 1e-8 the spring itself (relative difference (w h)^2 / 12).
  e.damping = zw * h > 1e-300 ? -std::expm1(-2 * zw * h) / h : 2 * zw;
  if (w2 * h * h < 1e-8) {
    e.stiffness = w2;
  } else {
    const Real eC = decayedModes(w2, zw, h).first;
    e.stiffness = (1 + std::exp(-2 * zw * h) - 2 * eC) / (h * h);
  }
  return e;
}

}  // namespace mpm_sdem
