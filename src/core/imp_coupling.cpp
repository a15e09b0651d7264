#include "mpm_sdem/core/imp_coupling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm_sdem {

void ImpCoupling::init(const CouplingDef& def, const Vec2& lo, const Vec2& hi, Real cell_size) {
  def_ = def;
  lo_ = lo;
  bucket_ = cell_size;
  nx_ = static_cast<int>(std::ceil((hi.x() - lo.x()) / bucket_)) + 1;
  ny_ = static_cast<int>(std::ceil((hi.y() - lo.y()) / bucket_)) + 1;
  built_ = false;
}

bool ImpCoupling::needsRebuild(const Particles& P, const Blocks& B) const {
  if (!built_ || x_built_.size() != P.size()) return true;
  // Points and blocks each may move up to half the Verlet distance before a pair outside the
  // list could reach contact.
  const Real limit2 = 0.25 * def_.verlet_distance * def_.verlet_distance;
  for (int b = 0; b < B.count(); ++b) {
    const BlockState& now = B.state(b);
    const BlockState& then = blocks_built_[b];
    Real reach = 0;  // farthest core vertex from the centre of mass
    for (int k = 0; k < B.vertexCount(b); ++k)
      reach = std::fmax(reach, (B.vertices(b)[k] - now.position).norm());
    const Real moved = (now.position - then.position).norm() +
                       std::abs(now.angle - then.angle) * (reach + B.def(b).rounding);
    if (moved * moved > limit2) return true;
  }
  const long n = static_cast<long>(P.size());
  int moved = 0;
#pragma omp parallel for schedule(static) reduction(| : moved)
  for (long p = 0; p < n; ++p) {
    const Real dx = P.x[p] - x_built_[p], dy = P.y[p] - y_built_[p];
    if (dx * dx + dy * dy > limit2) moved = 1;
  }
  return moved != 0;
}

void ImpCoupling::rebuild(const Particles& P, const Blocks& B) {
  ++rebuilds_;
  built_ = true;
  const std::size_t n = P.size();
  // Bucket sort of the points by cell (seed 002 sec. 3.1): counting sort, O(N).
  cell_of_.resize(n);
  cell_start_.assign(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  for (std::size_t p = 0; p < n; ++p) {
    const int i = std::clamp(static_cast<int>((P.x[p] - lo_.x()) / bucket_), 0, nx_ - 1);
    const int j = std::clamp(static_cast<int>((P.y[p] - lo_.y()) / bucket_), 0, ny_ - 1);
    cell_of_[p] = i + j * nx_;
    ++cell_start_[cell_of_[p] + 1];
  }
  for (std::size_t c = 1; c < cell_start_.size(); ++c) cell_start_[c] += cell_start_[c - 1];
  cell_items_.resize(n);
  {
    std::vector<int> fill(cell_start_.begin(), cell_start_.end() - 1);
    for (std::size_t p = 0; p < n; ++p) cell_items_[fill[cell_of_[p]]++] = static_cast<int>(p);
  }
  x_built_ = P.x;
  y_built_ = P.y;
  blocks_built_.resize(B.count());
  for (int b = 0; b < B.count(); ++b) blocks_built_[b] = B.state(b);

  // Candidates: points in the cells under each block's outline grown by r_p + V_d, kept when
  // within that distance. Sorted by (block, point) so that histories carry over by merge.
  previous_.swap(candidates_);
  candidates_.clear();
  for (int b = 0; b < B.count(); ++b) {
    const Real grow = B.def(b).rounding + def_.contact_radius + def_.verlet_distance;
    Vec2 lo = B.vertices(b)[0], hi = lo;
    for (int k = 1; k < B.vertexCount(b); ++k) {
      lo = lo.cwiseMin(B.vertices(b)[k]);
      hi = hi.cwiseMax(B.vertices(b)[k]);
    }
    const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - grow - lo_.x()) / bucket_)));
    const int i1 =
        std::min(nx_ - 1, static_cast<int>(std::floor((hi.x() + grow - lo_.x()) / bucket_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - grow - lo_.y()) / bucket_)));
    const int j1 =
        std::min(ny_ - 1, static_cast<int>(std::floor((hi.y() + grow - lo_.y()) / bucket_)));
    const std::size_t first = candidates_.size();
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const int c = i + j * nx_;
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const int p = cell_items_[k];
          const CoreDistance d =
              closestOnCore(B.vertices(b), B.vertexCount(b), Vec2(P.x[p], P.y[p]));
          if (d.distance < grow) candidates_.push_back({p, b, Vec2(0, 0), Vec2(0, 0)});
        }
      }
    }
    std::sort(candidates_.begin() + first, candidates_.end(),
              [](const Contact& x, const Contact& y) { return x.particle < y.particle; });
  }
  auto before = [](const Contact& x, const Contact& y) {
    return x.block != y.block ? x.block < y.block : x.particle < y.particle;
  };
  for (Contact& c : candidates_) {
    const auto it = std::lower_bound(previous_.begin(), previous_.end(), c, before);
    if (it != previous_.end() && it->block == c.block && it->particle == c.particle)
      c.history = it->history;
  }
}

void ImpCoupling::removeBlock(int b) {
  for (std::vector<Contact>* list : {&candidates_, &previous_}) {
    list->erase(
        std::remove_if(list->begin(), list->end(), [b](const Contact& c) { return c.block == b; }),
        list->end());
    for (Contact& c : *list)
      if (c.block > b) --c.block;
  }
  built_ = false;
}

void ImpCoupling::computeForces(const Particles& P, Blocks& B, Real dt) {
  if (needsRebuild(P, B)) rebuild(P, B);
  for (auto& c : B.coupling()) c = Blocks::Coupling();
  active_ = 0;
  const Real kn = def_.normal_stiffness, kt = def_.tangential_stiffness, rp = def_.contact_radius;
  for (Contact& c : candidates_) {
    const int b = c.block, p = c.particle;
    const BlockDef& bd = B.def(b);
    const Vec2 x(P.x[p], P.y[p]);
    const CoreDistance d = closestOnCore(B.vertices(b), B.vertexCount(b), x);
    const Real xi = bd.rounding + rp - d.distance;  // eq. 44
    if (xi <= 0) {
      c.history.setZero();
      c.force.setZero();
      continue;
    }
    // Contact point: the middle of the overlap along the normal (eq. 41 for a disk).
    const Vec2 point = d.point + (bd.rounding - xi / 2) * d.normal;
    const Vec2 v = Vec2(P.vx[p], P.vy[p]) - B.velocityAt(b, point);
    const Real vn = v.dot(d.normal);
    const Real mp = P.mass[p];
    const Real m = bd.type == BodyType::kDynamic
                       ? mp * B.massProperties(b).mass / (mp + B.massProperties(b).mass)
                       : mp;
    const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(kn * m);
    const Real fn = std::fmax(kn * xi - gamma * vn, Real(0));
    c.history += (v - vn * d.normal) * dt;
    c.history -= c.history.dot(d.normal) * d.normal;
    Vec2 ft = -kt * c.history;
    const Real cap = bd.friction * fn;
    if (ft.norm() > cap) {
      ft *= ft.norm() > 0 ? cap / ft.norm() : 0;
      c.history = -ft / kt;
    }
    c.force = fn * d.normal + ft;    // eq. 43 on the point
    B.addForce(b, -c.force, point);  // eq. 49-50, equal and opposite
    Blocks::Coupling& out = B.coupling()[b];
    out.force -= c.force;
    const Vec2 r = point - B.state(b).position;
    out.torque -= r.x() * c.force.y() - r.y() * c.force.x();
    ++out.contacts;
    ++active_;
  }
}

}  // namespace mpm_sdem
