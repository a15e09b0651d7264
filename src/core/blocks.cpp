#include "mpm_sdem/core/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpm_sdem/core/block_checks.hpp"

#include "box2d_shapes.hpp"
#include "contact_impulse.hpp"

namespace mpm_sdem {

using detail::box2dPolygon;
using detail::box2dReach;
using detail::fromB2;
using detail::toB2;

std::vector<Vec2> placedCore(const BlockDef& d) {
  std::vector<Vec2> v;
  const Real c = std::cos(d.angle), s = std::sin(d.angle);
  for (const Vec2& p : d.core)
    v.push_back(d.position + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y()));
  return v;
}

Real roundedGap(const Vec2* a, int na, Real ra, const Vec2* b, int nb, Real rb) {
  Real gap = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < na; ++k) gap = std::fmin(gap, closestOnCore(b, nb, a[k]).distance);
  for (int k = 0; k < nb; ++k) gap = std::fmin(gap, closestOnCore(a, na, b[k]).distance);
  return gap - ra - rb;
}

struct Blocks::Box2D {
  explicit Box2D(const b2Vec2& g) : world(g) { world.SetContactListener(&rule); }
  detail::SmallerOfTwo rule;  // declared before the world, so destroyed after it
  b2World world;
  std::vector<b2Body*> bodies;
};

Blocks::Blocks(const std::vector<BlockDef>& defs, const BlockContactDef& contact,
               const Vec2& gravity, Real length_hint)
    : contact_(contact) {
  // Length scale: the median block size (square root of its area) becomes one Box2D unit; with
  // no block yet, the caller's typical length does.
  std::vector<Real> sizes;
  Real rounding = std::numeric_limits<Real>::infinity(), moving = 0;
  for (const BlockDef& d : defs) {
    checkDef(d);
    std::vector<Vec2> core = d.core;
    makeCounterClockwise(core);
    sizes.push_back(std::sqrt(spheropolygonMass(core, d.rounding, 1).area));
    rounding = std::fmin(rounding, d.rounding);
    if (d.type != BodyType::kStatic) moving = std::fmax(moving, sizes.back());
  }
  if (!sizes.empty()) {
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    scale_ = 1 / sizes[sizes.size() / 2];
  } else if (length_hint > 0) {
    scale_ = 1 / length_hint;
  }
  // Box2D's contacts rest up to half a slop off touching (box2dReach): a finer scale makes that
  // 0.5% of the smallest rounding, as far as Box2D's tuning allows (moving bodies up to 10
  // units; b2_maxTranslation, 2 units, caps a step's travel).
  if (contact.model == BlockContactModel::kBox2D && std::isfinite(rounding)) {
    const Real fine = 0.5 * b2_linearSlop / (0.005 * rounding);
    scale_ = std::fmax(scale_, moving > 0 ? std::fmin(fine, 10 / moving) : fine);
  }
  b2_ = std::make_unique<Box2D>(toB2(gravity, scale_));
  for (const BlockDef& d : defs) add(d);
}

void Blocks::checkDef(const BlockDef& d) const {
  const Problem p = blockProblem(d, contact_.model);
  if (!p.empty()) throw std::invalid_argument("block '" + d.name + "': " + p.text());
}

int Blocks::add(const BlockDef& def) {
  checkDef(def);
  BlockDef d = def;
  makeCounterClockwise(d.core);
  const MassProperties m = spheropolygonMass(d.core, d.rounding, d.density);
  // The Box2D outline first: it may refuse the block, before anything is created.
  const bool box2d = contact_.model == BlockContactModel::kBox2D;
  const std::vector<b2Vec2> outline =
      box2d && d.core.size() > 1 ? box2dPolygon(d, scale_) : std::vector<b2Vec2>();
  b2BodyDef bd;
  bd.type = d.type == BodyType::kStatic      ? b2_staticBody
            : d.type == BodyType::kKinematic ? b2_kinematicBody
                                             : b2_dynamicBody;
  bd.position = toB2(d.position, scale_);
  bd.angle = static_cast<float>(d.angle);
  bd.allowSleep = false;  // a sleeping body ignores the coupling forces
  bd.bullet = d.type == BodyType::kDynamic && box2d;
  b2Body* body = b2_->world.CreateBody(&bd);
  if (box2d) {
    b2FixtureDef fd;
    fd.friction = static_cast<float>(d.friction);
    fd.restitution = static_cast<float>(d.restitution);
    // Box2D bounces only above this approach speed (default 1 unit/s): keep it a physical
    // 1 cm/s at every length scale.
    fd.restitutionThreshold = static_cast<float>(0.01 * scale_);
    fd.density = 0;  // mass set below, from the rounded shape
    b2CircleShape circle;
    b2PolygonShape polygon;
    if (d.core.size() == 1) {
      // A circle has no skin: its radius reaches past the outline like a polygon's skin.
      circle.m_p = toB2(d.core[0], scale_);
      circle.m_radius = static_cast<float>((d.rounding + box2dReach(scale_)) * scale_);
      fd.shape = &circle;
    } else {
      polygon.Set(outline.data(), static_cast<int32>(outline.size()));
      fd.shape = &polygon;
    }
    body->CreateFixture(&fd);
  }
  if (d.type == BodyType::kDynamic) {
    // Box2D's polygon mass ignores the rounding: set the spheropolygon's own (inertia about
    // the body origin, in Box2D units).
    b2MassData md;
    md.mass = static_cast<float>(m.mass);
    md.center = toB2(m.centroid, scale_);
    md.I = static_cast<float>((m.inertia + m.mass * m.centroid.squaredNorm()) * scale_ * scale_);
    body->SetMassData(&md);
  }
  if (d.type != BodyType::kStatic) {
    body->SetLinearVelocity(toB2(d.velocity, scale_));
    body->SetAngularVelocity(static_cast<float>(d.angular_velocity));
  }
  b2_->bodies.push_back(body);
  const Real c = std::cos(d.angle), sn = std::sin(d.angle);
  const Vec2 centre = d.position + Vec2(c * m.centroid.x() - sn * m.centroid.y(),
                                        sn * m.centroid.x() + c * m.centroid.y());
  kinematic_.push_back({centre, d.angle, d.velocity, d.angular_velocity});
  defs_.push_back(std::move(d));
  mass_.push_back(m);
  zeta_.push_back(restitutionDampingRatio(def.restitution));
  max_zeta_ = std::max(max_zeta_, zeta_.back());
  state_.emplace_back();
  world_vertices_.resize(defs_.size() * kMaxBlockVertices);
  force_.emplace_back(0, 0);
  block_force_.emplace_back(0, 0);
  torque_.push_back(0);
  coupling_.emplace_back();
  refresh();
  return count() - 1;
}

void Blocks::remove(int i) {
  b2_->world.DestroyBody(b2_->bodies[i]);
  b2_->bodies.erase(b2_->bodies.begin() + i);
  defs_.erase(defs_.begin() + i);
  mass_.erase(mass_.begin() + i);
  zeta_.erase(zeta_.begin() + i);
  max_zeta_ = zeta_.empty() ? 0 : *std::max_element(zeta_.begin(), zeta_.end());
  state_.erase(state_.begin() + i);
  kinematic_.erase(kinematic_.begin() + i);
  world_vertices_.resize(defs_.size() * kMaxBlockVertices);
  force_.erase(force_.begin() + i);
  block_force_.erase(block_force_.begin() + i);
  torque_.erase(torque_.begin() + i);
  coupling_.erase(coupling_.begin() + i);
  // The block-block spring histories are keyed by index: the indices after i have shifted.
  history_.clear();
  refresh();
}

int Blocks::find(const std::string& name) const {
  for (int i = 0; i < count(); ++i)
    if (defs_[i].name == name) return i;
  return -1;
}

Vec2 Blocks::origin(int i) const {
  return fromB2(b2_->bodies[i]->GetPosition(), scale_);
}

void Blocks::setPose(int i, const Vec2& origin, Real angle) {
  b2_->bodies[i]->SetTransform(toB2(origin, scale_), static_cast<float>(angle));
  refresh();
  const Vec2& g = mass_[i].centroid;
  const Real c = std::cos(angle), sn = std::sin(angle);
  kinematic_[i].centre = origin + Vec2(c * g.x() - sn * g.y(), sn * g.x() + c * g.y());
  kinematic_[i].angle = angle;
}

void Blocks::setVelocity(int i, const Vec2& origin_velocity, Real angular_velocity) {
  // Box2D's linear velocity is that of the centre of mass.
  const Vec2 r = state_[i].position - origin(i);
  const Vec2 v = origin_velocity + angular_velocity * Vec2(-r.y(), r.x());
  b2_->bodies[i]->SetLinearVelocity(toB2(v, scale_));
  b2_->bodies[i]->SetAngularVelocity(static_cast<float>(angular_velocity));
  kinematic_[i].velocity = v;
  kinematic_[i].angular_velocity = angular_velocity;
  refresh();
}

Blocks::~Blocks() = default;

void Blocks::refresh() {
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    const b2Body* body = b2_->bodies[i];
    BlockState& s = state_[i];
    s.angle = body->GetAngle();
    s.velocity = fromB2(body->GetLinearVelocity(), scale_);
    s.angular_velocity = body->GetAngularVelocity();
    const Vec2 origin = fromB2(body->GetPosition(), scale_);
    const Real c = std::cos(s.angle), sn = std::sin(s.angle);
    auto toWorld = [&](const Vec2& v) {
      return Vec2(origin.x() + c * v.x() - sn * v.y(), origin.y() + sn * v.x() + c * v.y());
    };
    s.position = toWorld(mass_[i].centroid);
    for (std::size_t k = 0; k < defs_[i].core.size(); ++k) {
      world_vertices_[i * kMaxBlockVertices + k] = toWorld(defs_[i].core[k]);
    }
  }
}

Vec2 Blocks::velocityAt(int i, const Vec2& p) const {
  const BlockState& s = state_[i];
  const Vec2 r = p - s.position;
  return s.velocity + s.angular_velocity * Vec2(-r.y(), r.x());
}

Real Blocks::lightestDynamicMass() const {
  Real m = std::numeric_limits<Real>::infinity();
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    if (defs_[i].type == BodyType::kDynamic) m = std::fmin(m, mass_[i].mass);
  }
  return m;
}

void Blocks::addForce(int i, const Vec2& f, const Vec2& point) {
  force_[i] += f;
  torque_[i] += cross(point - state_[i].position, f);
}

void Blocks::addMaterialForce(int i, const Vec2& f, const Vec2& point) {
  addForce(i, f, point);
  Coupling& c = coupling_[i];
  c.force += f;
  c.torque += cross(point - state_[i].position, f);
  ++c.contacts;
}

void Blocks::clearCoupling() {
  for (Coupling& c : coupling_) c = Coupling();
}

void Blocks::penaltyContacts(Real dt) {
  next_history_.clear();
  const int n = count();
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if (defs_[i].type != BodyType::kDynamic && defs_[j].type != BodyType::kDynamic) continue;
      // Seed 000 eq. 38 and 41: the overlapping vertex-edge pairs, vertices of i against the
      // edges of j, then vertices of j against i.
      springs_.clear();
      for (int side = 0; side < 2; ++side) {
        const int a = side == 0 ? i : j, b = side == 0 ? j : i;
        const int nb = vertexCount(b);
        // A disk has no edges: its centre meets the other's edges in the other pass.
        if (nb == 1 && (vertexCount(a) > 1 || side == 1)) continue;
        const Real reach = defs_[a].rounding + defs_[b].rounding;
        for (int k = 0; k < vertexCount(a); ++k) {
          const Vec2 X = vertices(a)[k];
          const CoreDistance c = closestOnCore(vertices(b), nb, X);
          const Real xi = reach - c.distance;  // eq. 38
          if (xi <= 0) continue;
          // Eq. 41: the middle of the overlap along the normal (which points from b to a).
          springs_.push_back({X - (defs_[a].rounding - xi / 2) * c.normal, c.normal, xi, k, side});
        }
      }
      if (springs_.empty()) continue;
      // Two convex outlines touch in one place: the pair's springs are one contact (a face
      // gives two or four, eq. 39). Its dashpot is sized for the restitution on the pair's
      // effective normal mass at the contact's centre (1/m = sum over the dynamic sides of
      // 1/M + (r x n)^2 / I), so that the springs together, n k_n on m, rebound with e; each
      // takes an equal share. Normals are counted from j towards i.
      Vec2 centre(0, 0), normal(0, 0);
      for (const Spring& s : springs_) {
        centre += s.point / static_cast<Real>(springs_.size());
        normal += s.side == 0 ? s.normal : Vec2(-s.normal);
      }
      normal = normal.norm() > 0 ? Vec2(normal.normalized()) : springs_[0].normal;
      const Real inverse_mass = normal.dot((detail::blockInverseMass(*this, i, centre) +
                                            detail::blockInverseMass(*this, j, centre)) *
                                           normal);
      const Real count = static_cast<Real>(springs_.size());
      // The less elastic side sets the damping (the smaller restitution, the larger ratio).
      const Real gamma = 2 * std::max(zeta_[i], zeta_[j]) *
                         std::sqrt(count * contact_.normal_stiffness / inverse_mass) / count;
      const Real mu = std::min(defs_[i].friction, defs_[j].friction);
      // Adhesion (seed 003 sec. 4.3): c over the length the outlines touch, the spread of the
      // springs' points across the normal (a face's length; zero on a vertex or a disk), shared
      // by the springs and pulling. Friction stays capped by what the springs push, which
      // includes the adhesion they balance.
      Real pull = 0;
      if (const Real c = std::max(defs_[i].adhesion, defs_[j].adhesion); c > 0) {
        const Vec2 t(-normal.y(), normal.x());
        Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
        for (const Spring& s : springs_) {
          lo = std::fmin(lo, s.point.dot(t));
          hi = std::fmax(hi, s.point.dot(t));
        }
        pull = c * (hi - lo) / count;
      }
      for (const Spring& s : springs_) {
        const int a = s.side == 0 ? i : j, b = s.side == 0 ? j : i;
        const Vec2 v = velocityAt(a, s.point) - velocityAt(b, s.point);
        const Real vn = v.dot(s.normal);
        const Real push = std::fmax(contact_.normal_stiffness * s.xi - gamma * vn, Real(0));
        const unsigned long long key = (static_cast<unsigned long long>(i) << 40) |
                                       (static_cast<unsigned long long>(j) << 16) |
                                       (static_cast<unsigned long long>(s.vertex) << 1) | s.side;
        Vec2 delta(0, 0);
        const auto it =
            std::lower_bound(history_.begin(), history_.end(), std::make_pair(key, Vec2(0, 0)),
                             [](const auto& x, const auto& y) { return x.first < y.first; });
        if (it != history_.end() && it->first == key) delta = it->second;
        // Eq. 43: tangential spring on the accumulated sliding, capped by Coulomb.
        delta += (v - vn * s.normal) * dt;
        delta -= delta.dot(s.normal) * s.normal;
        Vec2 ft = -contact_.tangential_stiffness * delta;
        if (ft.norm() > mu * push) {
          ft *= mu * push / ft.norm();
          delta = -ft / contact_.tangential_stiffness;
        }
        next_history_.emplace_back(key, delta);
        const Vec2 f = (push - pull) * s.normal + ft;
        addForce(a, f, s.point);
        addForce(b, -f, s.point);
      }
    }
  }
  std::sort(next_history_.begin(), next_history_.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  history_.swap(next_history_);
}

Real Blocks::stableStep(Real kappa2) const {
  if (contact_.model != BlockContactModel::kPenalty || count() < 2)
    return std::numeric_limits<Real>::infinity();  // no block-block spring can form
  // The fastest motion a contact's springs drive. For kinetic energy E, a block's normal
  // velocity at a contact point, v_n + w (r x n), squared is at most 2 E (1/M + (r x n)^2 / I)
  // <= 2 E / m_c (Cauchy-Schwarz), |r x n| being at most the distance to the farthest core vertex
  // (the contact point lies off the core only along n). So n springs between blocks a and b
  // vibrate at w^2 <= n k_n (1/m_c,a + 1/m_c,b). Their dashpots are in proportion to the
  // springs (penaltyContacts: c / k_n = 2 zeta / w_c, w_c the contact's own frequency, at least
  // that of the blocks translating), so a mode w has the damping ratio zeta w / w_c, at most
  // zeta sqrt(rho) with rho = M / m_c. The bound: four springs (a face, eq. 39) between two of
  // the blocks with the smallest m_c, with the largest rho and damping ratio.
  Real m_c = std::numeric_limits<Real>::infinity(), rho = 1;
  for (int b = 0; b < count(); ++b) {
    if (defs_[b].type != BodyType::kDynamic) continue;
    const MassProperties& m = mass_[b];
    Real r2 = 0;
    for (const Vec2& v : defs_[b].core) r2 = std::fmax(r2, (v - m.centroid).squaredNorm());
    m_c = std::fmin(m_c, 1 / (1 / m.mass + r2 / m.inertia));
    rho = std::fmax(rho, 1 + m.mass * r2 / m.inertia);
  }
  if (!std::isfinite(m_c)) return std::numeric_limits<Real>::infinity();
  return contactTimeStep(0.5 * m_c, contact_.normal_stiffness, max_zeta_ * std::sqrt(rho), 4,
                         kappa2);
}

int Blocks::step(Real dt, Real max_substep) {
  if (defs_.empty()) return 0;
  // The blocks' own springs are stiffer than the material's: the blocks take several steps for
  // one MPM step (multi-rate explicit integration), each within the block-block bound.
  const int substeps = dt > max_substep ? static_cast<int>(std::ceil(dt / max_substep)) : 1;
  const Real h = dt / substeps;
  held_force_ = force_;
  held_torque_ = torque_;
  for (Vec2& f : block_force_) f.setZero();
  for (int s = 0; s < substeps; ++s) {
    for (std::size_t i = 0; i < defs_.size(); ++i) {
      force_[i] = held_force_[i];
      torque_[i] = held_torque_[i];
    }
    if (contact_.model == BlockContactModel::kPenalty) {
      penaltyContacts(h);
      for (std::size_t i = 0; i < defs_.size(); ++i)
        block_force_[i] += (force_[i] - held_force_[i]) / substeps;
    }
    for (std::size_t i = 0; i < defs_.size(); ++i) {
      b2Body* body = b2_->bodies[i];
      if (defs_[i].type == BodyType::kDynamic) {
        // F (N/m) and tau (N m/m) into Box2D units: lengths scale by s, masses do not.
        body->ApplyForceToCenter(toB2(force_[i], scale_), true);
        body->ApplyTorque(static_cast<float>(torque_[i] * scale_ * scale_), true);
      }
    }
    b2_->world.Step(static_cast<float>(h), 8, 3);
    // A kinematic block moves with its twist exactly: Box2D's single-precision sum of small
    // steps drifts (93 um over 10,000 steps, RuntimeBlocks.KinematicBlockFollowsItsTwist), so
    // its pose is summed here in double and set.
    for (std::size_t i = 0; i < defs_.size(); ++i) {
      if (defs_[i].type != BodyType::kKinematic) continue;
      Kinematic& k = kinematic_[i];
      k.centre += h * k.velocity;
      k.angle += h * k.angular_velocity;
      const Vec2& g = mass_[i].centroid;
      const Real c = std::cos(k.angle), sn = std::sin(k.angle);
      const Vec2 origin = k.centre - Vec2(c * g.x() - sn * g.y(), sn * g.x() + c * g.y());
      b2_->bodies[i]->SetTransform(toB2(origin, scale_), static_cast<float>(k.angle));
    }
    refresh();
  }
  for (std::size_t i = 0; i < defs_.size(); ++i) {
    force_[i].setZero();
    torque_[i] = 0;
  }
  return substeps;
}

}  // namespace mpm_sdem
