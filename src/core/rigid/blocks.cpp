#include "mpm_sdem/core/rigid/blocks.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mpm_sdem/core/rigid/block_checks.hpp"

#include "rigid/box2d_bodies.hpp"
#include "rigid/penalty_contacts.hpp"

namespace mpm_sdem {

std::vector<Spheropolygon> blockParts(const BlockDef& d) {
  if (d.discs.empty()) {
    Spheropolygon part{d.core, d.rounding};
    makeCounterClockwise(part.core);
    return {part};
  }
  std::vector<Spheropolygon> parts;
  for (const Disc& disc : d.discs) parts.push_back({{disc.centre}, disc.radius});
  return parts;
}

std::vector<Spheropolygon> placedParts(const BlockDef& d) {
  std::vector<Spheropolygon> parts = blockParts(d);
  const Real c = std::cos(d.angle), s = std::sin(d.angle);
  for (Spheropolygon& part : parts)
    for (Vec2& p : part.core) p = d.position + Vec2(c * p.x() - s * p.y(), s * p.x() + c * p.y());
  return parts;
}

MassProperties blockMass(const BlockDef& d) {
  if (!d.discs.empty()) return discUnionMass(d.discs, d.density);
  const Spheropolygon part = blockParts(d)[0];
  return spheropolygonMass(part.core, part.rounding, d.density);
}

Real roundedGap(const Vec2* a, int na, Real ra, const Vec2* b, int nb, Real rb) {
  Real gap = std::numeric_limits<Real>::infinity();
  for (int k = 0; k < na; ++k) gap = std::fmin(gap, closestOnCore(b, nb, a[k]).distance);
  for (int k = 0; k < nb; ++k) gap = std::fmin(gap, closestOnCore(a, na, b[k]).distance);
  return gap - ra - rb;
}

Blocks::Blocks(const std::vector<BlockDef>& defs, const BlockContactDef& contact,
               const Vec2& gravity, Real length_hint)
    : gravity_(gravity), contact_(contact) {
  for (const BlockDef& d : defs) checkDef(d);
  scale_ = detail::box2dLengthScale(defs, contact.model, length_hint);
  b2_ = std::make_unique<detail::Box2DBodies>(gravity, scale_, contact.model);
  penalty_ = std::make_unique<detail::PenaltyContacts>(contact);
  for (const BlockDef& d : defs) add(d);
}

Blocks::~Blocks() = default;

void Blocks::checkDef(const BlockDef& d) const {
  const Problem p = blockProblem(d, contact_.model);
  if (!p.empty()) throw std::invalid_argument("block '" + d.name + "': " + p.text());
}

int Blocks::indexOf(BlockId id) const {
  if (id.slot < 0 || id.slot >= static_cast<int>(slot_place_.size())) return -1;
  return slot_generation_[id.slot] == id.generation ? slot_place_[id.slot] : -1;
}

int Blocks::checkedIndex(BlockId id) const {
  const int i = indexOf(id);
  if (i < 0) throw std::invalid_argument("no such block (removed, or never added)");
  return i;
}

BlockId Blocks::add(const BlockDef& def) {
  checkDef(def);
  BlockDef d = def;
  makeCounterClockwise(d.core);
  std::vector<Spheropolygon> parts = blockParts(d);
  const MassProperties m = blockMass(d);
  b2_->add(d, parts, m);  // the one step that may refuse the block: nothing is stored before it
  BlockId id;
  if (free_slots_.empty()) {
    id.slot = static_cast<int>(slot_place_.size());
    slot_place_.push_back(-1);
    slot_generation_.push_back(0);
  } else {
    id.slot = free_slots_.back();
    free_slots_.pop_back();
  }
  id.generation = slot_generation_[id.slot];
  slot_place_[id.slot] = count();
  Body b;
  b.mass = m;
  b.type = d.type;
  b.drive = d.drive;
  b.zeta = restitutionDampingRatio(def.restitution);
  b.kinematic_centre = d.position + rotated(d.angle, m.centroid);
  b.kinematic_angle = d.angle;
  b.kinematic_velocity = d.velocity;
  b.kinematic_angular_velocity = d.angular_velocity;
  max_zeta_ = std::max(max_zeta_, b.zeta);
  defs_.push_back(std::move(d));
  ids_.push_back(id);
  parts_.push_back(std::move(parts));
  lattices_.emplace_back();
  bodies_.push_back(b);
  coupling_.emplace_back();
  block_contact_.emplace_back();
  layoutShapes();
  refresh();
  return id;
}

void Blocks::remove(BlockId id) {
  const int i = checkedIndex(id);
  b2_->remove(i);
  defs_.erase(defs_.begin() + i);
  ids_.erase(ids_.begin() + i);
  parts_.erase(parts_.begin() + i);
  lattices_.erase(lattices_.begin() + i);
  bodies_.erase(bodies_.begin() + i);
  coupling_.erase(coupling_.begin() + i);
  block_contact_.erase(block_contact_.begin() + i);
  // The slot is free for the next block, under a new generation: this id names nothing now.
  slot_place_[id.slot] = -1;
  ++slot_generation_[id.slot];
  free_slots_.push_back(id.slot);
  for (int k = i; k < count(); ++k) slot_place_[ids_[k].slot] = k;
  max_zeta_ = 0;
  for (const Body& b : bodies_) max_zeta_ = std::max(max_zeta_, b.zeta);
  layoutShapes();
  refresh();
}

BlockId Blocks::find(const std::string& name) const {
  for (int i = 0; i < count(); ++i)
    if (defs_[i].name == name) return ids_[i];
  return {};
}

void Blocks::layoutShapes() {
  ++layout_version_;
  moving_.clear();
  for (int i = 0; i < count(); ++i)
    if (bodies_[i].type != BodyType::kStatic) moving_.push_back(i);
  shapes_.clear();
  int vertices = 0;
  for (int i = 0; i < count(); ++i) {
    bodies_[i].first_shape = static_cast<int>(shapes_.size());
    bodies_[i].shape_count = static_cast<int>(parts_[i].size());
    for (std::size_t k = 0; k < parts_[i].size(); ++k) {
      const int n = static_cast<int>(parts_[i][k].core.size());
      shapes_.push_back({i, static_cast<int>(k), vertices, n, parts_[i][k].rounding});
      vertices += n;
    }
  }
  world_vertices_.resize(vertices);
}

std::uint64_t Blocks::bodyKey(int s) const {
  // Generation (20 bits) and slot (24): never that of a removed block until its slot has been
  // reused a million times.
  const BlockId id = ids_[shapes_[s].block];
  return (static_cast<std::uint64_t>(id.generation & 0xfffff) << 24) |
         static_cast<std::uint64_t>(id.slot);
}

std::uint64_t Blocks::shapeKey(int s) const {
  return (bodyKey(s) << 20) | static_cast<std::uint64_t>(shapes_[s].part);  // part: 20 bits
}

Box Blocks::bounds(int s) const {
  const Vec2* core = coreVertices(s);
  Box box{core[0], core[0]};
  for (int k = 1; k < coreVertexCount(s); ++k) {
    box.min = box.min.cwiseMin(core[k]);
    box.max = box.max.cwiseMax(core[k]);
  }
  box.min.array() -= rounding(s);
  box.max.array() += rounding(s);
  return box;
}

std::vector<Spheropolygon> Blocks::currentParts(int i) const {
  std::vector<Spheropolygon> parts;
  for (int s = firstShape(i); s < firstShape(i) + shapesOf(i); ++s)
    parts.push_back({{coreVertices(s), coreVertices(s) + coreVertexCount(s)}, rounding(s)});
  return parts;
}

Box Blocks::blockBounds(int i) const {
  Box box = bounds(firstShape(i));
  for (int s = firstShape(i) + 1; s < firstShape(i) + shapesOf(i); ++s) {
    const Box b = bounds(s);
    box.min = box.min.cwiseMin(b.min);
    box.max = box.max.cwiseMax(b.max);
  }
  return box;
}

Real Blocks::mass(int s) const {
  return movable(s) ? bodies_[owner(s)].mass.mass : std::numeric_limits<Real>::infinity();
}

Vec2 Blocks::velocityAt(int s, const Vec2& p) const {
  const BlockState& st = bodies_[owner(s)].state;
  const Vec2 r = p - st.position;
  return st.velocity + st.angular_velocity * Vec2(-r.y(), r.x());
}

Eigen::Matrix<Real, 3, 1> Blocks::inverseMasses(int s) const {
  if (!movable(s)) return Eigen::Matrix<Real, 3, 1>::Zero();
  const Body& b = bodies_[owner(s)];
  // A held component (a drive) does not yield: infinite mass along it.
  return {b.drive.hold_vx ? 0 : 1 / b.mass.mass, b.drive.hold_vy ? 0 : 1 / b.mass.mass,
          b.drive.hold_angular ? 0 : 1 / b.mass.inertia};
}

Mat2 Blocks::inverseMass(int s, const Vec2& x) const {
  const Eigen::Matrix<Real, 3, 1> w = inverseMasses(s);
  const Vec2 r = x - bodies_[owner(s)].state.position;
  const Vec2 rp(-r.y(), r.x());
  return Mat2(w.head<2>().asDiagonal()) + rp * rp.transpose() * w.z();
}

Real Blocks::lightestMass() const {
  Real m = std::numeric_limits<Real>::infinity();
  for (const Body& b : bodies_)
    if (b.type == BodyType::kDynamic) m = std::fmin(m, b.mass.mass);
  return m;
}

BodyPose Blocks::pose(int s) const {
  const BlockState& st = bodies_[owner(s)].state;
  return {st.position, st.angle};
}

Real Blocks::movedSince(int s, const BodyPose& then) const {
  const BlockState& now = bodies_[owner(s)].state;
  Real reach = 0;  // farthest core vertex from the centre of mass
  for (int k = 0; k < coreVertexCount(s); ++k)
    reach = std::fmax(reach, (coreVertices(s)[k] - now.position).norm());
  return (now.position - then.position).norm() +
         std::abs(now.angle - then.angle) * (reach + rounding(s));
}

void Blocks::interiorPoints(int s, Real spacing, std::vector<Vec2>& points, Real& mass_each) {
  const int i = owner(s);
  Lattice& l = lattices_[i];
  const BlockState& st = bodies_[i].state;
  if (l.offset.empty() || l.spacing != spacing) {
    // Lattice points at cell centres of the block's box that lie within its outline, each
    // given to the first part that holds it (a cluster's discs overlap: the union counts once).
    l = Lattice();
    l.spacing = spacing;
    l.angle0 = st.angle;
    const Box box = blockBounds(i);
    std::vector<std::vector<Vec2>> by_part(shapesOf(i));
    for (Real y = box.min.y() + spacing / 2; y < box.max.y(); y += spacing) {
      for (Real x = box.min.x() + spacing / 2; x < box.max.x(); x += spacing) {
        for (int k = 0; k < shapesOf(i); ++k) {
          const int shape = firstShape(i) + k;
          if (closest(shape, Vec2(x, y)).distance < rounding(shape)) {
            by_part[k].push_back(Vec2(x, y) - st.position);
            break;
          }
        }
      }
    }
    std::size_t total = 0;
    for (const auto& part : by_part) total += part.size();
    if (total == 0) by_part[0].push_back(Vec2(0, 0));  // smaller than a point spacing
    for (const auto& part : by_part) {
      l.begin.push_back(static_cast<int>(l.offset.size()));
      l.offset.insert(l.offset.end(), part.begin(), part.end());
    }
    l.begin.push_back(static_cast<int>(l.offset.size()));
    l.mass = bodies_[i].mass.mass / static_cast<Real>(l.offset.size());
  }
  const int k = shapes_[s].part;
  const Real c = std::cos(st.angle - l.angle0), sn = std::sin(st.angle - l.angle0);
  points.clear();
  for (int n = l.begin[k]; n < l.begin[k + 1]; ++n) {
    const Vec2& o = l.offset[n];
    points.push_back(st.position + Vec2(c * o.x() - sn * o.y(), sn * o.x() + c * o.y()));
  }
  mass_each = l.mass;
}

void Blocks::beginCoupling(Real dt) {
  for (Load& c : coupling_) c = Load();
  for (Load& c : block_contact_) c = Load();
  for (Body& b : bodies_) {
    b.trial_v = b.state.velocity;
    b.trial_w = b.state.angular_velocity;
    if (b.type != BodyType::kDynamic) continue;
    // Gravity and the external loads added so far (the material's come after this call).
    b.trial_v += dt * (gravity_ + b.force / b.mass.mass);
    b.trial_w += dt * b.torque / b.mass.inertia;
    holdTrial(b);
  }
  for (Body& b : bodies_) {
    b.load_force = b.force;
    b.load_torque = b.torque;
    b.force.setZero();
    b.torque = 0;
  }
}

void Blocks::holdTrial(Body& b) {
  if (b.drive.hold_vx) b.trial_v.x() = b.drive.velocity.x();
  if (b.drive.hold_vy) b.trial_v.y() = b.drive.velocity.y();
  if (b.drive.hold_angular) b.trial_w = b.drive.angular_velocity;
}

Vec2 Blocks::trialVelocityAt(int s, const Vec2& p) const {
  const Body& b = bodies_[owner(s)];
  const Vec2 r = p - b.state.position;
  return b.trial_v + b.trial_w * Vec2(-r.y(), r.x());
}

void Blocks::addForce(int i, const Vec2& f, const Vec2& point) {
  bodies_[i].force += f;
  bodies_[i].torque += cross(point - bodies_[i].state.position, f);
}

void Blocks::addTorque(int i, Real torque) {
  bodies_[i].torque += torque;
}

void Blocks::addLoad(BlockId id, const Vec2& force, const Vec2& point, Real torque) {
  const int i = checkedIndex(id);
  addForce(i, force, point);
  addTorque(i, torque);
}

void Blocks::setGravity(const Vec2& gravity) {
  gravity_ = gravity;
  b2_->setGravity(gravity);
}

void Blocks::addContactForce(int a, int b, const Vec2& f, const Vec2& point) {
  addForce(a, f, point);
  addForce(b, -f, point);
  recordContactForce(a, b, f, point);
}

void Blocks::recordContactForce(int a, int b, const Vec2& f, const Vec2& point) {
  for (const auto& [i, fi] : {std::pair<int, Vec2>(a, f), std::pair<int, Vec2>(b, -f)}) {
    Load& c = block_contact_[i];
    c.force += substep_share_ * fi;
    c.torque += substep_share_ * cross(point - bodies_[i].state.position, fi);
    ++c.contacts;
  }
}

void Blocks::applyForce(int s, const Vec2& f, const Vec2& point) {
  pushForce(s, f, point);
  recordForce(s, f, point);
}

void Blocks::pushForce(int s, const Vec2& f, const Vec2& point) {
  addForce(owner(s), f, point);
}

void Blocks::recordForce(int s, const Vec2& f, const Vec2& point) {
  const int i = owner(s);
  Load& c = coupling_[i];
  c.force += f;
  c.torque += cross(point - bodies_[i].state.position, f);
  ++c.contacts;
}

void Blocks::applyImpulse(int s, const Vec2& impulse, const Vec2& point, Real dt) {
  Body& b = bodies_[owner(s)];
  if (b.type == BodyType::kDynamic) {
    b.trial_v += impulse / b.mass.mass;
    b.trial_w += cross(point - b.state.position, impulse) / b.mass.inertia;
    holdTrial(b);
  }
  applyForce(s, impulse / dt, point);
}

Real Blocks::stableStep(Real kappa2) const {
  if (contact_.model != BlockContactModel::kPenalty) return std::numeric_limits<Real>::infinity();
  return penalty_->stableStep(*this, kappa2);
}

}  // namespace mpm_sdem
