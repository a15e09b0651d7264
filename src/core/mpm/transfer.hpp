// Particle-grid transfers, one template instance per kernel so that the inner loops have fixed
// trip counts and no calls: the pieces the point sweeps share (sweeps.cpp holds the sweeps
// themselves, compiled per SIMD target) and the single-point spreads and reads of the couplings.
// Internal header of the core library.
#pragma once

#include <algorithm>
#include <cmath>
#include <optional>
#include <type_traits>

#include "contact_stencil.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "parallel.hpp"
#include "stress_batch.hpp"
#include "sweeps.hpp"

namespace mpm_sdem::detail {

template <class K>
inline void stencils(const Grid& g, Real x, Real y, Real lp, Real& xg, Real& yg, Stencil1D& sx,
                     Stencil1D& sy) {
  xg = (x - g.origin.x()) * g.inv_h;
  yg = (y - g.origin.y()) * g.inv_h;
  K::stencil(xg, lp, sx);
  K::stencil(yg, lp, sy);
}

// Run body(t) for every occupied tile t, colour by colour; the tiles of one colour are shared
// among the threads (see Tiles: no two of them write the same node).
template <class Body>
void forEachTileByColour(const Tiles& T, Body&& body) {
  for (const std::vector<int>& tiles : T.colour)
    parallelFor(static_cast<long>(tiles.size()), [&](long k) { body(tiles[k]); });
}
// Run body(p) for every particle of the grid sums, tile by tile as forEachTileByColour. With
// band(p), the SPH particles of the transition band go to band instead (they are updated by the
// SPH sums, and only lend the grid their mass, momentum and stress).
template <class Body, class Band>
void forEachParticleByColour(const Tiles& T, Body&& body, Band&& band) {
  forEachTileByColour(T, [&](int t) {
    for (int q = T.start[t]; q < T.mpm_end[t]; ++q) body(T.order[q]);
    for (int q = T.mpm_end[t]; q < T.grid_end[t]; ++q) band(T.order[q]);
  });
}
template <class Body>
void forEachParticleByColour(const Tiles& T, Body&& body) {
  forEachParticleByColour(T, body, body);
}

// The stress and volume of one point over dt with its velocity gradient L_p, by its model's
// update (constitutive.hpp: V^{n+1} = det(I + dt L) V^n, then, for a solid, Jaumann-rate
// elasticity, eq. 21-25, and its return; a fluid's stress from its new J and L), and no stress
// beyond the separation volume ratio.
[[gnu::always_inline]] inline void updatePointStress(const MaterialParams& m, Particles& P, long p,
                                                     Real dt) {
  const VelocityGradient L{P.lxx[p], P.lxy[p], P.lyx[p], P.lyy[p]};
  Real J = P.J[p];
  const Stress s = updateStress(m, {P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]}, L, J, dt);
  P.J[p] = J;
  P.sxx[p] = s.xx;
  P.syy[p] = s.yy;
  P.sxy[p] = s.xy;
  P.szz[p] = s.zz;
  if (J > m.separation) P.sxx[p] = P.syy[p] = P.sxy[p] = P.szz[p] = 0;
}

// Points waiting to have their stress updated together (updateStressBatch, issue 42): add(p)
// copies a point's L_p, stress and J in (flushing first if p's material differs from the
// waiting points'); flush(done) updates the waiting points, writes each back to P and then calls
// done(k, p) with its slot k. Only for materials that batchesStress.
class StressBatcher {
 public:
  StressBatcher(Particles& P, const std::vector<MaterialParams>& materials, Real dt)
      : P_(P), materials_(materials), dt_(dt) {}
  bool full() const { return batch_.count == StressBatch::kSize; }
  template <class Done>
  int add(int p, Done&& done) {
    if (P_.material[p] != material_) {
      flush(done);
      material_ = P_.material[p];
    }
    const int k = batch_.count++;
    batch_.lxx[k] = P_.lxx[p];
    batch_.lxy[k] = P_.lxy[p];
    batch_.lyx[k] = P_.lyx[p];
    batch_.lyy[k] = P_.lyy[p];
    batch_.sxx[k] = P_.sxx[p];
    batch_.syy[k] = P_.syy[p];
    batch_.sxy[k] = P_.sxy[p];
    batch_.szz[k] = P_.szz[p];
    batch_.J[k] = P_.J[p];
    points_[k] = p;
    return k;
  }
  template <class Done>
  void flush(Done&& done) {
    if (batch_.count == 0) return;
    updateStressBatch(materials_[material_], batch_, dt_);
    for (int k = 0; k < batch_.count; ++k) {
      const int p = points_[k];
      P_.sxx[p] = batch_.sxx[k];
      P_.syy[p] = batch_.syy[k];
      P_.sxy[p] = batch_.sxy[k];
      P_.szz[p] = batch_.szz[k];
      P_.J[p] = batch_.J[k];
      done(k, p);
    }
    batch_.count = 0;
  }

 private:
  Particles& P_;
  const std::vector<MaterialParams>& materials_;
  Real dt_;
  StressBatch batch_;
  int points_[StressBatch::kSize];
  int material_ = -1;
};

// USL's stress update (after G2P), every point in storage order: a batching material's points
// in batches, the others one by one.
inline void updateStresses(Particles& P, const std::vector<MaterialParams>& materials, Real dt) {
  const long n = static_cast<long>(P.size()), chunk = 8 * StressBatch::kSize;
  auto nothing = [](int, int) {};
  parallelFor((n + chunk - 1) / chunk, [&](long k) {
    const long c = k * chunk;
    StressBatcher batcher(P, materials, dt);
    for (long p = c; p < std::min(n, c + chunk); ++p) {
      const MaterialParams& m = materials[P.material[p]];
      if (!batchesStress(m)) {
        updatePointStress(m, P, p, dt);
        continue;
      }
      batcher.add(static_cast<int>(p), nothing);
      if (batcher.full()) batcher.flush(nothing);
    }
    batcher.flush(nothing);
  });
}

// The side walls' friction capacity on the nodes (issue 41, SidewallsDef): each point resists
// with 2 mu_w p_p V_p / W (coefficient = 2 mu_w / W; p_p its pressure, none in tension), spread
// like a body force, load_I = sum_p S_Ip coefficient p_p V_p (N per metre of thickness).
// Point p's part: coefficient p_p V_p, or 0.
[[gnu::always_inline]] inline Real sidewallForce(const Particles& P, long p, Real coefficient) {
  const Real pressure = -(P.sxx[p] + P.syy[p] + P.szz[p]) / 3;
  return pressure > 0 ? coefficient * pressure * P.volume0[p] * P.J[p] : Real(0);
}
// The nodes' load from every point (USL: after P2G; USF spreads it with the internal force,
// sweeps.hpp).
template <class K>
void sidewallLoad(const Particles& P, const Grid& G, const Tiles& T, Real coefficient, Real* load) {
  constexpr int S = K::kSupport;
  forEachParticleByColour(T, [&](int p) {
    const Real f = sidewallForce(P, p, coefficient);
    if (!(f > 0)) return;
    Real xg, yg;
    Stencil1D sx, sy;
    stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
    for (int j = 0; j < S; ++j) {
      const int row = (sy.base + j) * G.nx + sx.base;
      for (int i = 0; i < S; ++i) load[row + i] += sx.w[i] * sy.w[j] * f;
    }
  });
}

// The share of a point's departure from the grid's field that ASFLIP keeps over a step dt, for
// SolverDef::asflip_relaxation_time (0: all of it).
inline Real asflipKeep(Real dt, Real relaxation_time) {
  return relaxation_time > 0 ? std::exp(-dt / relaxation_time) : Real(1);
}

// Local non-viscous (Cundall) damping of one force component f against the velocity v:
// f - damping |f| sign(v) (SolverDef::damping); for a force per unit mass alike.
inline Real localDamping(Real f, Real v, Real damping) {
  if (!(damping > 0)) return f;
  return f - damping * std::abs(f) * (v > 0 ? 1 : v < 0 ? -1 : 0);
}

// x_p += dt v, kept inside the domain box (counted in clamped); a non-finite position is not
// taken (bad = 1), so that no stencil ever leaves the grid. Every particle moves through here,
// material point or SPH particle.
[[gnu::always_inline]] inline void moveInside(Particles& P, long p, const G2PSettings& s, Real vx,
                                              Real vy, long& clamped, int& bad) {
  Real x = P.x[p] + s.dt * vx, y = P.y[p] + s.dt * vy;
  if (!std::isfinite(x) || !std::isfinite(y)) {
    bad = 1;
    return;
  }
  if (s.periodic_x) {  // a step moves a point less than a cell, far less than the domain
    const Real width = s.hi.x() - s.lo.x();
    x = x < s.lo.x() ? x + width : x >= s.hi.x() ? x - width : x;
  }
  if (x < s.lo.x() || x > s.hi.x() || y < s.lo.y() || y > s.hi.y()) {
    ++clamped;
    x = x < s.lo.x() ? s.lo.x() : x > s.hi.x() ? s.hi.x() : x;  // finite here: no fmin call
    y = y < s.lo.y() ? s.lo.y() : y > s.hi.y() ? s.hi.y() : y;
  }
  P.x[p] = x;
  P.y[p] = y;
}

// Eq. 47: the contact force of each IMP goes to the grid like an external point load,
// f_I += S_Ip f for a force f on particle p (seed 000 eq. 48). With an offset d the force acts
// at x_p + d: the same f_I plus the couple d x f on the same nodes, as forces S_Ip (d x f) r_I^perp
// / D_p with r_I = x_I - x_p and D_p = sum S_Ip |r_I|^2. They sum to zero (sum S_Ip r_I = 0) and
// their moment about x_p is d x f, so a contact force and its reaction on a block act at one
// point and keep angular momentum. Every part is weighted by S_Ip, so no node gets more than a
// few times f S_Ip / m_I, whatever its mass. As a map, A_I = S_Ip (1 + r_I^perp d^perp^T / D_p)
// (d x f = d^perp . f); its transpose reads the grid's velocity at x_p + d with the nodes' mean
// rotation about x_p.
template <class K>
void particleForceStencil(const Grid& G, const Particles& P, int p, const Vec2& offset,
                          ContactStencil& st) {
  constexpr int S = K::kSupport;
  static_assert(S * S <= ContactStencil::kMaxNodes);
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
  Real second = 0;  // D_p / h^2
  for (int j = 0; j < S; ++j) {
    const Real ry = (sy.base + j) - yg;
    for (int i = 0; i < S; ++i) {
      const Real rx = (sx.base + i) - xg;
      second += sx.w[i] * sy.w[j] * (rx * rx + ry * ry);
    }
  }
  // The couple's force per unit S_Ip r_I^perp (r in cells) is (d^perp . f) inv_h / D.
  st.lever = second > 0 ? Vec2(Vec2(-offset.y(), offset.x()) * (G.inv_h / second)) : Vec2(0, 0);
  st.count = 0;
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    const Real ry = (sy.base + j) - yg;
    for (int i = 0; i < S; ++i) {
      const Real rx = (sx.base + i) - xg;
      const int k = st.count++;
      st.node[k] = row + i;
      st.w[k] = sx.w[i] * sy.w[j];
      st.rx[k] = -ry;  // r_I^perp
      st.ry[k] = rx;
    }
  }
}

template <class K>
void spreadParticleForce(Grid& G, const Particles& P, int p, const Vec2& f,
                         const Vec2& offset = Vec2(0, 0)) {
  ContactStencil st;
  particleForceStencil<K>(G, P, p, offset, st);
  st.spread(G.force_x, G.force_y, f);
}

// A point load at x on the nodes that carry mass, the weights renormalised over them (seed 003
// eq. 14), so that all of it reaches the material: A_I = S_I(x) / sum_J S_J(x) over those nodes.
// Returns false, adding no node, when no node around x has mass. mean: the weights' centroid
// relative to x (cells), for a couple.
template <class K>
bool pointLoadStencil(const Grid& G, const Vec2& x, Real half_size, ContactStencil& st,
                      Vec2* mean = nullptr) {
  constexpr int S = K::kSupport;
  static_assert(S * S <= ContactStencil::kMaxNodes);
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, x.x(), x.y(), half_size, xg, yg, sx, sy);
  Real sum = 0;
  Vec2 centroid(0, 0);
  st.count = 0;
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    for (int i = 0; i < S; ++i) {
      if (!(G.mass[row + i] > 0)) continue;
      const Real w = sx.w[i] * sy.w[j];
      sum += w;
      centroid += w * Vec2((sx.base + i) - xg, (sy.base + j) - yg);
      const int k = st.count++;
      st.node[k] = row + i;
      st.w[k] = w;
      st.rx[k] = st.ry[k] = 0;
    }
  }
  if (!(sum > 0)) {
    st.count = 0;
    return false;
  }
  for (int k = 0; k < st.count; ++k) st.w[k] /= sum;
  st.lever.setZero();
  if (mean) *mean = centroid / sum;
  return true;
}

// The point load acts at the weights' centroid xbar (x itself where every node around x has
// mass). With a couple (N m/m, counter-clockwise) the nodes also get w_I c r_I^perp, r_I from
// xbar: these sum to zero and their moment is the couple (as spreadParticleForce's offset), so
// a contact force that reaches the material inside its outline keeps the lever it has on the
// body at the contact point. Where few nodes around x carry mass (the ragged edge of a flow)
// their second moment about xbar can be tiny and c huge on a node of little mass; the divisor
// is therefore at least the whole stencil's, as if every node had mass, and such a load hands
// on only part of its couple. (Moving f itself from xbar to x as well spun up torn-off bits of
// the wooden-block flow: its partitioned wall, split as they flew, slowed the step to 11 ms.)
// Returns false, adding nothing, when no node around x has mass.
// half_size: GIMP's half width of the load's area, in cells (> 0).
template <class K>
bool spreadPointLoad(Grid& G, const Vec2& x, Real half_size, const Vec2& f,
                     std::optional<Real> couple = std::nullopt) {
  ContactStencil st;
  Vec2 mean;
  if (!pointLoadStencil<K>(G, x, half_size, st, &mean)) return false;
  st.spread(G.force_x, G.force_y, f);
  if (!couple) return true;
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, x.x(), x.y(), half_size, xg, yg, sx, sy);
  Real second = 0;
  for (int k = 0; k < st.count; ++k) {
    const int i = st.node[k] % G.nx, j = st.node[k] / G.nx;
    second += st.w[k] * (Vec2(i - xg, j - yg) - mean).squaredNorm();
  }
  const Real c = *couple * G.inv_h / std::max(second, sx.second_moment + sy.second_moment);
  for (int k = 0; k < st.count; ++k) {
    const int i = st.node[k] % G.nx, j = st.node[k] / G.nx;
    const Vec2 r = Vec2(i - xg, j - yg) - mean;
    G.force_x[st.node[k]] += st.w[k] * (-c * r.y());
    G.force_y[st.node[k]] += st.w[k] * (c * r.x());
  }
  return true;
}

// The grid velocity (vel_x, vel_y) at x as G2P interpolates it: sum_I S_I(x) v_I (nodes
// without mass carry zero).
template <class K>
Vec2 gridVelocityAt(const Grid& G, const Vec2& x, Real half_size) {
  constexpr int S = K::kSupport;
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, x.x(), x.y(), half_size, xg, yg, sx, sy);
  Vec2 v(0, 0);
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    for (int i = 0; i < S; ++i) v += sx.w[i] * sy.w[j] * Vec2(G.vel_x[row + i], G.vel_y[row + i]);
  }
  return v;
}

// The material's velocity at x for a massless tracer: sum_I S_I m_I v_I / sum_I S_I m_I. A node
// that holds only a sliver of mass at the edge of the material can carry a wild velocity
// (force over a tiny mass) that the points there barely see; weighting by mass keeps it out.
template <class K>
Vec2 materialVelocityAt(const Grid& G, const Vec2& x, Real half_size) {
  constexpr int S = K::kSupport;
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, x.x(), x.y(), half_size, xg, yg, sx, sy);
  Real sum = 0;
  Vec2 p(0, 0);
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    for (int i = 0; i < S; ++i) {
      const Real w = sx.w[i] * sy.w[j] * G.mass[row + i];
      sum += w;
      p += w * Vec2(G.vel_x[row + i], G.vel_y[row + i]);
    }
  }
  return sum > 0 ? Vec2(p / sum) : Vec2(0, 0);
}

// An impulse J on particle p (N s/m) onto the updated grid velocities: v_I += S_Ip J / m_I
// (seed 002 eq. 54 times the step).
template <class K>
void addParticleImpulse(Grid& G, const Particles& P, int p, const Vec2& J) {
  constexpr int S = K::kSupport;
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    for (int i = 0; i < S; ++i) {
      const Real m = G.mass[row + i];
      if (!(m > 0)) continue;
      const Real w = sx.w[i] * sy.w[j] / m;
      G.vel_x[row + i] += w * J.x();
      G.vel_y[row + i] += w * J.y();
    }
  }
}

// How fast particle p's interpolated velocity responds to an impulse on it spread by
// addParticleImpulse: sum_I S_Ip^2 / m_I (per kg per metre); below 1 / m_p wherever other
// points share p's nodes.
template <class K>
Real particleGridInverseMass(const Grid& G, const Particles& P, int p) {
  constexpr int S = K::kSupport;
  Real xg, yg;
  Stencil1D sx, sy;
  stencils<K>(G, P.x[p], P.y[p], P.half_size[p], xg, yg, sx, sy);
  Real sum = 0;
  for (int j = 0; j < S; ++j) {
    const int row = (sy.base + j) * G.nx + sx.base;
    for (int i = 0; i < S; ++i) {
      const Real m = G.mass[row + i];
      const Real w = sx.w[i] * sy.w[j];
      if (m > 0) sum += w * w / m;
    }
  }
  return sum;
}

// Call f(Kernel{}) for the scene's kernel: one dispatch per stage, none per particle.
template <class F>
void withKernel(KernelType k, F&& f) {
  switch (k) {
    case KernelType::kQuadraticBSpline:
      f(QuadraticBSpline{});
      break;
    case KernelType::kCubicBSpline:
      f(CubicBSpline{});
      break;
    case KernelType::kGimp:
      f(Gimp{});
      break;
  }
}

}  // namespace mpm_sdem::detail
