#include "rigid/penalty_contacts.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <tuple>

#include "mpm_sdem/core/coupling/restitution.hpp"

namespace mpm_sdem::detail {

namespace {

bool overlap(const Box& a, const Box& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() &&
         b.min.y() <= a.max.y();
}

}  // namespace

bool PenaltyContacts::Key::operator<(const Key& o) const {
  return std::tie(first, second, vertex, side) < std::tie(o.first, o.second, o.vertex, o.side);
}

bool PenaltyContacts::Key::operator==(const Key& o) const {
  return first == o.first && second == o.second && vertex == o.vertex && side == o.side;
}

void PenaltyContacts::apply(Blocks& B, Real h) {
  next_history_.clear();
  findPairs(B);
  // Two outlines can overlap only where their boxes do: blocks first, then their shapes.
  for (const auto& [i, j] : pairs_) {
    const bool single = B.shapesOf(i) == 1 && B.shapesOf(j) == 1;
    for (int p = B.firstShape(i); p < B.firstShape(i) + B.shapesOf(i); ++p)
      for (int q = B.firstShape(j); q < B.firstShape(j) + B.shapesOf(j); ++q)
        if (single || overlap(B.bounds(p), B.bounds(q))) pair(B, p, q, h);
  }
  std::sort(next_history_.begin(), next_history_.end(),
            [](const auto& x, const auto& y) { return x.first < y.first; });
  history_.swap(next_history_);
}

namespace {

// A box (m) in Box2D units, rounded outwards: the tree never misses a pair the boxes make.
b2AABB treeBox(const Box& b, Real scale) {
  b2AABB a;
  a.lowerBound.Set(std::nextafter(static_cast<float>(b.min.x() * scale), -INFINITY),
                   std::nextafter(static_cast<float>(b.min.y() * scale), -INFINITY));
  a.upperBound.Set(std::nextafter(static_cast<float>(b.max.x() * scale), INFINITY),
                   std::nextafter(static_cast<float>(b.max.y() * scale), INFINITY));
  return a;
}

}  // namespace

void PenaltyContacts::placeBoxes(const Blocks& B) {
  const int n = B.count();
  const Real scale = B.lengthScale();
  if (tree_ && placed_version_ == B.layoutVersion() && static_cast<int>(boxes_.size()) == n) {
    for (const int i : B.movingBlocks()) {
      boxes_[i] = B.blockBounds(i);
      tree_->MoveProxy(proxies_[i], treeBox(boxes_[i], scale), b2Vec2(0, 0));
    }
    return;
  }
  // Blocks came, went or were moved: the tree anew.
  tree_ = std::make_unique<b2DynamicTree>();
  boxes_.resize(n);
  proxies_.resize(n);
  dynamic_.clear();
  for (int i = 0; i < n; ++i) {
    boxes_[i] = B.blockBounds(i);
    proxies_[i] = tree_->CreateProxy(treeBox(boxes_[i], scale),
                                     reinterpret_cast<void*>(static_cast<std::uintptr_t>(i)));
    if (B.movable(B.firstShape(i))) dynamic_.push_back(i);
  }
  placed_version_ = B.layoutVersion();
}

void PenaltyContacts::findPairs(const Blocks& B) {
  placeBoxes(B);
  pairs_.clear();
  struct Query {
    const b2DynamicTree* tree;
    const std::vector<Box>* boxes;
    const Blocks* blocks;
    std::vector<std::pair<int, int>>* pairs;
    int i;
    bool QueryCallback(std::int32_t proxy) {
      const int j = static_cast<int>(reinterpret_cast<std::uintptr_t>(tree->GetUserData(proxy)));
      // A pair of dynamic blocks is asked for by both: kept once, by the first of the two.
      if (j == i || (j < i && blocks->movable(blocks->firstShape(j)))) return true;
      if (overlap((*boxes)[i], (*boxes)[j])) pairs->emplace_back(std::min(i, j), std::max(i, j));
      return true;
    }
  };
  const Real scale = B.lengthScale();
  for (int i : dynamic_) {
    Query q{tree_.get(), &boxes_, &B, &pairs_, i};
    tree_->Query(&q, treeBox(boxes_[i], scale));
  }
  std::sort(pairs_.begin(), pairs_.end());
}

void PenaltyContacts::pair(Blocks& B, int i, int j, Real h) {
  // Seed 000 eq. 38 and 41: the overlapping vertex-edge pairs, vertices of shape i against the
  // edges of j, then vertices of j against i.
  springs_.clear();
  for (int side = 0; side < 2; ++side) {
    const int a = side == 0 ? i : j, b = side == 0 ? j : i;
    const int nb = B.coreVertexCount(b);
    // A disk has no edges: its centre meets the other's edges in the other pass.
    if (nb == 1 && (B.coreVertexCount(a) > 1 || side == 1)) continue;
    const Real reach = B.rounding(a) + B.rounding(b);
    // A vertex farther than reach from b's core box along x or y is farther than that from the
    // core: no spring, and no distance to compute (a face's far vertices, half of them).
    Box near = B.bounds(b);
    near.min.array() -= B.rounding(a);
    near.max.array() += B.rounding(a);
    for (int k = 0; k < B.coreVertexCount(a); ++k) {
      const Vec2 X = B.coreVertices(a)[k];
      if ((X.array() < near.min.array()).any() || (X.array() > near.max.array()).any()) continue;
      const CoreDistance c = closestOnCore(B.coreVertices(b), nb, X);
      const Real xi = reach - c.distance;  // eq. 38
      if (xi <= 0) continue;
      // Eq. 41: the middle of the overlap along the normal (which points from b to a).
      springs_.push_back(
          {X - (B.rounding(a) - xi / 2) * c.normal, c.normal, xi, k, side, Rates::Zero(), 0});
    }
  }
  if (springs_.empty()) return;
  // Two convex outlines touch in one place: the pair's springs are one contact (a face gives
  // two or four, eq. 39). Its dashpot is sized for the restitution on the pair's effective
  // normal mass at the contact's centre (1/m = sum over the movable sides of 1/M + (r x n)^2 /
  // I), so that the springs together, n k_n on m, rebound with e; each takes an equal share.
  // Normals are counted from j towards i.
  Vec2 centre(0, 0), normal(0, 0);
  for (const Spring& s : springs_) {
    centre += s.point / static_cast<Real>(springs_.size());
    normal += s.side == 0 ? s.normal : Vec2(-s.normal);
  }
  normal = normal.norm() > 0 ? Vec2(normal.normalized()) : springs_[0].normal;
  const Real inverse_mass =
      normal.dot((B.inverseMass(i, centre) + B.inverseMass(j, centre)) * normal);
  const Real count = static_cast<Real>(springs_.size());
  // The less elastic side sets the damping (the smaller restitution, the larger ratio).
  const Real gamma = 2 * std::max(B.dampingRatio(i), B.dampingRatio(j)) *
                     std::sqrt(count * def_.normal_stiffness / inverse_mass) / count;
  pairPush(B, i, j, gamma, h);
  const Real mu = std::min(B.friction(i), B.friction(j));
  // Adhesion (seed 003 sec. 4.3): c over the length the outlines touch, the spread of the
  // springs' points across the normal (a face's length; zero on a vertex or a disk), shared by
  // the springs and pulling. Friction stays capped by what the springs push, which includes the
  // adhesion they balance.
  Real pull = 0;
  const Real c = std::max(B.def(B.owner(i)).adhesion, B.def(B.owner(j)).adhesion);
  if (c > 0) {
    const Vec2 t(-normal.y(), normal.x());
    Real lo = std::numeric_limits<Real>::infinity(), hi = -lo;
    for (const Spring& s : springs_) {
      lo = std::fmin(lo, s.point.dot(t));
      hi = std::fmax(hi, s.point.dot(t));
    }
    pull = c * (hi - lo) / count;
  }
  const std::uint64_t key_i = B.shapeKey(i), key_j = B.shapeKey(j);
  for (const Spring& s : springs_) {
    const int a = s.side == 0 ? i : j, b = s.side == 0 ? j : i;
    const Vec2 v = B.velocityAt(a, s.point) - B.velocityAt(b, s.point);
    const Real vn = v.dot(s.normal);
    const Real push = std::fmax(s.push, Real(0));
    const Key key{key_i, key_j, s.vertex, s.side};
    Vec2 delta(0, 0);
    const auto it =
        std::lower_bound(history_.begin(), history_.end(), std::make_pair(key, Vec2(0, 0)),
                         [](const auto& x, const auto& y) { return x.first < y.first; });
    if (it != history_.end() && it->first == key) delta = it->second;
    // Eq. 43: tangential spring on the accumulated sliding, capped by Coulomb.
    delta += (v - vn * s.normal) * h;
    delta -= delta.dot(s.normal) * s.normal;
    Vec2 ft = -def_.tangential_stiffness * delta;
    if (ft.norm() > mu * push) {
      ft *= mu * push / ft.norm();
      delta = -ft / def_.tangential_stiffness;
    }
    next_history_.emplace_back(key, delta);
    const Vec2 f = (push - pull) * s.normal + ft;
    B.addContactForce(B.owner(a), B.owner(b), f, s.point);
  }
}

void PenaltyContacts::pairPush(const Blocks& B, int i, int j, Real gamma, Real h) {
  // The pair's springs and dashpots as if the two blocks met nothing else. In the springs'
  // overlaps xi (J their rates on the blocks' velocities u, W the inverse masses),
  // xi'' = -A (k xi + gamma xi') with A = J W J^T: springs and dashpots share A (Rayleigh
  // damping), so the eigenvectors of A are the pair's modes (pressing, rocking), each a damped
  // oscillator of w^2 = lambda k and 2 zeta w = lambda gamma. Each mode's spring and dashpot are
  // the ones with which the blocks' symplectic Euler lands on its exact motion at every substep
  // (exactStepSpring): the restitution does not move with the substep, and the dashpots need
  // not bound it (stableStep; explicit ones bounded it 7 times lower at e = 0.05).
  const int n = static_cast<int>(springs_.size());
  const BlockState& si = B.state(B.owner(i));
  const BlockState& sj = B.state(B.owner(j));
  Rates u, w;
  u << si.velocity, si.angular_velocity, sj.velocity, sj.angular_velocity;
  w << B.inverseMasses(i), B.inverseMasses(j);
  for (Spring& s : springs_) {
    const Real sign = s.side == 0 ? 1 : -1;  // +1 on the vertex's block
    const Vec2 ri = s.point - si.position, rj = s.point - sj.position;
    s.rate << sign * s.normal, sign * s.normal.dot(Vec2(-ri.y(), ri.x())), -sign * s.normal,
        -sign * s.normal.dot(Vec2(-rj.y(), rj.x()));
  }
  const Real k = def_.normal_stiffness;
  // A mode of inverse mass lambda, overlap x and closing rate v: its push. A mode nothing moves
  // (a held or static side) takes the spring and dashpot themselves.
  auto push = [&](Real lambda, Real x, Real v) {
    if (!(lambda > 0)) return k * x + gamma * v;
    const ExactStepSpring e = exactStepSpring(lambda * k, lambda * gamma / 2, h);
    return (e.stiffness * x + e.damping * v) / lambda;
  };
  if (n == 1 || n > kMaxSprings) {
    // One spring: its own mode. More than a face's four many times over: outlines that passed
    // through each other, each spring stepped as if alone (no worse than explicit dashpots).
    for (Spring& s : springs_)
      s.push = push(s.rate.dot(w.cwiseProduct(s.rate)), s.xi, -s.rate.dot(u));
    return;
  }
  Matrix A(n, n);
  Vector overlap(n), closing(n);
  for (int r = 0; r < n; ++r) {
    overlap(r) = springs_[r].xi;
    closing(r) = -springs_[r].rate.dot(u);
    for (int c = 0; c <= r; ++c)
      A(r, c) = A(c, r) = springs_[r].rate.dot(w.cwiseProduct(springs_[c].rate));
  }
  modes_.compute(A);
  const Vector x = modes_.eigenvectors().transpose() * overlap;
  const Vector v = modes_.eigenvectors().transpose() * closing;
  Vector force(n);
  for (int m = 0; m < n; ++m) force(m) = push(modes_.eigenvalues()(m), x(m), v(m));
  const Vector each = modes_.eigenvectors() * force;
  for (int r = 0; r < n; ++r) springs_[r].push = each(r);
}

Real PenaltyContacts::stableStep(const Blocks& B, Real kappa2) const {
  if (B.count() < 2) return std::numeric_limits<Real>::infinity();  // no spring can form
  // The fastest motion a contact's springs drive. For kinetic energy E, a block's normal
  // velocity at a contact point, v_n + w (r x n), squared is at most 2 E (1/M + (r x n)^2 / I)
  // <= 2 E / m_c (Cauchy-Schwarz), |r x n| being at most the distance to the farthest core vertex
  // (the contact point lies off the core only along n). So n springs between blocks a and b
  // vibrate at w^2 <= n k_n (1/m_c,a + 1/m_c,b). A pair's modes are stepped exactly (pairPush),
  // so its dashpots bound nothing, but several pairs add up explicitly (the undamped bound,
  // w h <= 2) and a contact starts and ends between substeps. So the substep is the bound the
  // explicit dashpots allowed (contactTimeStep with the damping ratio zeta sqrt(rho): a mode w
  // of a pair whose dashpot is sized on w_c has the ratio zeta w / w_c, at most zeta sqrt(rho)
  // with rho = M / m_c), but at least half the undamped one. At the full undamped bound the
  // Drucker-Prager wooden-block scene (subcycled, e = 0.05) moved block 1 by 0.42 cm from
  // kappa_2 = 0.1 to 0.025; at half of it by 0.25 cm (SubcycledContact test).
  // The bound: n springs between two of the blocks with the smallest m_c, with the largest rho
  // and damping ratio. Two spheropolygons meet with at most four springs (a face, eq. 39); a
  // cluster with at most one per disc pair, and a disc of one cluster meets at most two discs of
  // another along a face (staggered), so twice its discs.
  Real m_c = std::numeric_limits<Real>::infinity(), rho = 1;
  int springs = 4;
  for (int b = 0; b < B.count(); ++b) {
    if (!B.movable(B.firstShape(b))) continue;
    const MassProperties& m = B.massProperties(b);
    Real r2 = 0;
    for (const Spheropolygon& part : B.parts(b))
      for (const Vec2& v : part.core) r2 = std::fmax(r2, (v - m.centroid).squaredNorm());
    m_c = std::fmin(m_c, 1 / (1 / m.mass + r2 / m.inertia));
    rho = std::fmax(rho, 1 + m.mass * r2 / m.inertia);
    if (B.shapesOf(b) > 1) springs = std::max(springs, 2 * B.shapesOf(b));
  }
  if (!std::isfinite(m_c)) return std::numeric_limits<Real>::infinity();
  const Real k = def_.normal_stiffness;
  return std::fmax(
      contactTimeStep(0.5 * m_c, k, B.maxDampingRatio() * std::sqrt(rho), springs, kappa2),
      0.5 * contactTimeStep(0.5 * m_c, k, 0, springs, kappa2));
}

}  // namespace mpm_sdem::detail
