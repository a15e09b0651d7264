#include "mpm_sdem/core/rigid/block_checks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace mpm_sdem {

namespace {

std::string num(Real v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

Problem rangeOf(const char* key, Real v, const limits::Range& r) {
  const Problem p = limits::rangeProblem(v, r);
  return p.empty() ? p : p.under(key);
}

Problem outlineProblem(const BlockDef& d) {
  if (!d.discs.empty()) {
    if (!d.core.empty())
      return {"discs", "a cluster of discs has no core polygon: give discs or vertices, not both"};
    if (Problem p = discsProblem(d.discs); !p.empty()) return p.under("discs");
    for (const Disc& disc : d.discs) {
      const Real r = std::hypot(disc.centre.x(), disc.centre.y());
      if (r > limits::kLength.max)
        return {"discs", "a disc centre lies " + num(r) + " m from the block origin; at most " +
                             num(limits::kLength.max) + " m"};
      if (Problem p = rangeOf("discs", disc.radius, limits::kLength); !p.empty()) return p;
    }
    return {};
  }
  for (const Vec2& v : d.core) {
    const Real r = std::hypot(v.x(), v.y());  // no overflow: 1e300 stays 1e300
    if (v.allFinite() && r > limits::kLength.max)
      return {"vertices", "a core vertex lies " + num(r) + " m from the block origin; at most " +
                              num(limits::kLength.max) + " m"};
  }
  if (Problem p = coreProblem(d.core); !p.empty()) return p.under("vertices");
  return rangeOf("rounding", d.rounding, limits::kLength);
}

}  // namespace

Real blockReach(const BlockDef& d) {
  Real r = 0;
  for (const Spheropolygon& part : blockParts(d))
    for (const Vec2& v : part.core) r = std::fmax(r, v.norm() + part.rounding);
  return r;
}

Problem twistProblem(const BlockDef& d, const Vec2& v, Real w) {
  if (!v.allFinite() || !std::isfinite(w))
    return {"velocity", "must be finite numbers (no NaN or infinity)"};
  if (d.type == BodyType::kStatic && (v.squaredNorm() > 0 || w != 0))
    return {"velocity", "a static block does not move: make it kinematic to give it a velocity"};
  const Real speed = v.norm() + std::abs(w) * blockReach(d);
  if (speed > limits::kSpeed.max)
    return {"velocity",
            "its fastest point would move at " + num(speed) + " m/s (|v| + |w| * reach " +
                num(blockReach(d)) + " m); at most " + num(limits::kSpeed.max) +
                " m/s, beyond which the material's stable step collapses (seed 000 eq. 51)"};
  return {};
}

Problem blockProblem(const BlockDef& d, BlockContactModel model) {
  if (Problem p = limits::nameProblem(d.name); !p.empty()) return p.under("name");
  if (Problem p = outlineProblem(d); !p.empty()) return p;
  if (!d.position.allFinite() || !std::isfinite(d.angle))
    return {"position", "must be finite numbers (no NaN or infinity)"};
  for (int a = 0; a < 2; ++a) {
    if (Problem p = rangeOf("position", d.position[a], limits::kCoordinate); !p.empty()) return p;
  }
  // In radians here, whatever unit the caller's key has (the scene's is degrees).
  if (!(std::abs(d.angle) <= limits::kAngle.max))
    return {"angle", "must lie within +-" + num(limits::kAngle.max) + " rad (" +
                         num(limits::kAngle.max * 180 / M_PI) +
                         " deg; Box2D holds it in single precision), got " + num(d.angle) + " rad"};
  // Static and kinematic blocks have no mass to speak of; a density given must still be sane.
  if (d.type == BodyType::kDynamic || d.density != 0) {
    if (Problem p = rangeOf("density", d.density, limits::kDensity); !p.empty()) return p;
  }
  if (Problem p = rangeOf("friction", d.friction, limits::kFriction); !p.empty()) return p;
  if (Problem p = rangeOf("restitution", d.restitution, limits::kRestitution); !p.empty()) return p;
  if (Problem p = rangeOf("adhesion", d.adhesion, limits::kStrength); !p.empty()) return p;
  if (d.adhesion > 0 && model != BlockContactModel::kPenalty)
    return {"adhesion",
            "needs block_contact.model: penalty (Box2D's contact solver has no adhesion); remove "
            "it or switch the model"};
  if (d.drive.any()) {
    if (d.type != BodyType::kDynamic)
      return {"drive",
              "only a dynamic block has a drive (a kinematic one moves at its velocity already)"};
    if (Problem p = twistProblem(d, d.drive.velocity, d.drive.angular_velocity); !p.empty())
      return {"drive", p.message};
  }
  Problem twist = twistProblem(d, d.velocity, d.angular_velocity);
  if (!twist.empty() && twist.key == "velocity" && d.velocity.squaredNorm() == 0)
    twist.key = "angular_velocity";
  return twist;
}

Real loadAcceleration(const BlockDef& d, const Vec2& force, const Vec2& point, Real torque) {
  if (d.type != BodyType::kDynamic) return std::numeric_limits<Real>::infinity();
  const MassProperties m = blockMass(d);
  Real reach = 0;  // R: the outline's farthest point from the centre of mass
  for (const Spheropolygon& part : blockParts(d))
    for (const Vec2& v : part.core)
      reach = std::fmax(reach, (v - m.centroid).norm() + part.rounding);
  const Real f = force.norm();
  const Real spin = ((point - m.centroid).norm() * f + std::abs(torque)) / m.inertia;
  return f / m.mass + spin * reach;
}

Problem heldLoadsProblem(const std::vector<HeldLoad>& loads) {
  Real acceleration = 0, speed = 0;
  for (const HeldLoad& l : loads) {
    acceleration += l.acceleration;
    if (std::isfinite(l.duration)) speed += l.acceleration * l.duration;
  }
  if (!(acceleration <= limits::kLoadAcceleration.max))
    return {"wrench", "the loads held on the block would accelerate its fastest point at up to " +
                          num(acceleration) + " m/s^2; at most " +
                          num(limits::kLoadAcceleration.max) +
                          " m/s^2 (the strongest gravity accepted): lower the force or torque"};
  if (!(speed <= limits::kSpeed.max))
    return {"duration", "the loads held on the block could add " + num(speed) +
                            " m/s to its fastest point before they end; at most " +
                            num(limits::kSpeed.max) +
                            " m/s (the speed cap of every block): lower or shorten them"};
  return {};
}

bool keepInsideDomain(const Box& b, Real reach, Real h, const Vec2& lo, const Vec2& hi, Vec2& v,
                      Real& w) {
  bool cut = false;
  const Real sweep = std::abs(w) * h * reach;
  if (sweep > 0 && ((b.min - Vec2::Constant(sweep)).array() < lo.array() ||
                    (b.max + Vec2::Constant(sweep)).array() > hi.array())
                       .any()) {
    w = 0;
    cut = true;
  }
  for (int a = 0; a < 2; ++a) {
    // The largest step towards each side that keeps the box inside (0 once it is outside).
    const Real up = std::fmax(hi[a] - b.max[a], Real(0)) / h;
    const Real down = std::fmin(lo[a] - b.min[a], Real(0)) / h;
    if (v[a] > up || v[a] < down) {
      v[a] = std::clamp(v[a], down, up);
      cut = true;
    }
  }
  return cut;
}

Problem domainProblem(const BlockDef& d, const Vec2& lo, const Vec2& hi) {
  Vec2 bmin = Vec2::Constant(INFINITY), bmax = Vec2::Constant(-INFINITY);
  for (const Spheropolygon& part : placedParts(d)) {
    for (const Vec2& v : part.core) {
      bmin = bmin.cwiseMin(v - Vec2::Constant(part.rounding));
      bmax = bmax.cwiseMax(v + Vec2::Constant(part.rounding));
    }
  }
  const std::string box =
      "[" + num(lo.x()) + ", " + num(hi.x()) + "] x [" + num(lo.y()) + ", " + num(hi.y()) + "] m";
  if (d.type == BodyType::kStatic) {
    if ((bmax.array() < lo.array()).any() || (bmin.array() > hi.array()).any())
      return {"position", "the static block does not touch the domain " + box};
    return {};
  }
  if ((bmin.array() < lo.array()).any() || (bmax.array() > hi.array()).any())
    return {"position", "the block reaches outside the domain " + box +
                            "; only a static block (a boundary) may"};
  return {};
}

Real startingOverlap(const std::vector<Spheropolygon>& a, const std::vector<Spheropolygon>& b) {
  Real depth = 0;
  for (const Spheropolygon& p : a) {
    for (const Spheropolygon& q : b) {
      const Real gap = roundedGap(p.core.data(), static_cast<int>(p.core.size()), p.rounding,
                                  q.core.data(), static_cast<int>(q.core.size()), q.rounding);
      if (gap < -0.01 * std::fmin(p.rounding, q.rounding)) depth = std::fmax(depth, -gap);
    }
  }
  return depth;
}

bool insideOutline(const std::vector<Spheropolygon>& parts, const Vec2& p) {
  for (const Spheropolygon& part : parts)
    if (closestOnCore(part.core.data(), static_cast<int>(part.core.size()), p).distance <
        part.rounding)
      return true;
  return false;
}

}  // namespace mpm_sdem
