#include "rigid/box2d_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rigid/box2d_shapes.hpp"
#include "rigid/penalty_contacts.hpp"

namespace mpm_sdem {

namespace detail {

Real box2dLengthScale(const std::vector<BlockDef>& defs, BlockContactModel model,
                      Real length_hint) {
  // The median block size (square root of its area) becomes one Box2D unit; with no block yet,
  // the caller's typical length does.
  std::vector<Real> sizes;
  Real rounding = std::numeric_limits<Real>::infinity(), moving = 0;
  for (const BlockDef& d : defs) {
    sizes.push_back(std::sqrt(blockMass(d).area));
    for (const Spheropolygon& part : blockParts(d)) rounding = std::fmin(rounding, part.rounding);
    if (d.type != BodyType::kStatic) moving = std::fmax(moving, sizes.back());
  }
  Real scale = 1;
  if (!sizes.empty()) {
    std::nth_element(sizes.begin(), sizes.begin() + sizes.size() / 2, sizes.end());
    scale = 1 / sizes[sizes.size() / 2];
  } else if (length_hint > 0) {
    scale = 1 / length_hint;
  }
  // Box2D's contacts rest up to half a slop off touching (box2dReach): a finer scale makes that
  // 0.5% of the smallest rounding, as far as Box2D's tuning allows (moving bodies up to 10
  // units; b2_maxTranslation, 2 units, caps a step's travel).
  if (model == BlockContactModel::kBox2D && std::isfinite(rounding)) {
    const Real fine = 0.5 * b2_linearSlop / (0.005 * rounding);
    scale = std::fmax(scale, moving > 0 ? std::fmin(fine, 10 / moving) : fine);
  }
  return scale;
}

struct Box2DBodies::World {
  explicit World(const b2Vec2& g) : world(g) { world.SetContactListener(&rule); }
  SmallerOfTwo rule;  // declared before the world, so destroyed after it
  b2World world;
  // Null for a static block without fixtures (the penalty model): it never moves, so it stays
  // out of Box2D, whose every step walks all its bodies (a thousand static obstacles cost a
  // third of the step); its pose is kept in pose[i] as Box2D would hold it (Box2D units, float).
  std::vector<b2Body*> bodies;
  std::vector<Raw> pose;
};

Box2DBodies::Box2DBodies(const Vec2& gravity, Real scale, BlockContactModel model)
    : w_(std::make_unique<World>(toB2(gravity, scale))), scale_(scale), model_(model) {}

void Box2DBodies::setGravity(const Vec2& gravity) {
  w_->world.SetGravity(toB2(gravity, scale_));
}

Box2DBodies::~Box2DBodies() = default;

void Box2DBodies::add(const BlockDef& d, const std::vector<Spheropolygon>& parts,
                      const MassProperties& m, const Raw* at) {
  // The Box2D outlines first: they may refuse the block, before anything is created.
  // The Box2D body's origin is the centre of mass, so its whole state is the centre, angle and
  // twist that Box2D integrates (no origin derived from them in single precision): a checkpoint
  // restores it exactly (setState). The parts move into the centroid's frame.
  const bool box2d = model_ == BlockContactModel::kBox2D;
  std::vector<Spheropolygon> local = parts;
  for (Spheropolygon& part : local)
    for (Vec2& v : part.core) v -= m.centroid;
  std::vector<std::vector<b2Vec2>> outlines(parts.size());
  for (std::size_t k = 0; k < parts.size(); ++k)
    if (box2d && local[k].core.size() > 1) outlines[k] = box2dPolygon(local[k], d.name, scale_);
  b2BodyDef bd;
  bd.type = d.type == BodyType::kStatic      ? b2_staticBody
            : d.type == BodyType::kKinematic ? b2_kinematicBody
                                             : b2_dynamicBody;
  bd.position = at ? b2Vec2(at->x, at->y) : toB2(d.position + rotated(d.angle, m.centroid), scale_);
  bd.angle = at ? at->angle : static_cast<float>(d.angle);
  if (d.type == BodyType::kStatic && !box2d) {
    w_->bodies.push_back(nullptr);
    w_->pose.push_back({bd.position.x, bd.position.y, bd.angle, 0, 0, 0});
    return;
  }
  bd.allowSleep = false;  // a sleeping body ignores the coupling forces
  bd.bullet = d.type == BodyType::kDynamic && box2d;
  b2Body* body = w_->world.CreateBody(&bd);
  for (std::size_t k = 0; box2d && k < parts.size(); ++k) {
    b2FixtureDef fd;
    fd.friction = static_cast<float>(d.friction);
    fd.restitution = static_cast<float>(d.restitution);
    // Box2D bounces only above this approach speed (default 1 unit/s): keep it a physical
    // 1 cm/s at every length scale.
    fd.restitutionThreshold = static_cast<float>(0.01 * scale_);
    fd.density = 0;  // mass set below, from the rounded outline
    b2CircleShape circle;
    b2PolygonShape polygon;
    if (local[k].core.size() == 1) {
      // A circle has no skin: its radius reaches past the outline like a polygon's skin.
      circle.m_p = toB2(local[k].core[0], scale_);
      circle.m_radius = static_cast<float>((local[k].rounding + box2dReach(scale_)) * scale_);
      fd.shape = &circle;
    } else {
      polygon.Set(outlines[k].data(), static_cast<int32>(outlines[k].size()));
      fd.shape = &polygon;
    }
    body->CreateFixture(&fd);
  }
  if (d.type == BodyType::kDynamic) {
    // Box2D's own mass ignores the rounding and counts overlapping discs twice: set the
    // outline's (inertia about the body origin, the centroid, in Box2D units).
    b2MassData md;
    md.mass = static_cast<float>(m.mass);
    md.center = b2Vec2(0, 0);
    md.I = static_cast<float>(m.inertia * scale_ * scale_);
    body->SetMassData(&md);
  }
  if (d.type != BodyType::kStatic) {
    body->SetLinearVelocity(at ? b2Vec2(at->vx, at->vy) : toB2(d.velocity, scale_));
    body->SetAngularVelocity(at ? at->angular_velocity : static_cast<float>(d.angular_velocity));
  }
  // The body's place in the list, for reportContacts.
  body->GetUserData().pointer = w_->bodies.size();
  w_->bodies.push_back(body);
  w_->pose.emplace_back();
}

void Box2DBodies::remove(int i) {
  if (w_->bodies[i]) w_->world.DestroyBody(w_->bodies[i]);
  w_->bodies.erase(w_->bodies.begin() + i);
  w_->pose.erase(w_->pose.begin() + i);
  for (std::size_t k = i; k < w_->bodies.size(); ++k)
    if (w_->bodies[k]) w_->bodies[k]->GetUserData().pointer = k;
}

Box2DBodies::Raw Box2DBodies::raw(int i) const {
  const b2Body* b = w_->bodies[i];
  if (!b) return w_->pose[i];
  return {b->GetPosition().x,       b->GetPosition().y,       b->GetAngle(),
          b->GetLinearVelocity().x, b->GetLinearVelocity().y, b->GetAngularVelocity()};
}

Vec2 Box2DBodies::centre(int i) const {
  const b2Body* b = w_->bodies[i];
  return fromB2(b ? b->GetPosition() : b2Vec2(w_->pose[i].x, w_->pose[i].y), scale_);
}
Real Box2DBodies::angle(int i) const {
  const b2Body* b = w_->bodies[i];
  return b ? b->GetAngle() : w_->pose[i].angle;
}
Vec2 Box2DBodies::velocity(int i) const {
  const b2Body* b = w_->bodies[i];
  return b ? fromB2(b->GetLinearVelocity(), scale_) : Vec2(0, 0);
}
Real Box2DBodies::angularVelocity(int i) const {
  const b2Body* b = w_->bodies[i];
  return b ? b->GetAngularVelocity() : 0;
}

void Box2DBodies::setTransform(int i, const Vec2& centre, Real angle) {
  const b2Vec2 p = toB2(centre, scale_);
  if (!w_->bodies[i]) {
    w_->pose[i] = {p.x, p.y, static_cast<float>(angle), 0, 0, 0};
    return;
  }
  w_->bodies[i]->SetTransform(p, static_cast<float>(angle));
}

void Box2DBodies::setVelocity(int i, const Vec2& v, Real w) {
  if (!w_->bodies[i]) return;  // static: Box2D would ignore it too
  w_->bodies[i]->SetLinearVelocity(toB2(v, scale_));
  w_->bodies[i]->SetAngularVelocity(static_cast<float>(w));
}

void Box2DBodies::applyForce(int i, const Vec2& f, Real torque) {
  // F (N/m) and tau (N m/m) into Box2D units: lengths scale by s, masses do not.
  w_->bodies[i]->ApplyForceToCenter(toB2(f, scale_), true);
  w_->bodies[i]->ApplyTorque(static_cast<float>(torque * scale_ * scale_), true);
}

void Box2DBodies::step(Real h) {
  w_->world.Step(static_cast<float>(h), 8, 3);
}

void Box2DBodies::reportContacts(Real h, Blocks& blocks) const {
  for (b2Contact* c = w_->world.GetContactList(); c; c = c->GetNext()) {
    if (!c->IsTouching() || !c->IsEnabled()) continue;
    const b2Manifold* m = c->GetManifold();
    b2WorldManifold wm;
    c->GetWorldManifold(&wm);
    const int a = static_cast<int>(c->GetFixtureA()->GetBody()->GetUserData().pointer);
    const int b = static_cast<int>(c->GetFixtureB()->GetBody()->GetUserData().pointer);
    // The solver's impulse on body B at each point (b2ContactSolver: P = normal impulse along
    // the manifold normal, A to B, plus tangent impulse along cross(normal, 1)); B2D impulses
    // are kg Box2D-units/s, so SI divides by the scale, and the step's mean force by h.
    const Vec2 n(wm.normal.x, wm.normal.y), t(wm.normal.y, -wm.normal.x);
    for (int k = 0; k < m->pointCount; ++k) {
      const b2ManifoldPoint& p = m->points[k];
      const Vec2 on_b = (p.normalImpulse * n + p.tangentImpulse * t) / (scale_ * h);
      blocks.recordContactForce(a, b, -on_b, fromB2(wm.points[k], scale_));
    }
  }
}

}  // namespace detail

Vec2 Blocks::origin(int i) const {
  const BlockState& s = bodies_[i].state;
  return s.position - rotated(s.angle, bodies_[i].mass.centroid);
}

void Blocks::setPose(BlockId id, const Vec2& origin, Real angle) {
  const int i = checkedIndex(id);
  Body& b = bodies_[i];
  b.kinematic_centre = origin + rotated(angle, b.mass.centroid);
  b.kinematic_angle = angle;
  b2_->setTransform(i, b.kinematic_centre, angle);
  ++layout_version_;
  refresh(i);
}

Vec2 Blocks::originVelocity(int i) const {
  const BlockState& s = bodies_[i].state;
  const Vec2 r = origin(i) - s.position;
  return s.velocity + s.angular_velocity * Vec2(-r.y(), r.x());
}

void Blocks::setVelocity(BlockId id, const Vec2& origin_velocity, Real angular_velocity) {
  const int i = checkedIndex(id);
  // Box2D's linear velocity is that of the centre of mass.
  const Vec2 r = bodies_[i].state.position - origin(i);
  const Vec2 v = origin_velocity + angular_velocity * Vec2(-r.y(), r.x());
  b2_->setVelocity(i, v, angular_velocity);
  bodies_[i].kinematic_velocity = v;
  bodies_[i].kinematic_angular_velocity = angular_velocity;
  refresh(i);
}

void Blocks::holdDrives() {
  for (const int k : moving_) {
    const BlockDrive& d = bodies_[k].drive;
    if (bodies_[k].type != BodyType::kDynamic || !d.any()) continue;
    Vec2 v = b2_->velocity(k);
    Real w = b2_->angularVelocity(k);
    if (d.hold_vx) v.x() = d.velocity.x();
    if (d.hold_vy) v.y() = d.velocity.y();
    if (d.hold_angular) w = d.angular_velocity;
    b2_->setVelocity(k, v, w);
  }
}

void Blocks::refresh() {
  for (int i = 0; i < count(); ++i) refresh(i);
}

void Blocks::refresh(int i) {
  Body& b = bodies_[i];
  BlockState& s = b.state;
  s.angle = b2_->angle(i);
  s.velocity = b2_->velocity(i);
  s.angular_velocity = b2_->angularVelocity(i);
  s.position = b2_->centre(i);
  const Real c = std::cos(s.angle), sn = std::sin(s.angle);
  const Vec2 origin = s.position - Vec2(c * b.mass.centroid.x() - sn * b.mass.centroid.y(),
                                        sn * b.mass.centroid.x() + c * b.mass.centroid.y());
  auto toWorld = [&](const Vec2& v) {
    return Vec2(origin.x() + c * v.x() - sn * v.y(), origin.y() + sn * v.x() + c * v.y());
  };
  for (int k = 0; k < b.shape_count; ++k) {
    const Shape& shape = shapes_[b.first_shape + k];
    const std::vector<Vec2>& core = parts_[i][k].core;
    for (int v = 0; v < shape.vertex_count; ++v)
      world_vertices_[shape.first_vertex + v] = toWorld(core[v]);
  }
}

int Blocks::step(Real dt, Real max_substep) {
  for (Load& c : block_contact_) c = Load();
  return advance(dt, max_substep, true, 1);
}

int Blocks::substep(Real h, Real max_substep, Real share) {
  return advance(h, max_substep, false, share);  // beginCoupling cleared the records
}

int Blocks::advance(Real dt, Real max_substep, bool ends_step, Real share) {
  if (bodies_.empty()) return 0;
  // The blocks' own springs are stiffer than the material's: the blocks take several steps for
  // one MPM step (multi-rate explicit integration), each within the block-block bound.
  const int substeps = dt > max_substep ? static_cast<int>(std::ceil(dt / max_substep)) : 1;
  const Real h = dt / substeps;
  // A static block takes forces (recorded in block_contact_ and coupling_) but never moves: only
  // the moving blocks' are held and applied.
  for (const int i : moving_) {
    Body& b = bodies_[i];
    b.held_force = b.force + b.load_force;
    b.held_torque = b.torque + b.load_torque;
  }
  substep_share_ = share / substeps;
  for (int s = 0; s < substeps; ++s) {
    for (const int i : moving_) {
      Body& b = bodies_[i];
      b.force = b.held_force;
      b.torque = b.held_torque;
    }
    for (Load& c : block_contact_) c.contacts = 0;  // the last substep's count
    if (contact_.model == BlockContactModel::kPenalty) penalty_->apply(*this, h);
    for (const int i : moving_) {
      Body& b = bodies_[i];
      if (b.type != BodyType::kDynamic) continue;
      // A held component moves at its value: the forces along it do nothing.
      if (b.drive.hold_vx) b.force.x() = 0;
      if (b.drive.hold_vy) b.force.y() = 0;
      if (b.drive.hold_angular) b.torque = 0;
      b2_->applyForce(i, b.force, b.torque);
    }
    holdDrives();
    b2_->step(h);
    holdDrives();  // Box2D's own contacts (box2d model) and gravity may have changed them
    // Before refresh(): Box2D's contact points were found at the poses the step started from.
    if (contact_.model == BlockContactModel::kBox2D) b2_->reportContacts(h, *this);
    // A kinematic block moves with its twist exactly: Box2D's single-precision sum of small
    // steps drifts (93 um over 10,000 steps, RuntimeBlocks.KinematicBlockFollowsItsTwist), so
    // its pose is summed here in double and set.
    for (const int i : moving_) {
      Body& b = bodies_[i];
      if (b.type != BodyType::kKinematic) continue;
      b.kinematic_centre += h * b.kinematic_velocity;
      b.kinematic_angle += h * b.kinematic_angular_velocity;
      b2_->setTransform(i, b.kinematic_centre, b.kinematic_angle);
    }
    for (const int i : moving_) refresh(i);
  }
  for (Body& b : bodies_) {
    b.force.setZero();
    b.torque = 0;
    if (!ends_step) continue;
    b.load_force.setZero();
    b.load_torque = 0;
  }
  return substeps;
}

}  // namespace mpm_sdem
