#include "mpm_sdem/core/contact_search.hpp"

#include <algorithm>
#include <cmath>

namespace mpm_sdem {

void ContactSearch::init(const Vec2& lo, const Vec2& hi, Real cell_size, Real reach,
                         Real verlet_distance) {
  lo_ = lo;
  reach_ = reach;
  verlet_ = verlet_distance;
  bucket_ = cell_size;
  nx_ = static_cast<int>(std::ceil((hi.x() - lo.x()) / bucket_)) + 1;
  ny_ = static_cast<int>(std::ceil((hi.y() - lo.y()) / bucket_)) + 1;
  built_ = false;
}

bool ContactSearch::needsRebuild(const Particles& P, const Blocks& B) const {
  if (!built_ || x_built_.size() != P.size()) return true;
  // Points and blocks each may move up to half the Verlet distance before a pair outside the
  // list could reach contact.
  const Real limit2 = 0.25 * verlet_ * verlet_;
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

void ContactSearch::rebuild(const Particles& P, const Blocks& B) {
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

  // Pairs: points in the cells under each block's outline grown by the reach + V_d, kept when
  // within that distance. Sorted by (block, point) so that histories carry over by merge.
  previous_.swap(pairs_);
  pairs_.clear();
  for (int b = 0; b < B.count(); ++b) {
    const Real grow = B.def(b).rounding + reach_ + verlet_;
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
    const std::size_t first = pairs_.size();
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const int c = i + j * nx_;
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const int p = cell_items_[k];
          const CoreDistance d =
              closestOnCore(B.vertices(b), B.vertexCount(b), Vec2(P.x[p], P.y[p]));
          if (d.distance < grow) pairs_.push_back({p, b});
        }
      }
    }
    std::sort(pairs_.begin() + first, pairs_.end(),
              [](const ContactPair& x, const ContactPair& y) { return x.particle < y.particle; });
  }
  auto before = [](const ContactPair& x, const ContactPair& y) {
    return x.block != y.block ? x.block < y.block : x.particle < y.particle;
  };
  for (ContactPair& c : pairs_) {
    const auto it = std::lower_bound(previous_.begin(), previous_.end(), c, before);
    if (it != previous_.end() && it->block == c.block && it->particle == c.particle)
      c.history = it->history;
  }
}

void ContactSearch::removeBlock(int b) {
  for (std::vector<ContactPair>* list : {&pairs_, &previous_}) {
    list->erase(std::remove_if(list->begin(), list->end(),
                               [b](const ContactPair& c) { return c.block == b; }),
                list->end());
    for (ContactPair& c : *list)
      if (c.block > b) --c.block;
  }
  built_ = false;
}

void ContactSearch::update(const Particles& P, const Blocks& B) {
  if (needsRebuild(P, B)) rebuild(P, B);
}

}  // namespace mpm_sdem
