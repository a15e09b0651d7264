#include "mpm_sdem/core/mpm/sleep.hpp"

#include <algorithm>
#include <cmath>

#include "parallel.hpp"
#include "sweeps.hpp"

namespace mpm_sdem {

void Sleep::init(const SleepDef& def, const Grid& g, const Tiles& t) {
  def_ = def;
  nx_ = t.nx;
  ny_ = t.ny;
  // Two tiles by default: a block is seen before it reaches a sleeping point's stencil, its
  // contact reach or the contact search's Verlet margin, all within a few cells.
  margin_ = def.margin > 0 ? def.margin : 2 * Tiles::kSize * g.h;
  const std::size_t n = static_cast<std::size_t>(nx_) * ny_;
  for (auto* a : {&asleep_, &moved_, &change_, &near_}) a->assign(n, 0);
  quiet_.assign(n, 0);
  sleeping_points_ = 0;
  runs_.clear();
  if (!on()) return;
  sleepers_.init(g);
  share_.init(g.origin + Vec2(Grid::kPad * g.h, Grid::kPad * g.h), g.cells_x, g.cells_y, g.h);
}

void Sleep::noteMovingNodes(const Grid& G) {
  if (!any()) return;
  const Real speed2 = def_.speed * def_.speed;
  // A node a sleeping tile's points read (cells c of the tile read nodes c - 1 .. c + 2) moving
  // faster than the sleep speed: the load of a moving neighbour has reached the tile. Nodes no
  // awake point used are zero.
  detail::parallelFor(static_cast<long>(asleep_.size()), [&](long t) {
    moved_[t] = 0;
    if (!asleep_[t]) return;
    const int a = static_cast<int>(t % nx_) * Tiles::kSize;
    const int b = static_cast<int>(t / nx_) * Tiles::kSize;
    for (int j = std::max(b - 1, 0); j <= std::min(b + Tiles::kSize + 1, G.ny - 1); ++j) {
      for (int i = std::max(a - 1, 0); i <= std::min(a + Tiles::kSize + 1, G.nx - 1); ++i) {
        const int k = G.index(i, j);
        if (G.vel_x[k] * G.vel_x[k] + G.vel_y[k] * G.vel_y[k] > speed2) {
          moved_[t] = 1;
          return;
        }
      }
    }
  });
}

void Sleep::keepAwake(const Vec2& lo, const Vec2& hi) {
  if (!on() || nx_ == 0) return;
  // Tile (i, j) covers cells kSize i .. kSize (i + 1) - 1 from the grid's origin (share_ has
  // the grid's geometry).
  const Real tile = Tiles::kSize * share_.h;
  const Vec2 a = (lo - share_.origin).array() - margin_, b = (hi - share_.origin).array() + margin_;
  const int i0 = std::clamp(static_cast<int>(std::floor(a.x() / tile)), 0, nx_ - 1);
  const int i1 = std::clamp(static_cast<int>(std::floor(b.x() / tile)), 0, nx_ - 1);
  const int j0 = std::clamp(static_cast<int>(std::floor(a.y() / tile)), 0, ny_ - 1);
  const int j1 = std::clamp(static_cast<int>(std::floor(b.y() / tile)), 0, ny_ - 1);
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) near_[i + j * nx_] = 1;
}

bool Sleep::update(Particles& P, const Tiles& T, KernelType kernel, Real dt) {
  if (!on()) return false;
  const Real speed2 = def_.speed * def_.speed;
  // Each tile decides from its own awake points (binned at their current positions) and
  // nodes, so the tiles decide in parallel.
  detail::parallelFor(static_cast<long>(asleep_.size()), [&](long t) {
    const int begin = T.start[t], end = T.mpm_end[t];
    change_[t] = kStays;
    if (asleep_[t]) {
      // An awake point in a sleeping tile has entered it.
      if (near_[t] || begin != end || moved_[t]) change_[t] = kWakes;
      return;
    }
    if (begin == end) {
      quiet_[t] = 0;  // empty: a point entering starts the count afresh
      return;
    }
    bool fast = near_[t];
    for (int q = begin; q < end && !fast; ++q) {
      const int p = T.order[q];
      fast = P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p] > speed2;
    }
    quiet_[t] = fast ? 0 : quiet_[t] + dt;
    if (quiet_[t] >= def_.time) change_[t] = kSleeps;
  });
  std::fill(near_.begin(), near_.end(), 0);
  bool changed = false;
  for (std::size_t t = 0; t < asleep_.size(); ++t) {
    if (change_[t] == kWakes) {
      asleep_[t] = 0;
      moved_[t] = 0;
      quiet_[t] = 0;
      for (int q = sleepers_.start[t]; q < sleepers_.mpm_end[t]; ++q)
        P.asleep[sleepers_.order[q]] = 0;
      changed = true;
    } else if (change_[t] == kSleeps) {
      asleep_[t] = 1;
      for (int q = T.start[t]; q < T.mpm_end[t]; ++q) {
        // At rest: a sleeper holds no momentum, and its stress stays as it is.
        const int p = T.order[q];
        P.asleep[p] = 1;
        for (auto* c :
             {&P.vx, &P.vy, &P.bxx, &P.bxy, &P.byx, &P.byy, &P.lxx, &P.lxy, &P.lyx, &P.lyy})
          (*c)[p] = 0;
      }
      changed = true;
    }
  }
  if (changed) rebuild(P, kernel);
  return changed;
}

void Sleep::rebuild(const Particles& P, KernelType kernel) {
  ++generation_;
  const long n = static_cast<long>(P.size());
  sleeping_points_ = 0;
  for (long p = 0; p < n; ++p) sleeping_points_ += P.asleep[p];
  runs_.clear();
  if (!on()) return;
  share_.forEachField([](std::vector<Real>& a) { std::fill(a.begin(), a.end(), Real(0)); });
  if (sleeping_points_ == 0) return;
  // The share: P2G of the sleepers alone, mass and the internal force of their stress (their
  // momentum is zero); always the whole of it, so that it depends on the points only.
  sleepers_.bin(P, share_, true);
  detail::particleToGrid(kernel, {true, true, false}, P, share_, sleepers_);
  for (long p = 0; p < n;) {
    if (P.asleep[p]) {
      ++p;
      continue;
    }
    const long begin = p;
    while (p < n && !P.asleep[p] && p - begin < kRun) ++p;
    runs_.push_back({begin, p});
  }
}

void Sleep::addMass(Grid& G, int first, int end) const {
  const Real* m = share_.mass.data();
  Real* gm = G.mass.data();
#pragma omp simd
  for (int i = first; i < end; ++i) gm[i] += m[i];
}

void Sleep::addForce(Grid& G, int first, int end) const {
  const Real *fx = share_.force_x.data(), *fy = share_.force_y.data();
  Real *gx = G.force_x.data(), *gy = G.force_y.data();
#pragma omp simd
  for (int i = first; i < end; ++i) {
    gx[i] += fx[i];
    gy[i] += fy[i];
  }
}

}  // namespace mpm_sdem
