// The momentum exchange of seed 002 (eq. 27-32 at a node, eq. 47-52 at a particle) for a contact
// between a material velocity and a contact body: the impulse that makes the two velocities
// equal (stick), or, when that needs more than Coulomb friction allows, the normal impulse that
// stops the approach with friction at its limit (slip). Internal header of the core library.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::detail {

struct Exchange {
  Vec2 impulse{0, 0};         // on the material (N s/m); the block gets minus this
  Vec2 relative_after{0, 0};  // relative velocity after the exchange (m/s)
  bool stuck = false;
};

// u: material velocity minus the block's at the contact (m/s); n: unit normal out of the block;
// K: sum of both sides' inverse effective masses; target: the relative normal velocity to reach
// (0, or -gap/dt to close a gap exactly); mu: friction. Call only when u.n < target: the
// contact then pushes (the normal impulse is > 0) and never pulls.
inline Exchange exchange(const Mat2& K, const Vec2& u, const Vec2& n, Real target, Real mu) {
  Exchange e;
  const Vec2 t(-n.y(), n.x());
  // Stick (eq. 28 / 48 with matrices): u + K J = target n.
  const Vec2 j_stick = K.inverse() * (target * n - u);
  const Real jn = j_stick.dot(n), jt = j_stick.dot(t);
  if (jn > 0 && std::abs(jt) <= mu * jn) {
    e.impulse = j_stick;
    e.stuck = true;
  } else {
    // Slip (eq. 31 / 52): J = j (n + mu s t), j from the normal condition n.(u + K J) = target.
    const Vec2 dir = n + mu * (jt > 0 ? 1 : jt < 0 ? -1 : 0) * t;
    Real knn = n.dot(K * dir);
    Vec2 d = dir;
    if (!(knn > 0)) {  // friction coupling larger than the normal term: drop friction
      d = n;
      knn = n.dot(K * n);
    }
    e.impulse = (target - u.dot(n)) / knn * d;
  }
  e.relative_after = u + K * e.impulse;
  return e;
}

}  // namespace mpm_sdem::detail
