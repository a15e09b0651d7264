// The point sweeps of sweeps.hpp for every SIMD target Highway compiles here, and the run-time
// choice among them (hwy/foreach_target.h re-includes this file, and node_rows.hpp with it, once
// per target). P2G and the stress sweep work on GCC's vectors (node_rows.hpp: a row of four
// nodes): inside HWY_BEFORE_NAMESPACE the compiler lowers them, and the functions of
// transfer.hpp and constitutive.hpp they inline, to the target's instructions (AVX-512, AVX2,
// SSE4, SSE2). G2P of the quadratic B-spline works across points in Highway's vectors
// (laneSums), the other kernels' on rows. The colour loops (forEachTileByColour) stay baseline
// code and call each tile's work.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "mpm/sweeps.cpp"
#include "hwy/foreach_target.h"  // IWYU pragma: keep

#include <algorithm>
#include <cmath>
#include <limits>

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
// With kGiven, L_p is the points' own (volumetric_average.hpp corrected it) and is not summed.
template <class K, bool kGiven>
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
  // (L_p across points, as G2P's sums, measured slower here: the points come in tile order, so
  // their positions are gathered and L_p written back one by one, and the spread that follows
  // needs each point's row weights anyway.)
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
      if constexpr (!kGiven) {
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
      }
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

// A point's sums over its nodes in G2P: the PIC velocity sum_I S_Ip v_I (eq. 26), FLIP's
// increment sum_I S_Ip (v_I - v0_I) (eq. 28), APIC's B_p = sum_I S_Ip v_I (x_I - x_p)^T (eq. 31)
// and, in USL, L_p = sum_I v_I (grad S_Ip)^T; each only where the scheme uses it.
struct G2PSums {
  Real vx, vy, dvx, dvy, bxx, bxy, byx, byy, lxx, lxy, lyx, lyy;
};

// The sums of point p with rows of four nodes (node_rows.hpp): every kernel.
template <class K, TransferScheme kScheme, bool kGradient>
[[gnu::always_inline]] inline G2PSums rowSums(const Particles& P, const Grid& G, long p) {
  constexpr int S = K::kSupport;
  const Real h = G.h, inv_h = G.inv_h;
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
  return {v[0], v[1], v[2], v[3], b[0], b[1], b[2], b[3], l[0], l[1], l[2], l[3]};
}

namespace hn = hwy::HWY_NAMESPACE;

// G2P of the quadratic B-spline across points: as many points at once as a vector has lanes,
// their nodes' velocities gathered, so that the stencil's arithmetic runs across points instead
// of across a row's four nodes, of which it uses three (the G2P stage 2.0x faster than on rows,
// 10k-100k points, AVX-512; bench/README.md). Bit for bit rowSums' result: the same weights
// (node_rows.hpp's polynomials in r equal kernels.hpp's in f = x_g - base, exact here), the
// same products, sums and fused multiply-adds in the same order (what GCC makes of the rows:
// y_g's product fused into each of its uses, a row's four lanes added as (0 + 1) + (2 + 3)),
// which test_simd_targets checks on whole runs.
using LaneTag = hn::ScalableTag<Real>;
using Lanes = hn::Vec<LaneTag>;
using LaneIndices = hn::Vec<hn::RebindToSigned<LaneTag>>;

// The points' stencils: weights, their derivatives (per grid unit) and offsets x_I - x_p (grid
// units) at the three nodes per axis, and the index of each point's first node.
struct LaneStencil {
  Lanes wx[3], dwx[3], rx[3], wy[3], dwy[3], ry[3];
  // The row window starts a node before the stencil (x's fraction 1/2 or more).
  hn::Mask<LaneTag> shifted;
  LaneIndices first_node;
};

// Seed 000 eq. A3 at the stencil's three nodes, as QuadraticBSpline::stencil writes it, from the
// point's offset f in [1/2, 3/2) from the first node: the weights and their derivatives.
[[gnu::always_inline]] inline void quadraticWeights(Lanes f, Lanes w[3], Lanes dw[3]) {
  const LaneTag d;
  const Lanes half = hn::Set(d, 0.5);
  const Lanes a = hn::Set(d, 1.5) - f, b = f - hn::Set(d, 1), c = f - half;
  w[0] = half * a * a;
  w[1] = hn::NegMulAdd(b, b, hn::Set(d, 0.75));
  w[2] = half * c * c;
  dw[0] = hn::Neg(a);
  dw[1] = hn::Set(d, -2) * b;
  dw[2] = c;
}

[[gnu::always_inline]] inline LaneStencil laneStencil(const Grid& G, Lanes x, Lanes y) {
  const LaneTag d;
  const Lanes inv_h = hn::Set(d, G.inv_h), half = hn::Set(d, 0.5);
  const Lanes xg = (x - hn::Set(d, G.origin.x())) * inv_h;
  const Lanes dy = y - hn::Set(d, G.origin.y());  // y_g = dy inv_h, never rounded (as the rows)
  // Along x the row window's weights at the stencil's nodes; along y QuadraticBSpline::stencil's.
  const Lanes base_x = hn::Floor(xg - half);
  const Lanes base_y = hn::Floor(hn::MulAdd(dy, inv_h, hn::Neg(half)));
  LaneStencil st;
  st.shifted = hn::Eq(base_x, hn::Floor(xg));
  quadraticWeights(xg - base_x, st.wx, st.dwx);
  quadraticWeights(hn::MulSub(dy, inv_h, base_y), st.wy, st.dwy);
  for (int k = 0; k < 3; ++k) {
    st.rx[k] = (base_x + hn::Set(d, k)) - xg;
    st.ry[k] = hn::NegMulAdd(dy, inv_h, base_y + hn::Set(d, k));
  }
  st.first_node =
      hn::ConvertTo(hn::RebindToSigned<LaneTag>(), hn::MulAdd(base_y, hn::Set(d, G.nx), base_x));
  return st;
}

// Node (k, j) of the stencil: k along x, j along y.
[[gnu::always_inline]] inline LaneIndices laneNode(const Grid& G, const LaneStencil& st, int k,
                                                   int j) {
  return st.first_node + hn::Set(hn::RebindToSigned<LaneTag>(), j * G.nx + k);
}

// A sum over the stencil from its three node columns, in the rows' order.
[[gnu::always_inline]] inline Lanes columnsInRowOrder(const LaneStencil& st, Lanes c0, Lanes c1,
                                                      Lanes c2) {
  return hn::IfThenElse(st.shifted, c0 + (c1 + c2), (c0 + c1) + c2);
}

constexpr int kG2PSums = 12;  // G2PSums' fields, in its order

// rowSums' sums for the points at x and y (one per lane).
template <TransferScheme kScheme, bool kGradient>
void laneSums(const Grid& G, Lanes x, Lanes y, Lanes out[kG2PSums]) {
  const LaneTag d;
  constexpr bool kFlipPart = kScheme == TransferScheme::kFlip || kScheme == TransferScheme::kAsflip;
  const Lanes h = hn::Set(d, G.h), inv_h = hn::Set(d, G.inv_h);
  const LaneStencil st = laneStencil(G, x, y);
  Lanes rx[3], ry[3];
  for (int k = 0; k < 3; ++k) rx[k] = st.rx[k] * h, ry[k] = st.ry[k] * h;
  // Per node column k the sums over its three rows (a lane of rowSums' rows).
  Lanes column[3][kG2PSums];
  for (int k = 0; k < 3; ++k) {
    Lanes* c = column[k];
    for (int q = 0; q < kG2PSums; ++q) c[q] = hn::Zero(d);
    for (int j = 0; j < 3; ++j) {
      const LaneIndices node = laneNode(G, st, k, j);
      const Lanes w = st.wx[k] * st.wy[j];
      const Lanes gvx = hn::GatherIndex(d, G.vel_x.data(), node);
      const Lanes gvy = hn::GatherIndex(d, G.vel_y.data(), node);
      if (carriesAffine(kScheme)) {  // w v_I serves the velocity and B: rounded once
        const Lanes tx = w * gvx, ty = w * gvy;
        c[0] = c[0] + tx, c[1] = c[1] + ty;
        c[4] = hn::MulAdd(tx, rx[k], c[4]), c[5] = hn::MulAdd(tx, ry[j], c[5]);
        c[6] = hn::MulAdd(ty, rx[k], c[6]), c[7] = hn::MulAdd(ty, ry[j], c[7]);
      } else {
        c[0] = hn::MulAdd(w, gvx, c[0]), c[1] = hn::MulAdd(w, gvy, c[1]);
      }
      if (kFlipPart) {
        c[2] = hn::MulAdd(w, gvx - hn::GatherIndex(d, G.vel0_x.data(), node), c[2]);
        c[3] = hn::MulAdd(w, gvy - hn::GatherIndex(d, G.vel0_y.data(), node), c[3]);
      }
      if (kGradient) {
        const Lanes gx = st.dwx[k] * st.wy[j] * inv_h, gy = st.wx[k] * st.dwy[j] * inv_h;
        c[8] = hn::MulAdd(gvx, gx, c[8]), c[9] = hn::MulAdd(gvx, gy, c[9]);
        c[10] = hn::MulAdd(gvy, gx, c[10]), c[11] = hn::MulAdd(gvy, gy, c[11]);
      }
    }
  }
  for (int q = 0; q < kG2PSums; ++q)
    out[q] = columnsInRowOrder(st, column[0][q], column[1][q], column[2][q]);
}

// The velocity, B or L and position of point p from its sums: PIC velocity (eq. 26), FLIP blend
// (eq. 28), APIC affine matrix (eq. 31) or both, then x_p += dt sum_I S_Ip v_I (the PIC velocity
// moves the point in every scheme). kGradient (USL): also L_p from the post-kick velocity.
template <TransferScheme kScheme, bool kGradient>
[[gnu::always_inline]] inline void finishPoint(Particles& P, long p, const G2PSums& m,
                                               const G2PSettings& s, long& clamped, int& bad) {
  if (kScheme == TransferScheme::kFlip) {
    const Real a = s.pic_fraction;
    P.vx[p] = a * m.vx + (1 - a) * (P.vx[p] + m.dvx);
    P.vy[p] = a * m.vy + (1 - a) * (P.vy[p] + m.dvy);
  } else if (kScheme == TransferScheme::kAsflip) {
    // FLIP's increment (eq. 28 with alpha = 0): the point keeps its own departure from the
    // grid's field, v_p - v^n(x_p), which APIC drops at every transfer (a share lost per
    // step, so a loss that grows as the step shrinks); B below is APIC's, from the grid.
    // With a relaxation time the departure decays by the same factor at every point:
    // sum_p m_p (v_p - v^n(x_p)) = 0 (APIC's transfer keeps momentum), so momentum stays exact.
    if (s.keep < 1) {
      P.vx[p] = m.vx + s.keep * (P.vx[p] + m.dvx - m.vx);
      P.vy[p] = m.vy + s.keep * (P.vy[p] + m.dvy - m.vy);
    } else {
      P.vx[p] += m.dvx;
      P.vy[p] += m.dvy;
    }
  } else {
    P.vx[p] = m.vx;
    P.vy[p] = m.vy;
  }
  if (carriesAffine(kScheme)) {
    P.bxx[p] = m.bxx;
    P.bxy[p] = m.bxy;
    P.byx[p] = m.byx;
    P.byy[p] = m.byy;
  }
  if (kGradient) {
    P.lxx[p] = m.lxx;
    P.lxy[p] = m.lxy;
    P.lyx[p] = m.lyx;
    P.lyy[p] = m.lyy;
  }
  moveInside(P, p, s, m.vx, m.vy, clamped, bad);
}

// Whether finishLanes does a scheme's velocity update: all but FLIP's blend, which goes point
// by point (finishPoint).
constexpr bool finishesLanes(TransferScheme scheme) {
  return scheme != TransferScheme::kFlip;
}

// finishPoint for the points p0 .. p0 + lanes - 1 at once, bit for bit (moveInside's fused
// x_p + dt v and its tests lane by lane).
template <TransferScheme kScheme, bool kGradient>
[[gnu::always_inline]] inline void finishLanes(Particles& P, long p0, const Lanes m[kG2PSums],
                                               const G2PSettings& s, long& clamped, int& bad) {
  const LaneTag d;
  if (kScheme == TransferScheme::kAsflip) {
    const Lanes vx = hn::LoadU(d, P.vx.data() + p0) + m[2];
    const Lanes vy = hn::LoadU(d, P.vy.data() + p0) + m[3];
    if (s.keep < 1) {
      const Lanes keep = hn::Set(d, s.keep);
      hn::StoreU(hn::MulAdd(keep, vx - m[0], m[0]), d, P.vx.data() + p0);
      hn::StoreU(hn::MulAdd(keep, vy - m[1], m[1]), d, P.vy.data() + p0);
    } else {
      hn::StoreU(vx, d, P.vx.data() + p0);
      hn::StoreU(vy, d, P.vy.data() + p0);
    }
  } else {
    hn::StoreU(m[0], d, P.vx.data() + p0);
    hn::StoreU(m[1], d, P.vy.data() + p0);
  }
  if (carriesAffine(kScheme)) {
    hn::StoreU(m[4], d, P.bxx.data() + p0);
    hn::StoreU(m[5], d, P.bxy.data() + p0);
    hn::StoreU(m[6], d, P.byx.data() + p0);
    hn::StoreU(m[7], d, P.byy.data() + p0);
  }
  if (kGradient) {
    hn::StoreU(m[8], d, P.lxx.data() + p0);
    hn::StoreU(m[9], d, P.lxy.data() + p0);
    hn::StoreU(m[10], d, P.lyx.data() + p0);
    hn::StoreU(m[11], d, P.lyy.data() + p0);
  }
  const Lanes dt = hn::Set(d, s.dt), x0 = hn::LoadU(d, P.x.data() + p0);
  const Lanes y0 = hn::LoadU(d, P.y.data() + p0);
  Lanes x = hn::MulAdd(dt, m[0], x0), y = hn::MulAdd(dt, m[1], y0);
  const auto finite = hn::And(hn::IsFinite(x), hn::IsFinite(y));  // the others keep x_p
  if (!hn::AllTrue(d, finite)) bad = 1;
  const Lanes lo_x = hn::Set(d, s.lo.x()), hi_x = hn::Set(d, s.hi.x());
  const Lanes lo_y = hn::Set(d, s.lo.y()), hi_y = hn::Set(d, s.hi.y());
  if (s.periodic_x) {
    const Lanes width = hn::Set(d, s.hi.x() - s.lo.x());
    x = hn::IfThenElse(hn::Lt(x, lo_x), x + width, hn::IfThenElse(hn::Ge(x, hi_x), x - width, x));
  }
  const auto outside =
      hn::Or(hn::Or(hn::Lt(x, lo_x), hn::Gt(x, hi_x)), hn::Or(hn::Lt(y, lo_y), hn::Gt(y, hi_y)));
  clamped += static_cast<long>(hn::CountTrue(d, hn::And(outside, finite)));
  x = hn::IfThenElse(hn::Lt(x, lo_x), lo_x, hn::IfThenElse(hn::Gt(x, hi_x), hi_x, x));
  y = hn::IfThenElse(hn::Lt(y, lo_y), lo_y, hn::IfThenElse(hn::Gt(y, hi_y), hi_y, y));
  hn::StoreU(hn::IfThenElse(finite, x, x0), d, P.x.data() + p0);
  hn::StoreU(hn::IfThenElse(finite, y, y0), d, P.y.data() + p0);
}

// The quadratic B-spline's G2P of points p0 .. p0 + lanes - 1 (fewer before end, where the last
// lanes repeat the last point).
template <TransferScheme kScheme, bool kGradient>
void laneBlock(Particles& P, const Grid& G, const G2PSettings& s, long p0, long end, long& clamped,
               int& bad) {
  constexpr size_t kMax = hn::MaxLanes(LaneTag());
  const long lanes = static_cast<long>(hn::Lanes(LaneTag()));
  const long count = std::min(lanes, end - p0);
  Lanes m[kG2PSums];
  if (count == lanes) {
    laneSums<kScheme, kGradient>(G, hn::LoadU(LaneTag(), P.x.data() + p0),
                                 hn::LoadU(LaneTag(), P.y.data() + p0), m);
    if (finishesLanes(kScheme)) {
      finishLanes<kScheme, kGradient>(P, p0, m, s, clamped, bad);
      return;
    }
  } else {
    Real x[kMax] = {}, y[kMax] = {};
    for (long l = 0; l < lanes; ++l) {
      x[l] = P.x[p0 + std::min(l, count - 1)];
      y[l] = P.y[p0 + std::min(l, count - 1)];
    }
    laneSums<kScheme, kGradient>(G, hn::LoadU(LaneTag(), x), hn::LoadU(LaneTag(), y), m);
  }
  HWY_ALIGN Real sums[kG2PSums * kMax];
  for (int q = 0; q < kG2PSums; ++q) hn::Store(m[q], LaneTag(), sums + q * lanes);
  for (long l = 0; l < count; ++l) {
    const Real* v = sums + l;
    const G2PSums lane{v[0],         v[lanes],     v[2 * lanes],  v[3 * lanes],
                       v[4 * lanes], v[5 * lanes], v[6 * lanes],  v[7 * lanes],
                       v[8 * lanes], v[9 * lanes], v[10 * lanes], v[11 * lanes]};
    finishPoint<kScheme, kGradient>(P, p0 + l, lane, s, clamped, bad);
  }
}

// G2P over every point: without SPH particles in storage order, the quadratic B-spline's
// points a vector's lanes at a time (laneSums); with them (T given), the material points of
// each tile one by one.
template <class K, TransferScheme kScheme, bool kGradient>
void gridToParticle(Particles& P, const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T = nullptr) {
  const long n = static_cast<long>(P.size());
  long clamped_count = 0;
  int bad = 0;
  constexpr bool kLanes = std::is_same_v<K, QuadraticBSpline>;
  // laneStencil computes node indices in Real: exact below 2^53 nodes in double, 2^24 in float.
  const bool exact =
      static_cast<double>(G.nx) * G.ny < std::ldexp(1.0, std::numeric_limits<Real>::digits);
  const bool across = kLanes && !T && exact && !rowSweepsForTest();
  const long lanes = across ? static_cast<long>(hn::Lanes(LaneTag())) : 1;
  // The reduction's private copies are passed in: a lambda made outside the parallel region
  // would capture the shared ones.
  auto point = [&](long p, long& clamped_here, int& bad_here) __attribute__((always_inline)) {
    finishPoint<kScheme, kGradient>(P, p, rowSums<K, kScheme, kGradient>(P, G, p), s, clamped_here,
                                    bad_here);
  };
  // The points of the grid sums, tile by tile in sorted order, or the awake runs, or all in
  // storage order.
  const long count = T         ? static_cast<long>(T->start.size()) - 1
                     : s.awake ? static_cast<long>(s.awake->size())
                               : (n + lanes - 1) / lanes;
  auto item = [&](long k, long& clamped_here, int& bad_here) __attribute__((always_inline)) {
    if (T) {
      for (int q = T->start[k]; q < T->mpm_end[k]; ++q) point(T->order[q], clamped_here, bad_here);
    } else if (s.awake) {
      const PointRun run = (*s.awake)[k];
      for (long p = run.begin; p < run.end; p += lanes) {
        if constexpr (kLanes) {
          if (across) {
            laneBlock<kScheme, kGradient>(P, G, s, p, run.end, clamped_here, bad_here);
            continue;
          }
        }
        point(p, clamped_here, bad_here);
      }
    } else if (across) {
      if constexpr (kLanes)
        laneBlock<kScheme, kGradient>(P, G, s, k * lanes, n, clamped_here, bad_here);
    } else {
      point(k, clamped_here, bad_here);
    }
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
                            SidewallLoad walls, bool gradient_given) {
  withKernel(kernel, [&](auto k) {
    using K = decltype(k);
    gradient_given ? stressAndInternalForce<K, true>(P, G, T, materials, dt, walls)
                   : stressAndInternalForce<K, false>(P, G, T, materials, dt, walls);
  });
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
                            SidewallLoad walls, bool gradient_given) {
  MPM_SDEM_SWEEP(StressAndInternalForce)(kernel, P, G, T, materials, dt, walls, gradient_given);
}

void gridToParticle(KernelType kernel, TransferScheme scheme, bool gradient, Particles& P,
                    const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T) {
  MPM_SDEM_SWEEP(GridToParticle)(kernel, scheme, gradient, P, G, s, clamped, finite, T);
}

const char* simdTarget() {
  return MPM_SDEM_SWEEP(TargetName)();
}

namespace {
bool row_sweeps_for_test = false;
}
void setRowSweepsForTest(bool rows) {
  row_sweeps_for_test = rows;
}
bool rowSweepsForTest() {
  return row_sweeps_for_test;
}

}  // namespace mpm_sdem::detail
#endif
