#include "sph/sph_step.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "sph/sph_kernel.hpp"

namespace mpm_sdem {

const char* sphKernelName(SphKernel k) {
  return k == SphKernel::kWendlandC2 ? "wendland_c2" : "cubic_spline";
}

Problem sphProblem(const SphDef& d, Real cell_size) {
  // h_s in [0.5, 1.5] cells: the kernel reaches 2 h_s, and the tiles (3 cells) are its cell list.
  const Real hs = d.smoothing_length > 0 ? d.smoothing_length : cell_size;
  const limits::Range cells{0.5 * cell_size, 0.5 * Tiles::kSize * cell_size * (1 + 1e-12), "m"};
  if (Problem p = limits::rangeProblem(hs, cells); !p.empty())
    return {"smoothing_length",
            p.message +
                " (0.5 to 1.5 cells: the kernel reaches twice it, and the grid's tiles of 3 "
                "cells are its cell list)"};
  if (Problem p = limits::rangeProblem(d.viscosity_alpha, limits::kArtificialViscosity); !p.empty())
    return p.under("viscosity_alpha");
  if (Problem p = limits::rangeProblem(d.viscosity_beta, limits::kArtificialViscosity); !p.empty())
    return p.under("viscosity_beta");
  return {};
}

}  // namespace mpm_sdem

namespace mpm_sdem::detail {

void SphColumns::resize(std::size_t n) {
  for (auto* c : {&cxx, &cxy, &cyx, &cyy, &ax, &ay}) c->resize(n, 0);
}

void assignKinds(const std::vector<ShapeDef>& regions, const std::vector<char>& sph_body,
                 Particles& P) {
  const long n = static_cast<long>(P.size());
#pragma omp parallel for schedule(static)
  for (long p = 0; p < n; ++p) {
    bool sph = sph_body[P.body[p]] != 0;
    for (std::size_t r = 0; !sph && r < regions.size(); ++r)
      sph = contains(regions[r], Vec2(P.x[p], P.y[p]));
    const std::uint8_t kind = sph ? kSphParticle : kMaterialPoint;
    if (kind == P.kind[p]) continue;
    P.kind[p] = kind;
    P.bxx[p] = P.bxy[p] = P.byx[p] = P.byy[p] = 0;
  }
}

namespace {

// Call f(t) for each tile within one of tile t (the 3 x 3 block around it).
template <class F>
void forNeighbourTiles(const Tiles& T, int t, F&& f) {
  const int a = t % T.nx, b = t / T.nx;
  for (int j = std::max(b - 1, 0); j <= std::min(b + 1, T.ny - 1); ++j)
    for (int i = std::max(a - 1, 0); i <= std::min(a + 1, T.nx - 1); ++i) f(i + j * T.nx);
}

bool hasPoints(const Tiles& T, int t) {
  return T.start[t] < T.mpm_end[t];
}
bool hasSph(const Tiles& T, int t) {
  return T.mpm_end[t] < T.start[t + 1];
}
bool near(const Tiles& T, int t, bool (*what)(const Tiles&, int)) {
  bool found = false;
  forNeighbourTiles(T, t, [&](int u) { found = found || what(T, u); });
  return found;
}

// Call f(b, dx, dy, grad_x, grad_y) for every particle b != a within the support of particle a
// ((dx, dy) = x_a - x_b, grad W_ab with respect to x_a). The tiles are the cell list (R <= kSize
// cells): only those the support's bounding box overlaps are read, 2 x 2 to 3 x 3 of them.
template <class K, class F>
void forNeighbours(const Particles& P, const Tiles& T, const Grid& G, int a, Real R, F&& f) {
  const Real xa = P.x[a], ya = P.y[a], R2 = R * R;
  const Real scale = G.inv_h / Tiles::kSize;  // tiles per metre
  const int i0 = std::max(static_cast<int>((xa - R - G.origin.x()) * scale), 0);
  const int i1 = std::min(static_cast<int>((xa + R - G.origin.x()) * scale), T.nx - 1);
  const int j0 = std::max(static_cast<int>((ya - R - G.origin.y()) * scale), 0);
  const int j1 = std::min(static_cast<int>((ya + R - G.origin.y()) * scale), T.ny - 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      const int u = i + j * T.nx;
      for (int q = T.start[u]; q < T.start[u + 1]; ++q) {
        const int b = T.order[q];
        const Real dx = xa - P.x[b], dy = ya - P.y[b], r2 = dx * dx + dy * dy;
        // A coincident pair (two points clamped into one corner) has no direction, and both
        // kernels' gradients vanish at r = 0: skipped, as a itself.
        if (r2 >= R2 || !(r2 > 0)) continue;
        const Real r = std::sqrt(r2);
        const KernelValue k = K::eval(r, R);
        f(b, dx, dy, k.dw * dx / r, k.dw * dy / r);
      }
    }
  }
}

// Run f(a) for every SPH particle, the tiles shared among the threads (each particle writes
// only its own columns).
template <class F>
void forEachSph(const Tiles& T, F&& f) {
  const long tiles = static_cast<long>(T.start.size()) - 1;
#pragma omp parallel for schedule(dynamic, 16)
  for (long t = 0; t < tiles; ++t)
    for (int q = T.mpm_end[t]; q < T.start[t + 1]; ++q) f(T.order[q]);
}

// The correction C_a = rho_a M^-T is applied where det(M) / rho_a^2 (1 with a full kernel
// support, about 0.5 in a strip two points thick) exceeds this; below it M is nearly singular
// (a point alone, a single row) and the plain gradient is used. (At 0.3 the thin bar of seed 001
// sec. 5.2 lost its correction and came 35% off.)
constexpr Real kMinCorrectedDet = 1e-3;

Real density(const Particles& P, int p) {
  return P.mass[p] / (P.volume0[p] * P.J[p]);
}

}  // namespace

void markBand(const Particles& P, const Grid& G, KernelType kernel, Tiles& T,
              std::vector<std::uint32_t>& stamp, std::uint32_t now) {
  const int tiles = T.nx * T.ny;
  stamp.resize(G.nodeCount(), 0);
  withKernel(kernel, [&](auto k) {
    using K = decltype(k);
    auto forStencil = [&](int p, auto&& f) {
      Real xg, yg;
      Stencil1D sx, sy;
      stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
      for (int j = 0; j < K::kSupport; ++j)
        for (int i = 0; i < K::kSupport; ++i) f((sy.base + j) * G.nx + sx.base + i);
    };
    // Nodes reached by the material points that have SPH particles near (only there can an SPH
    // particle reach the same node); serial, since neighbouring points share nodes.
    for (int t = 0; t < tiles; ++t) {
      if (!hasPoints(T, t) || !near(T, t, hasSph)) continue;
      for (int q = T.start[t]; q < T.mpm_end[t]; ++q)
        forStencil(T.order[q], [&](int node) { stamp[node] = now; });
    }
    // Within each tile, the SPH particles reaching such a node first (in their order).
#pragma omp parallel
    {
      std::vector<int> rest;
#pragma omp for schedule(dynamic, 16)
      for (int t = 0; t < tiles; ++t) {
        int end = T.mpm_end[t];
        if (!hasSph(T, t) || !near(T, t, hasPoints)) {
          T.grid_end[t] = end;
          continue;
        }
        rest.clear();
        for (int q = T.mpm_end[t]; q < T.start[t + 1]; ++q) {
          const int p = T.order[q];
          bool reached = false;
          forStencil(p, [&](int node) { reached = reached || stamp[node] == now; });
          if (reached)
            T.order[end++] = p;
          else
            rest.push_back(p);
        }
        T.grid_end[t] = end;
        std::copy(rest.begin(), rest.end(), T.order.begin() + end);
      }
    }
  });
}

void sphVelocityGradient(Particles& P, const Tiles& T, const Grid& G, const SphSettings& s,
                         const std::vector<MaterialParams>& materials, Real stress_dt,
                         SphColumns& c, SphPairs& pairs) {
  pairs.lists.resize(static_cast<std::size_t>(omp_get_max_threads()));
  for (auto& l : pairs.lists) l.pairs.clear();  // their capacity stays: no allocation once grown
  for (auto* v : {&pairs.list, &pairs.start, &pairs.count}) v->resize(P.size());
  withSphKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    forEachSph(T, [&](int a) {
      const int thread = omp_get_thread_num();
      std::vector<SphPairs::Pair>& list = pairs.lists[thread].pairs;
      pairs.list[a] = thread;
      pairs.start[a] = static_cast<int>(list.size());
      // A = sum_b m_b (v_b - v_a) (x) grad W and M = sum_b m_b (x_b - x_a) (x) grad W: for a
      // linear field v = L0 x, A = L0 M, so L = A M^-1 is exact wherever M is invertible (Bonet
      // and Lok 1999). Without the correction L = A / rho_a: eq. 2.9 with the volume m_b / rho_a
      // (the seed writes m_b / rho_b; with rho_a the work of eq. 2.6's forces equals the stress
      // power exactly, and for equal densities the two agree).
      const Real vxa = P.vx[a], vya = P.vy[a];
      Real axx = 0, axy = 0, ayx = 0, ayy = 0, mxx = 0, mxy = 0, myx = 0, myy = 0;
      forNeighbours<K>(P, T, G, a, s.support, [&](int b, Real dx, Real dy, Real gx, Real gy) {
        list.push_back({b, gx, gy});
        const Real m = P.mass[b], dvx = P.vx[b] - vxa, dvy = P.vy[b] - vya;
        axx += m * dvx * gx;
        axy += m * dvx * gy;
        ayx += m * dvy * gx;
        ayy += m * dvy * gy;
        // x_b - x_a = -(dx, dy)
        mxx -= m * dx * gx;
        mxy -= m * dx * gy;
        myx -= m * dy * gx;
        myy -= m * dy * gy;
      });
      pairs.count[a] = static_cast<int>(list.size()) - pairs.start[a];
      const Real rho = density(P, a);
      const Real det = mxx * myy - mxy * myx;
      const bool corrected = s.corrected && det > kMinCorrectedDet * rho * rho;
      if (corrected) {
        // L = A M^-1; C_a = rho_a M^-T, so that L = sum_b (m_b / rho_a) dv (x) C_a grad W.
        const Real ixx = myy / det, ixy = -mxy / det, iyx = -myx / det, iyy = mxx / det;
        P.lxx[a] = axx * ixx + axy * iyx;
        P.lxy[a] = axx * ixy + axy * iyy;
        P.lyx[a] = ayx * ixx + ayy * iyx;
        P.lyy[a] = ayx * ixy + ayy * iyy;
        c.cxx[a] = rho * ixx;
        c.cxy[a] = rho * iyx;
        c.cyx[a] = rho * ixy;
        c.cyy[a] = rho * iyy;
      } else {
        P.lxx[a] = axx / rho;
        P.lxy[a] = axy / rho;
        P.lyx[a] = ayx / rho;
        P.lyy[a] = ayy / rho;
        c.cxx[a] = c.cyy[a] = 1;
        c.cxy[a] = c.cyx[a] = 0;
      }
      if (stress_dt != 0) updatePointStress(materials[P.material[a]], P, a, stress_dt);
    });
  });
}

Real sphAcceleration(const Particles& P, const Tiles& T, const SphSettings& s,
                     const std::vector<MaterialParams>& materials, const Vec2& gravity,
                     SphColumns& c, const SphPairs& pairs) {
  Real mu_max = 0;
  {
    const Real hs = s.smoothingLength(), eps = Real(0.01) * hs * hs;
    const long tiles = static_cast<long>(T.start.size()) - 1;
#pragma omp parallel for schedule(dynamic, 16) reduction(max : mu_max)
    for (long t = 0; t < tiles; ++t) {
      for (int q = T.mpm_end[t]; q < T.start[t + 1]; ++q) {
        const int a = T.order[q];
        const Real rho_a = density(P, a), inv_a = 1 / (rho_a * rho_a);
        const Real sxx_a = P.sxx[a] * inv_a, syy_a = P.syy[a] * inv_a, sxy_a = P.sxy[a] * inv_a;
        const Real ca = std::sqrt(squaredWaveSpeed(materials[P.material[a]], P.J[a]));
        const Real cxx = c.cxx[a], cxy = c.cxy[a], cyx = c.cyx[a], cyy = c.cyy[a];
        Real fx = 0, fy = 0;
        const SphPairs::Pair* pair = pairs.lists[pairs.list[a]].pairs.data() + pairs.start[a];
        const Real xa = P.x[a], ya = P.y[a];  // x_a - x_b as the first pass computed it
        for (int n = 0; n < pairs.count[a]; ++n) {
          const int b = pair[n].b;
          const Real dx = xa - P.x[b], dy = ya - P.y[b], gx = pair[n].gx, gy = pair[n].gy;
          // C_a grad W and C_b grad W (a material point borrows C_a: it has no correction of
          // its own, and is not moved by these forces).
          const Real gax = cxx * gx + cxy * gy, gay = cyx * gx + cyy * gy;
          Real gbx = gax, gby = gay;
          if (P.kind[b] == kSphParticle) {
            gbx = c.cxx[b] * gx + c.cxy[b] * gy;
            gby = c.cyx[b] * gx + c.cyy[b] * gy;
          }
          const Real rho_b = density(P, b), inv_b = 1 / (rho_b * rho_b);
          // Eq. 2.6: sigma_a / rho_a^2 C_a grad W + sigma_b / rho_b^2 C_b grad W; the pair's
          // terms are opposite for a and b, so momentum is conserved.
          Real tx = sxx_a * gax + sxy_a * gay + inv_b * (P.sxx[b] * gbx + P.sxy[b] * gby);
          Real ty = sxy_a * gax + syy_a * gay + inv_b * (P.sxy[b] * gbx + P.syy[b] * gby);
          // Eq. 2.7-2.8 for approaching pairs, a pressure Pi_ab on both (the seed prints it
          // added to sigma; with tension positive it must be subtracted to resist the
          // approach).
          const Real vdotx = (P.vx[a] - P.vx[b]) * dx + (P.vy[a] - P.vy[b]) * dy;
          if (vdotx < 0 && (s.alpha > 0 || s.beta > 0)) {
            const Real mu = hs * vdotx / (dx * dx + dy * dy + eps);
            const Real cb = std::sqrt(squaredWaveSpeed(materials[P.material[b]], P.J[b]));
            const Real pi = (-s.alpha * Real(0.5) * (ca + cb) * mu + s.beta * mu * mu) /
                            (Real(0.5) * (rho_a + rho_b));
            tx -= Real(0.5) * pi * (gax + gbx);
            ty -= Real(0.5) * pi * (gay + gby);
            mu_max = std::fmax(mu_max, -mu);
          }
          fx += P.mass[b] * tx;
          fy += P.mass[b] * ty;
        }
        c.ax[a] = fx + gravity.x();
        c.ay[a] = fy + gravity.y();
      }
    }
  }
  return mu_max;
}

void sphKickDrift(Particles& P, const Tiles& T, const SphColumns& c, Real kick, Real damping,
                  const G2PSettings& s, long& clamped, bool& finite) {
  const long tiles = static_cast<long>(T.start.size()) - 1;
  long clamped_count = 0;
  int bad = 0;
#pragma omp parallel for schedule(static) reduction(+ : clamped_count) reduction(| : bad)
  for (long t = 0; t < tiles; ++t) {
    for (int q = T.mpm_end[t]; q < T.start[t + 1]; ++q) {
      const int a = T.order[q];
      const Real ax = localDamping(c.ax[a], P.vx[a], damping);
      const Real ay = localDamping(c.ay[a], P.vy[a], damping);
      P.vx[a] += kick * ax;
      P.vy[a] += kick * ay;
      moveInside(P, a, s, P.vx[a], P.vy[a], clamped_count, bad);
    }
  }
  clamped += clamped_count;
  if (bad) finite = false;
}

Real sphSignalSpeed(const Particles& P, const Tiles& T, const SphSettings& s,
                    const std::vector<MaterialParams>& materials, Real mu_max) {
  const long tiles = static_cast<long>(T.start.size()) - 1;
  Real fastest = 0;
#pragma omp parallel for schedule(static) reduction(max : fastest)
  for (long t = 0; t < tiles; ++t) {
    for (int q = T.mpm_end[t]; q < T.start[t + 1]; ++q) {
      const int a = T.order[q];
      const Real c = std::sqrt(squaredWaveSpeed(materials[P.material[a]], P.J[a]));
      const Real v = std::sqrt(P.vx[a] * P.vx[a] + P.vy[a] * P.vy[a]);
      const Real speed = c + v + Real(1.2) * (s.alpha * c + s.beta * mu_max);
      fastest = speed > fastest ? speed : fastest;
    }
  }
  return fastest;
}

}  // namespace mpm_sdem::detail
