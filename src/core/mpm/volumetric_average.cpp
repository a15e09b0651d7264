#include "mpm_sdem/core/mpm/volumetric_average.hpp"

#include <algorithm>

#include "mpm/transfer.hpp"
#include "parallel.hpp"

namespace mpm_sdem {

namespace {

template <class K>
void averageDivergence(Particles& P, const Grid& G, const Tiles& T, std::vector<Real>& volume,
                       std::vector<Real>& rate) {
  constexpr int S = K::kSupport;
  const Real inv_h = G.inv_h;
  auto forNodes = [&](long p, auto&& f) {
    Real xg, yg;
    Stencil1D sx, sy;
    detail::stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i)
        f(G.index(sx.base + i, sy.base + j), sx.w[i] * sy.w[j],
          Vec2(sx.dw[i] * sy.w[j], sx.w[i] * sy.dw[j]) * inv_h);
  };
  // L_p = sum_I v_I (grad S_Ip)^T (seed 000 eq. 21-22), from the pre-kick velocity.
  auto gradient = [&](long p) {
    Real lxx = 0, lxy = 0, lyx = 0, lyy = 0;
    forNodes(p, [&](int n, Real, const Vec2& g) {
      lxx += G.vel0_x[n] * g.x();
      lxy += G.vel0_x[n] * g.y();
      lyx += G.vel0_y[n] * g.x();
      lyy += G.vel0_y[n] * g.y();
    });
    P.lxx[p] = lxx, P.lxy[p] = lxy, P.lyx[p] = lyx, P.lyy[p] = lyy;
  };
  std::fill(volume.begin(), volume.end(), Real(0));
  std::fill(rate.begin(), rate.end(), Real(0));
  // Gradients and the nodes' sums, coloured as P2G (no two tiles of a colour share a node).
  detail::forEachTileByColour(T, [&](int t) {
    for (int q = T.start[t]; q < T.mpm_end[t]; ++q) {
      const int p = T.order[q];
      gradient(p);
      const Real v = P.volume0[p] * P.J[p], d = P.lxx[p] + P.lyy[p];
      forNodes(p, [&](int n, Real w, const Vec2&) {
        volume[n] += w * v;
        rate[n] += w * v * d;
      });
    }
  });
  // Back to the points: only the divergence changes.
  detail::forEachTileByColour(T, [&](int t) {
    for (int q = T.start[t]; q < T.mpm_end[t]; ++q) {
      const int p = T.order[q];
      Real mean = 0;
      forNodes(p, [&](int n, Real w, const Vec2&) {
        if (volume[n] > 0) mean += w * rate[n] / volume[n];
      });
      const Real shift = Real(0.5) * (mean - (P.lxx[p] + P.lyy[p]));
      P.lxx[p] += shift;
      P.lyy[p] += shift;
    }
  });
}

}  // namespace

void VolumetricAverage::apply(KernelType kernel, Particles& P, const Grid& G, const Tiles& T) {
  const std::size_t nodes = G.mass.size();
  volume_.resize(nodes);
  rate_.resize(nodes);
  detail::withKernel(kernel,
                     [&](auto k) { averageDivergence<decltype(k)>(P, G, T, volume_, rate_); });
}

}  // namespace mpm_sdem
