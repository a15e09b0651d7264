// The point sweeps of sweeps.hpp for every SIMD target Highway compiles here, and the run-time
// choice among them (hwy/foreach_target.h re-includes this file, and node_rows.hpp with it, once
// per target). The sweeps' vectors are GCC's (node_rows.hpp: a row of four nodes): inside
// HWY_BEFORE_NAMESPACE the compiler lowers them, and the functions of transfer.hpp and
// constitutive.hpp they inline, to the target's instructions (AVX-512, AVX2, SSE4, SSE2). The
// colour loops (forEachTileByColour) stay baseline code and call each tile's work.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mpm/sweeps.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include "hwy/highway.h"
#include "mpm/node_rows.hpp"
#include "mpm/transfer.hpp"

HWY_BEFORE_NAMESPACE();
namespace mpm_sdem::detail::HWY_NAMESPACE {

// Point p's stencils as the particle sweeps take them: along x a four-node window
// (node_rows.hpp), along y the kernel's own stencil; yg is the point's y in grid units.
template <class K>
[[gnu::always_inline]] inline void sweepStencils(const Grid& g, const Particles& P, long p,
                                                 Real& yg, Window& sx, Stencil1D& sy) {
  yg = (P.y[p] - g.origin.y()) * g.inv_h;
  sx = window<K>((P.x[p] - g.origin.x()) * g.inv_h, P.half_size[p]);
  K::stencil(yg, P.half_size[p], sy);
}

// P2G: nodal mass (eq. 18), momentum (eq. 19, or eq. 30 with the APIC affine term) and internal
// force f_I = -sum_p V_p sigma_p grad S_Ip (eq. 13). Gravity is added on the grid (eq. 14 with a
// uniform body force equals m_I g).
// The SPH particles of the transition band lend the nodes the affine velocity field their own
// velocity gradient gives, v_p + L_p (x_I - x_p), in every transfer scheme: without it the
// band's nodes see a velocity field smoothed towards the particles' (the coupled bar of seed
// 001 sec. 5.2 came to a strain 2.4% short; with it, 0.01%).
enum AffineSource { kNoAffine, kAffineFromB, kAffineFromL };

template <class K, bool kApic, bool kMomentum, bool kForce>
void particleToGrid(const Particles& P, Grid& G, const Tiles& T) {
  constexpr int S = K::kSupport;
  const Real h = G.h, inv_h = G.inv_h;
  const int nx = G.nx;
  Real* gm = G.mass.data();
  Real* gpx = G.mom_x.data();
  Real* gpy = G.mom_y.data();
  Real* gfx = G.force_x.data();
  Real* gfy = G.force_y.data();
  // Inlined into the tile loop (always_inline): the compiler then keeps the columns' addresses
  // in registers across points instead of reloading them through the closure for each one.
  auto deposit = [&](int p, auto source) __attribute__((always_inline)) {
    constexpr AffineSource kAffine = decltype(source)::value;
    Real yg;
    Window sx;  // x: one vector per row
    Stencil1D sy;
    sweepStencils<K>(G, P, p, yg, sx, sy);
    const Real m = P.mass[p];
    const Real mvx = m * P.vx[p], mvy = m * P.vy[p];
    // m C (x_I - x_p) with offsets in grid units r h: APIC's C = B D^-1 with D = diag(second
    // moments) h^2, or an SPH particle's C = L.
    Real cxx = 0, cxy = 0, cyx = 0, cyy = 0;
    if constexpr (kAffine == kAffineFromB) {
      const Real ax = m * inv_h / sx.second_moment, ay = m * inv_h / sy.second_moment;
      cxx = P.bxx[p] * ax;
      cxy = P.bxy[p] * ay;
      cyx = P.byx[p] * ax;
      cyy = P.byy[p] * ay;
    } else if constexpr (kAffine == kAffineFromL) {
      const Real a = m * h;
      cxx = P.lxx[p] * a;
      cxy = P.lxy[p] * a;
      cyx = P.lyx[p] * a;
      cyy = P.lyy[p] * a;
    }
    Real sxx = 0, syy = 0, sxy = 0;
    if (kForce) {
      const Real vol = P.volume0[p] * P.J[p] * inv_h;
      sxx = vol * P.sxx[p];
      syy = vol * P.syy[p];
      sxy = vol * P.sxy[p];
    }
    const Row4 px = mvx + cxx * sx.r, py = mvy + cyx * sx.r;  // the row-independent part
    for (int j = 0; j < S; ++j) {
      const Real wy = sy.w[j], dwy = sy.dw[j];
      const Real ry = (sy.base + j) - yg;
      const int row = (sy.base + j) * nx + sx.first;
      const Row4 w = sx.w * wy;
      if (kMomentum) {
        storeRow(gm + row, loadRow(gm + row) + w * m);
        storeRow(gpx + row, loadRow(gpx + row) + w * (px + cxy * ry));
        storeRow(gpy + row, loadRow(gpy + row) + w * (py + cyy * ry));
      }
      if (kForce) {
        const Row4 gx = sx.dw * wy, gy = sx.w * dwy;
        storeRow(gfx + row, loadRow(gfx + row) - (sxx * gx + sxy * gy));
        storeRow(gfy + row, loadRow(gfy + row) - (sxy * gx + syy * gy));
      }
    }
  };
  using Points = std::integral_constant<AffineSource, kApic ? kAffineFromB : kNoAffine>;
  using Band = std::integral_constant<AffineSource, kAffineFromL>;
  forEachTileByColour(T, [&](int t) {
    for (int q = T.start[t]; q < T.mpm_end[t]; ++q) deposit(T.order[q], Points{});
    for (int q = T.mpm_end[t]; q < T.grid_end[t]; ++q) deposit(T.order[q], Band{});
  });
}

// The middle of a USF step (seed 000 sec. 2.2) in one sweep per point, coloured like P2G: the
// velocity gradient L_p = sum_I v_I (grad S_Ip)^T from the pre-kick grid velocity (eq. 21-22),
// the stress update over dt with it (skipped when dt = 0, the first step), then the internal
// force of the new stress onto the same nodes (eq. 13).
// The SPH particles of the transition band lend the nodes their stress, which the SPH sums
// updated (seed 001 sec. 4). With side walls, the new pressure's wall load onto the same nodes
// (sidewallForce in transfer.hpp): one pass over the points instead of two.
template <class K>
void stressAndInternalForce(Particles& P, Grid& G, const Tiles& T,
                            const std::vector<MaterialParams>& materials, Real dt,
                            SidewallLoad walls) {
  constexpr int S = K::kSupport;
  const Real inv_h = G.inv_h;
  const int nx = G.nx;
  const Real* vx0 = G.vel0_x.data();
  const Real* vy0 = G.vel0_y.data();
  Real* gfx = G.force_x.data();
  Real* gfy = G.force_y.data();
  // A point's weights, all its internal force needs (held while the point waits in a batch).
  struct Weights {
    int first, base;
    Row4 wx, dwx;
    Real wy[S], dwy[S];
  };
  auto weights = [](const Window& sx, const Stencil1D& sy) {
    Weights k{sx.first, sy.base, sx.w, sx.dw, {}, {}};
    for (int j = 0; j < S; ++j) {
      k.wy[j] = sy.w[j];
      k.dwy[j] = sy.dw[j];
    }
    return k;
  };
  auto spreadStress = [&](int p, const Weights& k) {
    const Real vol = P.volume0[p] * P.J[p] * inv_h;
    const Real sxx = vol * P.sxx[p], syy = vol * P.syy[p], sxy = vol * P.sxy[p];
    for (int j = 0; j < S; ++j) {
      const int row = (k.base + j) * nx + k.first;
      const Row4 gx = k.dwx * k.wy[j], gy = k.wx * k.dwy[j];
      storeRow(gfx + row, loadRow(gfx + row) - (sxx * gx + sxy * gy));
      storeRow(gfy + row, loadRow(gfy + row) - (sxy * gx + syy * gy));
    }
    if (!walls.load) return;
    const Real f = sidewallForce(P, p, walls.coefficient);
    if (!(f > 0)) return;
    for (int j = 0; j < S; ++j) {
      const int row = (k.base + j) * nx + k.first;
      storeRow(walls.load + row, loadRow(walls.load + row) + k.wx * (k.wy[j] * f));
    }
  };
  auto band = [&](int p) {
    Real yg;
    Window sx;
    Stencil1D sy;
    sweepStencils<K>(G, P, p, yg, sx, sy);
    spreadStress(p, weights(sx, sy));
  };
  // A point's L_p, then its stress now (a fluid, or the first step) or, batched with the points
  // of its material, once the batch is full: the batch's points keep their weights until then.
  forEachTileByColour(T, [&](int t) {
    StressBatcher batcher(P, materials, dt);
    Weights held[StressBatch::kSize];
    auto spread = [&](int k, int p) { spreadStress(p, held[k]); };
    for (int q = T.start[t]; q < T.mpm_end[t]; ++q) {
      const int p = T.order[q];
      Real yg;
      Window sx;
      Stencil1D sy;
      sweepStencils<K>(G, P, p, yg, sx, sy);
      Row4 lxx = {}, lxy = {}, lyx = {}, lyy = {};
      for (int j = 0; j < S; ++j) {
        const int row = (sy.base + j) * nx + sx.first;
        const Row4 gx = sx.dw * sy.w[j], gy = sx.w * sy.dw[j];
        const Row4 vx = loadRow(vx0 + row), vy = loadRow(vy0 + row);
        lxx += vx * gx;
        lxy += vx * gy;
        lyx += vy * gx;
        lyy += vy * gy;
      }
      const Row4 l = sums(lxx, lxy, lyx, lyy) * inv_h;
      P.lxx[p] = l[0];
      P.lxy[p] = l[1];
      P.lyx[p] = l[2];
      P.lyy[p] = l[3];
      const MaterialParams& m = materials[P.material[p]];
      if (dt == 0 || !batchesStress(m)) {
        if (dt != 0) updatePointStress(m, P, p, dt);
        spreadStress(p, weights(sx, sy));
        continue;
      }
      held[batcher.add(p, spread)] = weights(sx, sy);
      if (batcher.full()) batcher.flush(spread);
    }
    batcher.flush(spread);
    for (int q = T.mpm_end[t]; q < T.grid_end[t]; ++q) band(T.order[q]);
  });
}

// G2P: PIC velocity (eq. 26), FLIP blend (eq. 28), APIC affine matrix (eq. 31) or both, then
// x_p += dt sum_I S_Ip v_I (the PIC velocity moves the point in every scheme). kGradient (USL):
// also L_p from the post-kick velocity.
// Without SPH particles every point in storage order; with them (T given), the material points
// of each tile.
template <class K, TransferScheme kScheme, bool kGradient>
void gridToParticle(Particles& P, const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T = nullptr) {
  constexpr int S = K::kSupport;
  const long n = static_cast<long>(P.size());
  const Real h = G.h, inv_h = G.inv_h;
  long clamped_count = 0;
  int bad = 0;
  // The reduction's private copies are passed in: a lambda made outside the parallel region
  // would capture the shared ones.
  auto point = [&](long p, long& clamped_here, int& bad_here) __attribute__((always_inline)) {
    Real yg;
    Window sx;
    Stencil1D sy;
    sweepStencils<K>(G, P, p, yg, sx, sy);
    const Row4 rx = sx.r * h;
    Row4 v_x = {}, v_y = {}, dv_x = {}, dv_y = {};
    Row4 b_xx = {}, b_xy = {}, b_yx = {}, b_yy = {};
    Row4 l_xx = {}, l_xy = {}, l_yx = {}, l_yy = {};
    for (int j = 0; j < S; ++j) {
      const Real ry = ((sy.base + j) - yg) * h;
      const int row = (sy.base + j) * G.nx + sx.first;
      const Row4 w = sx.w * sy.w[j];
      const Row4 gvx = loadRow(G.vel_x.data() + row), gvy = loadRow(G.vel_y.data() + row);
      v_x += w * gvx;
      v_y += w * gvy;
      if (kScheme == TransferScheme::kFlip || kScheme == TransferScheme::kAsflip) {
        dv_x += w * (gvx - loadRow(G.vel0_x.data() + row));
        dv_y += w * (gvy - loadRow(G.vel0_y.data() + row));
      }
      if (carriesAffine(kScheme)) {
        b_xx += w * gvx * rx;
        b_xy += w * gvx * ry;
        b_yx += w * gvy * rx;
        b_yy += w * gvy * ry;
      }
      if (kGradient) {
        const Row4 gx = sx.dw * sy.w[j] * inv_h, gy = sx.w * sy.dw[j] * inv_h;
        l_xx += gvx * gx;
        l_xy += gvx * gy;
        l_yx += gvy * gx;
        l_yy += gvy * gy;
      }
    }
    const Row4 v = sums(v_x, v_y, dv_x, dv_y), b = sums(b_xx, b_xy, b_yx, b_yy);
    const Row4 l = sums(l_xx, l_xy, l_yx, l_yy);
    const Real vx = v[0], vy = v[1], dvx = v[2], dvy = v[3];
    const Real bxx = b[0], bxy = b[1], byx = b[2], byy = b[3];
    const Real lxx = l[0], lxy = l[1], lyx = l[2], lyy = l[3];
    if (kScheme == TransferScheme::kFlip) {
      const Real a = s.pic_fraction;
      P.vx[p] = a * vx + (1 - a) * (P.vx[p] + dvx);
      P.vy[p] = a * vy + (1 - a) * (P.vy[p] + dvy);
    } else if (kScheme == TransferScheme::kAsflip) {
      // FLIP's increment (eq. 28 with alpha = 0): the point keeps its own departure from the
      // grid's field, v_p - v^n(x_p), which APIC drops at every transfer (a share lost per
      // step, so a loss that grows as the step shrinks); B below is APIC's, from the grid.
      // With a relaxation time the departure decays by the same factor at every point:
      // sum_p m_p (v_p - v^n(x_p)) = 0 (APIC's transfer keeps momentum), so momentum stays exact.
      if (s.keep < 1) {
        P.vx[p] = vx + s.keep * (P.vx[p] + dvx - vx);
        P.vy[p] = vy + s.keep * (P.vy[p] + dvy - vy);
      } else {
        P.vx[p] += dvx;
        P.vy[p] += dvy;
      }
    } else {
      P.vx[p] = vx;
      P.vy[p] = vy;
    }
    if (carriesAffine(kScheme)) {
      P.bxx[p] = bxx;
      P.bxy[p] = bxy;
      P.byx[p] = byx;
      P.byy[p] = byy;
    }
    if (kGradient) {
      P.lxx[p] = lxx;
      P.lxy[p] = lxy;
      P.lyx[p] = lyx;
      P.lyy[p] = lyy;
    }
    moveInside(P, p, s, vx, vy, clamped_here, bad_here);
  };
  // The points of the grid sums, tile by tile in sorted order, or all in storage order.
  const long count = T ? static_cast<long>(T->start.size()) - 1 : n;
  auto item = [&](long k, long& clamped_here, int& bad_here) __attribute__((always_inline)) {
    if (!T) {
      point(k, clamped_here, bad_here);
      return;
    }
    for (int q = T->start[k]; q < T->mpm_end[k]; ++q) point(T->order[q], clamped_here, bad_here);
  };
  if (singleThread()) {
    for (long k = 0; k < count; ++k) item(k, clamped_count, bad);
  } else {
#pragma omp parallel for schedule(static) reduction(+ : clamped_count) reduction(| : bad)
    for (long k = 0; k < count; ++k) item(k, clamped_count, bad);
  }
  clamped += clamped_count;
  if (bad) finite = false;
}

// The entry points, one per sweep: the scene's kernel and scheme picked once per call.
void ParticleToGrid(KernelType kernel, P2GParts parts, const Particles& P, Grid& G,
                    const Tiles& T) {
  withKernel(kernel, [&](auto k) {
    using K = decltype(k);
    if (parts.momentum && parts.force) {
      parts.affine ? particleToGrid<K, true, true, true>(P, G, T)
                   : particleToGrid<K, false, true, true>(P, G, T);
    } else if (parts.momentum) {
      parts.affine ? particleToGrid<K, true, true, false>(P, G, T)
                   : particleToGrid<K, false, true, false>(P, G, T);
    } else if (parts.force) {
      particleToGrid<K, false, false, true>(P, G, T);
    }
  });
}

void StressAndInternalForce(KernelType kernel, Particles& P, Grid& G, const Tiles& T,
                            const std::vector<MaterialParams>& materials, Real dt,
                            SidewallLoad walls) {
  withKernel(kernel,
             [&](auto k) { stressAndInternalForce<decltype(k)>(P, G, T, materials, dt, walls); });
}

void GridToParticle(KernelType kernel, TransferScheme scheme, bool gradient, Particles& P,
                    const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T) {
  withKernel(kernel, [&](auto k) {
    using K = decltype(k);
    auto run = [&](auto tag) {
      constexpr TransferScheme kScheme = decltype(tag)::value;
      gradient ? gridToParticle<K, kScheme, true>(P, G, s, clamped, finite, T)
               : gridToParticle<K, kScheme, false>(P, G, s, clamped, finite, T);
    };
    switch (scheme) {
      case TransferScheme::kPic:
        run(std::integral_constant<TransferScheme, TransferScheme::kPic>{});
        break;
      case TransferScheme::kFlip:
        run(std::integral_constant<TransferScheme, TransferScheme::kFlip>{});
        break;
      case TransferScheme::kApic:
        run(std::integral_constant<TransferScheme, TransferScheme::kApic>{});
        break;
      case TransferScheme::kAsflip:
        run(std::integral_constant<TransferScheme, TransferScheme::kAsflip>{});
        break;
    }
  });
}

const char* TargetName() {
  return hwy::TargetName(HWY_TARGET);
}

}  // namespace mpm_sdem::detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace mpm_sdem::detail {

#if MPM_SDEM_STATIC_SIMD
// Only the target the compiler flags name (bench/instructions.sh, as in stress_batch.cpp).
#define MPM_SDEM_SWEEP(name) HWY_STATIC_DISPATCH(name)
#else
HWY_EXPORT(ParticleToGrid);
HWY_EXPORT(StressAndInternalForce);
HWY_EXPORT(GridToParticle);
HWY_EXPORT(TargetName);
#define MPM_SDEM_SWEEP(name) HWY_DYNAMIC_DISPATCH(name)
#endif

void particleToGrid(KernelType kernel, P2GParts parts, const Particles& P, Grid& G,
                    const Tiles& T) {
  MPM_SDEM_SWEEP(ParticleToGrid)(kernel, parts, P, G, T);
}

void stressAndInternalForce(KernelType kernel, Particles& P, Grid& G, const Tiles& T,
                            const std::vector<MaterialParams>& materials, Real dt,
                            SidewallLoad walls) {
  MPM_SDEM_SWEEP(StressAndInternalForce)(kernel, P, G, T, materials, dt, walls);
}

void gridToParticle(KernelType kernel, TransferScheme scheme, bool gradient, Particles& P,
                    const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T) {
  MPM_SDEM_SWEEP(GridToParticle)(kernel, scheme, gradient, P, G, s, clamped, finite, T);
}

const char* simdTarget() {
  return MPM_SDEM_SWEEP(TargetName)();
}

}  // namespace mpm_sdem::detail
#endif
