#include "mpm_sdem/core/mpm/volume_fit.hpp"

#include <algorithm>
#include <cmath>

#include "mpm_sdem/core/sph/sph.hpp"
#include "transfer.hpp"

namespace mpm_sdem {

namespace {

// Every node's 1D capacity on [lo, hi] (grid units from node 0; times h): its weight summed
// over a regular lattice of `per_cell` points per cell, each standing for h / per_cell, as the
// bodies are filled (fillPoints). So a lattice that fills the domain is exactly at capacity,
// also at a wall, where the lattice's sum differs from the weight's integral (for the quadratic
// B-spline at 2 points per cell, by 1/192 of a cell at the node next to the wall).
template <class K>
std::vector<Real> capacities(int nodes, Real lo, Real hi, Real h, int per_cell) {
  std::vector<Real> c(nodes, 0);
  const long n = std::lround((hi - lo) * per_cell);
  const Real step = (hi - lo) / n;
  for (long k = 0; k < n; ++k) {
    Stencil1D s;
    K::stencil(lo + (k + Real(0.5)) * step, 0, s);
    for (int a = 0; a < K::kSupport; ++a)
      if (s.base + a >= 0 && s.base + a < nodes) c[s.base + a] += s.w[a] * step * h;
  }
  return c;
}

// The point's shear rate gamma_dot = sqrt(2 dev D : dev D), D = sym(L), 2D deviator: |du/dy|
// in simple shear, 0 in any rigid motion or isotropic expansion.
inline Real shearRate(const Particles& P, long p) {
  const Real a = P.lxx[p] - P.lyy[p], b = P.lxy[p] + P.lyx[p];
  return std::sqrt(a * a + b * b);
}

}  // namespace

void VolumeFit::init(const Grid& g, KernelType kernel, const Vec2& lo, const Vec2& hi,
                     bool periodic_x, int points_per_cell) {
  kernel_ = kernel;
  lo_ = lo;
  hi_ = hi;
  periodic_x_ = periodic_x;
  const Vec2 a = (lo - g.origin) * g.inv_h, b = (hi - g.origin) * g.inv_h;
  detail::withKernel(kernel, [&](auto k) {
    using K = decltype(k);
    capacity_x_ = capacities<K>(g.nx, a.x(), b.x(), g.h, points_per_cell);
    capacity_y_ = capacities<K>(g.ny, a.y(), b.y(), g.h, points_per_cell);
  });
  // Periodic in x: every column's support lies whole in the domain (its far part is the other
  // side's, which Grid::foldPeriodicX adds).
  if (periodic_x) std::fill(capacity_x_.begin(), capacity_x_.end(), g.h);
}

VolumeFit::Result VolumeFit::measure(const Particles& P, const Grid& g) {
  Result r;
  detail::withKernel(
      kernel_, [&](auto k) { r = run<decltype(k)>(const_cast<Particles&>(P), g, nullptr, 0); });
  return r;
}

VolumeFit::Result VolumeFit::fit(Particles& P, const Grid& g, const std::vector<char>& flows,
                                 Real dt) {
  Result r;
  detail::withKernel(kernel_, [&](auto k) { r = run<decltype(k)>(P, g, &flows, dt); });
  return r;
}

// One pass over the points for the nodes' volumes, one for the gradient g_p = dPhi / dx_p =
// V_p sum_i H_i grad S_ip, one for the linearised change of the over-fill along -g, one to move.
// Serial: the sums are in the points' order on any number of threads.
template <class K>
VolumeFit::Result VolumeFit::run(Particles& P, const Grid& g, const std::vector<char>* flows,
                                 Real dt) {
  constexpr int S = K::kSupport;
  const long n = static_cast<long>(P.size());
  const int nx = g.nx;
  Result r;
  fill_.assign(g.nodeCount(), 0);
  auto weights = [&](long p, Stencil1D& sx, Stencil1D& sy) {
    Real xg, yg;
    detail::stencils<K>(g, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
  };
  for (long p = 0; p < n; ++p) {
    if (P.kind[p] != kMaterialPoint) continue;
    const Real v = P.volume0[p] * P.J[p];
    Stencil1D sx, sy;
    weights(p, sx, sy);
    for (int b = 0; b < S; ++b)
      for (int a = 0; a < S; ++a) fill_[g.index(sx.base + a, sy.base + b)] += v * sx.w[a] * sy.w[b];
  }
  if (periodic_x_) g.foldPeriodicX(fill_);
  // H_i in place of v_i, and the largest over a full node's capacity h^2 (a node at a wall has a
  // sliver of it, 1/64 h^2 beyond the base, which the wall's elastic strain alone would fill
  // 0.1% over). Nodes outside the domain have no capacity (and no volume).
  const Real full = g.h * g.h;
  for (int j = 0; j < g.ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      Real& f = fill_[g.index(i, j)];
      const Real c = capacity(i, j);
      f = c > 0 && f > c ? f - c : Real(0);
      r.largest_overfill = std::max(r.largest_overfill, f / full);
    }
  }
  if (!flows || r.largest_overfill == 0) return r;

  // Which points move: awake material points of a flowing material that shear.
  auto moves = [&](long p) {
    return P.kind[p] == kMaterialPoint && !P.asleep[p] && (*flows)[P.material[p]] &&
           shearRate(P, p) > 0;
  };
  gx_.assign(n, 0);
  gy_.assign(n, 0);
  Real along = 0;  // |g|^2
  for (long p = 0; p < n; ++p) {
    if (!moves(p)) continue;
    const Real v = P.volume0[p] * P.J[p];
    Stencil1D sx, sy;
    weights(p, sx, sy);
    Real hx = 0, hy = 0;
    for (int b = 0; b < S; ++b)
      for (int a = 0; a < S; ++a) {
        const Real H = fill_[g.index(sx.base + a, sy.base + b)];
        hx += H * sx.dw[a] * sy.w[b];
        hy += H * sx.w[a] * sy.dw[b];
      }
    gx_[p] = v * hx * g.inv_h;
    gy_[p] = v * hy * g.inv_h;
    along += gx_[p] * gx_[p] + gy_[p] * gy_[p];
  }
  if (!(along > 0)) return r;
  // The over-fill's rate of change along -g: (J g)_i = sum_p V_p grad S_ip . g_p.
  push_.assign(g.nodeCount(), 0);
  for (long p = 0; p < n; ++p) {
    if (gx_[p] == 0 && gy_[p] == 0) continue;
    const Real v = P.volume0[p] * P.J[p] * g.inv_h;
    Stencil1D sx, sy;
    weights(p, sx, sy);
    for (int b = 0; b < S; ++b)
      for (int a = 0; a < S; ++a)
        push_[g.index(sx.base + a, sy.base + b)] +=
            v * (sx.dw[a] * sy.w[b] * gx_[p] + sx.w[a] * sy.dw[b] * gy_[p]);
  }
  if (periodic_x_) g.foldPeriodicX(push_);
  // Gauss-Newton along -g on the over-filled nodes (each counted once when periodic):
  // min_s |H - s J g|^2 gives s = (J^T H . g) / |J g|^2 = |g|^2 / |J g|^2.
  Real across = 0;
  const int first = periodic_x_ ? Grid::kPad : 0, last = periodic_x_ ? Grid::kPad + g.cells_x : nx;
  for (int j = 0; j < g.ny; ++j)
    for (int i = first; i < last; ++i) {
      const int k = g.index(i, j);
      if (fill_[k] > 0) across += push_[k] * push_[k];
    }
  if (!(across > 0)) return r;
  const Real s = along / across;
  const Real width = hi_.x() - lo_.x();
  for (long p = 0; p < n; ++p) {
    if (gx_[p] == 0 && gy_[p] == 0) continue;
    Real dx = -s * gx_[p], dy = -s * gy_[p];
    // At most as far as the neighbours shear past the point in this step.
    const Real reach = std::sqrt(P.volume0[p] * P.J[p]) * shearRate(P, p) * dt;
    const Real length = std::hypot(dx, dy);
    if (!(length <= reach)) {
      const Real scale = reach / length;  // not finite, or NaN, when either is: the point stays
      if (!(scale >= 0 && std::isfinite(scale))) continue;
      dx *= scale, dy *= scale;
    }
    Real x = P.x[p] + dx, y = P.y[p] + dy;
    if (periodic_x_) x = x < lo_.x() ? x + width : x >= hi_.x() ? x - width : x;
    P.x[p] = std::clamp(x, lo_.x(), hi_.x());
    P.y[p] = std::clamp(y, lo_.y(), hi_.y());
    ++r.moved;
  }
  return r;
}

}  // namespace mpm_sdem
