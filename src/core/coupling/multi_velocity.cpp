#include "coupling/multi_velocity.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "coupling/contact_impulse.hpp"
#include "mpm/transfer.hpp"

namespace mpm_sdem {

MultiVelocityCoupling::MultiVelocityCoupling(const CouplingDef& def, Real cell_size)
    : Coupling(def), h_(cell_size) {}

void MultiVelocityCoupling::correctGridVelocity(CouplingStep& s) {
  ContactBodies& B = s.bodies;
  Grid& G = s.grid;
  const Particles& P = s.particles;
  constexpr Real kInfinity = std::numeric_limits<Real>::infinity();
  const Real spacing = h_ / def_.block_points_per_cell;
  active_ = 0;
  on_material_.setZero();
  // Blocks only: the scheme meets no FEM bodies (couplingSchemes(), refused before a step).
  InteriorLattice* lattice = B.interiorLattice();
  if (!lattice) return;
  const Real half_size = Real(0.5) / def_.block_points_per_cell;  // GIMP, in cells
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    constexpr int S = K::kSupport;
    for (int b = 0; b < B.shapeCount(); ++b) {
      // The body's own points (its lattice, moved with it) and their nodal patch: every node
      // they touch.
      Real sample_mass = 0;
      lattice->interiorPoints(b, spacing, samples_, sample_mass);
      Vec2 lo = samples_[0], hi = lo;
      for (const Vec2& x : samples_) {
        lo = lo.cwiseMin(x);
        hi = hi.cwiseMax(x);
      }
      if (!lo.allFinite() || !hi.allFinite()) continue;  // World reports the non-finite state
      const int i0 = std::max(0, static_cast<int>((lo.x() - G.origin.x()) * G.inv_h) - 2);
      const int j0 = std::max(0, static_cast<int>((lo.y() - G.origin.y()) * G.inv_h) - 2);
      const int i1 = std::min(G.nx - 1, static_cast<int>((hi.x() - G.origin.x()) * G.inv_h) + 3);
      const int j1 = std::min(G.ny - 1, static_cast<int>((hi.y() - G.origin.y()) * G.inv_h) + 3);
      const int w = i1 - i0 + 1;
      // The material's nodes in the patch: only they can share momentum with the block, so the
      // samples that reach none of them are skipped (a floor block's lattice spans the floor; the
      // material touches a few cells of it). The kept nodes sum the same terms in the same order.
      int mi0 = i1 + 1, mi1 = i0 - 1, mj0 = j1 + 1, mj1 = j0 - 1;
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          if (!(G.mass[G.index(i, j)] > 0)) continue;
          mi0 = std::min(mi0, i);
          mi1 = std::max(mi1, i);
          mj0 = std::min(mj0, j);
          mj1 = std::max(mj1, j);
        }
      }
      if (mi0 > mi1) continue;  // no material near this block
      // A sample's stencil starts at most a node below it and spans S nodes.
      const Vec2 reach_lo = G.origin + Vec2(mi0 - S, mj0 - S) * G.h;
      const Vec2 reach_hi = G.origin + Vec2(mi1 + S, mj1 + S) * G.h;
      patch_mass_.assign(static_cast<std::size_t>(w) * (j1 - j0 + 1), 0);
      patch_normal_.assign(patch_mass_.size(), Vec2(0, 0));
      // f(q, w, grad) for each patch entry q of the nodes around x (GIMP half size lp, cells),
      // with the node's weight S and its gradient (1/m).
      auto forPatchNodes = [&](const Vec2& x, Real lp, auto&& f) {
        Real xg, yg;
        Stencil1D sx, sy;
        detail::stencils<K>(G, x.x(), x.y(), lp, xg, yg, sx, sy);
        for (int j = 0; j < S; ++j) {
          for (int i = 0; i < S; ++i) {
            const int pi = sx.base + i - i0, pj = sy.base + j - j0;
            if (pi < 0 || pi >= w || pj < 0 || pj > j1 - j0) continue;
            f(static_cast<std::size_t>(pi + pj * w), sx.w[i] * sy.w[j],
              Vec2(G.inv_h * Vec2(sx.dw[i] * sy.w[j], sx.w[i] * sy.dw[j])));
          }
        }
      };
      for (const Vec2& x : samples_) {
        if (x.x() < reach_lo.x() || x.y() < reach_lo.y() || x.x() > reach_hi.x() ||
            x.y() > reach_hi.y())
          continue;
        forPatchNodes(x, half_size, [&](std::size_t q, Real weight, const Vec2& grad) {
          patch_mass_[q] += weight * sample_mass;
          patch_normal_[q] += sample_mass * grad;  // eq. 23: n_I = sum_p m_p grad S_Ip, outwards
        });
      }
      // The material's gap to the block at each node (seed 002 sec. 2.4.1 adds a distance check
      // to eq. 22, after Ma et al.: without one, bodies touch wherever their kernels overlap, up
      // to two cells apart). Here: the least gap, to the block's rounded outline, of the points
      // that map to the node and lie within half a cell of it along the surface; a point's gap
      // is its distance less its reach. The contact then sits at the nodes beside the true
      // contact point. Without the check a disk rested on a patch some three cells wide that
      // friction could not tip (the normal impulses moved mu R ahead of the centre and
      // cancelled the friction's torque: a thrown disk did not spin) and floated a cell high.
      patch_gap_.assign(patch_mass_.size(), kInfinity);
      const Vec2 near_lo = G.origin + Vec2(i0 - 1, j0 - 1) * G.h;
      const Vec2 near_hi = G.origin + Vec2(i1 + 1, j1 + 1) * G.h;
      const Real a = B.rounding(b);
      // The points near the patch, from the tiles they were binned in this step.
      const Tiles& T = s.tiles;
      std::vector<int>& near = near_points_;
      near.clear();
      for (int tb = std::max(0, (j0 - 1) / Tiles::kSize);
           tb <= std::min(T.ny - 1, (j1 + 1) / Tiles::kSize); ++tb)
        for (int ta = std::max(0, (i0 - 1) / Tiles::kSize);
             ta <= std::min(T.nx - 1, (i1 + 1) / Tiles::kSize); ++ta)
          for (int q = T.start[ta + tb * T.nx]; q < T.start[ta + tb * T.nx + 1]; ++q)
            near.push_back(T.order[q]);
      for (const int p : near) {
        const Vec2 x(P.x[p], P.y[p]);
        if (x.x() < near_lo.x() || x.y() < near_lo.y() || x.x() > near_hi.x() ||
            x.y() > near_hi.y())
          continue;
        const Real lp = P.half_size[p];
        const Real gap = B.closest(b, x).distance - a - materialReach(P, p, lp * G.h);
        forPatchNodes(x, lp, [&](std::size_t q, Real weight, const Vec2&) {
          const Vec2& nq = patch_normal_[q];
          const int pi = static_cast<int>(q % w), pj = static_cast<int>(q / w);
          const Vec2 along = x - (G.origin + Vec2(i0 + pi, j0 + pj) * G.h);
          if (weight > 0 && std::abs(cross(along, nq)) <= 0.5 * G.h * nq.norm())
            patch_gap_[q] = std::min(patch_gap_[q], gap);
        });
      }
      const Real mu = B.friction(b);
      for (int pj = 0; pj <= j1 - j0; ++pj) {
        for (int pi = 0; pi < w; ++pi) {
          const std::size_t q = static_cast<std::size_t>(pi + pj * w);
          const int node = G.index(i0 + pi, j0 + pj);
          const Real ms = G.mass[node];
          const Real nn = patch_normal_[q].norm();
          if (!(patch_mass_[q] > 0 && ms > 0 && nn > 0 && patch_gap_[q] < kInfinity))
            continue;  // not a shared node
          const Vec2 n = patch_normal_[q] / nn;
          const Vec2 xI = G.origin + Vec2(i0 + pi, j0 + pj) * G.h;
          // The body's trial velocity, changed by each node's exchange (Gauss-Seidel), so that the
          // nodes of one contact share the body's momentum.
          const Vec2 u = Vec2(G.vel_x[node], G.vel_y[node]) - B.trialVelocityAt(b, xI);
          // Eq. 22 with the distance check: the node may approach by its gap within the step
          // and no further; a node already in contact may not approach at all.
          const Real target = patch_gap_[q] > 0 ? -patch_gap_[q] / s.dt : 0;
          if (!(u.dot(n) < target)) continue;
          const Mat2 Kb = B.inverseMass(b, xI);
          const detail::Exchange e = detail::exchange(Mat2::Identity() / ms + Kb, u, n, target, mu);
          G.vel_x[node] += e.impulse.x() / ms;  // eq. 25
          G.vel_y[node] += e.impulse.y() / ms;
          B.applyImpulse(b, -e.impulse, xI, s.dt);
          on_material_ += e.impulse / s.dt;
          ++active_;
        }
      }
    }
  });
}

std::string MultiVelocityCoupling::settings() const {
  return std::to_string(def_.block_points_per_cell) + " block points per cell side";
}

}  // namespace mpm_sdem
