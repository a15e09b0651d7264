#include "coupling/contact_search.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "parallel.hpp"

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

bool ContactSearch::needsRebuild(const Particles& P, const ContactBodies& B) const {
  if (!built_ || x_built_.size() != P.size() ||
      bodies_built_.size() != static_cast<std::size_t>(B.shapeCount()))
    return true;
  // Points and blocks each may move up to half the Verlet distance before a pair outside the
  // list could reach contact.
  const Real limit2 = 0.25 * verlet_ * verlet_;
  for (int b = 0; b < B.shapeCount(); ++b) {
    const Real moved = B.movedSince(b, bodies_built_[b]);
    if (moved * moved > limit2) return true;
  }
  const long n = static_cast<long>(P.size());
  auto far = [&](long p) {
    const Real dx = P.x[p] - x_built_[p], dy = P.y[p] - y_built_[p];
    return dx * dx + dy * dy > limit2;
  };
  if (detail::singleThread()) {
    for (long p = 0; p < n; ++p)
      if (far(p)) return true;
    return false;
  }
  int moved = 0;
#pragma omp parallel for schedule(static) reduction(| : moved)
  for (long p = 0; p < n; ++p) moved |= far(p);
  return moved != 0;
}

void ContactSearch::rebuild(const Particles& P, const ContactBodies& B) {
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
  bodies_built_.resize(B.shapeCount());
  for (int b = 0; b < B.shapeCount(); ++b) bodies_built_[b] = B.pose(b);

  // Pairs: points in the cells under each body's outline grown by the reach + V_d, kept when
  // within that distance. Sorted by (body, point) so that histories carry over by merge.
  previous_.swap(pairs_);
  pairs_.clear();
  for (int b = 0; b < B.shapeCount(); ++b) {
    const Real grow = B.rounding(b) + reach_ + verlet_;  // from the core
    const Box box = B.bounds(b);
    const Vec2 lo = box.min.array() - (reach_ + verlet_);
    const Vec2 hi = box.max.array() + (reach_ + verlet_);
    const int i0 = std::max(0, static_cast<int>(std::floor((lo.x() - lo_.x()) / bucket_)));
    const int i1 = std::min(nx_ - 1, static_cast<int>(std::floor((hi.x() - lo_.x()) / bucket_)));
    const int j0 = std::max(0, static_cast<int>(std::floor((lo.y() - lo_.y()) / bucket_)));
    const int j1 = std::min(ny_ - 1, static_cast<int>(std::floor((hi.y() - lo_.y()) / bucket_)));
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const int c = i + j * nx_;
        for (int k = cell_start_[c]; k < cell_start_[c + 1]; ++k) {
          const int p = cell_items_[k];
          if (B.closest(b, Vec2(P.x[p], P.y[p])).distance < grow)
            pairs_.push_back({p, b, B.bodyOf(b), B.bodyKey(b)});
        }
      }
    }
  }
  std::sort(pairs_.begin(), pairs_.end(), [](const ContactPair& x, const ContactPair& y) {
    return std::tie(x.body, x.particle, x.shape) < std::tie(y.body, y.particle, y.shape);
  });
  // Histories carry over by (body key, particle), from the first pair of a point with a body
  // (the one that carries the contact): the bodies may have been renumbered since.
  auto before = [](const ContactPair& x, const ContactPair& y) {
    return std::tie(x.body_key, x.particle, x.shape) < std::tie(y.body_key, y.particle, y.shape);
  };
  std::sort(previous_.begin(), previous_.end(), before);
  for (ContactPair& c : pairs_) {
    const auto it = std::lower_bound(
        previous_.begin(), previous_.end(), c, [](const ContactPair& x, const ContactPair& y) {
          return std::tie(x.body_key, x.particle) < std::tie(y.body_key, y.particle);
        });
    if (it != previous_.end() && it->body_key == c.body_key && it->particle == c.particle)
      c.history = it->history;
  }
}

void ContactSearch::update(const Particles& P, const ContactBodies& B) {
  if (needsRebuild(P, B)) rebuild(P, B);
}

}  // namespace mpm_sdem
