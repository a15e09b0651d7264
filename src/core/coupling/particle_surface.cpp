#include "coupling/particle_surface.hpp"

#include <cstdio>

#include "coupling/contact_impulse.hpp"
#include "mpm/transfer.hpp"
#include "state_archive.hpp"

namespace mpm_sdem {

namespace {

// The weights that read the grid's velocity at x + d to first order, W_I = S_I(x) + d . grad
// S_I(x), on x's nodes. They sum to 1 and their first moment is x + d, so an impulse spread with
// them keeps the momentum and acts at x + d (to first order); the velocity read with them then
// responds by sum_I W_I^2 / m_I per unit impulse (the spread is the reading's adjoint).
template <class K>
struct OffsetWeights {
  static constexpr int S = K::kSupport;
  int row[S];
  Real w[S][S];
  OffsetWeights(const Grid& G, const Vec2& x, Real half_size, const Vec2& d) {
    Real xg, yg;
    Stencil1D sx, sy;
    detail::stencils<K>(G, x.x(), x.y(), half_size, xg, yg, sx, sy);
    const Vec2 dc = d * G.inv_h;  // in cells, as dw
    for (int j = 0; j < S; ++j) {
      row[j] = (sy.base + j) * G.nx + sx.base;
      for (int i = 0; i < S; ++i)
        w[j][i] = sx.w[i] * sy.w[j] + dc.x() * sx.dw[i] * sy.w[j] + dc.y() * sx.w[i] * sy.dw[j];
    }
  }
  Vec2 velocity(const Grid& G) const {
    Vec2 v(0, 0);
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i) v += w[j][i] * Vec2(G.vel_x[row[j] + i], G.vel_y[row[j] + i]);
    return v;
  }
  Real inverseMass(const Grid& G) const {
    Real sum = 0;
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i)
        if (G.mass[row[j] + i] > 0) sum += w[j][i] * w[j][i] / G.mass[row[j] + i];
    return sum;
  }
  void addImpulse(Grid& G, const Vec2& J) const {
    for (int j = 0; j < S; ++j)
      for (int i = 0; i < S; ++i) {
        const Real m = G.mass[row[j] + i];
        if (!(m > 0)) continue;
        G.vel_x[row[j] + i] += w[j][i] / m * J.x();
        G.vel_y[row[j] + i] += w[j][i] / m * J.y();
      }
  }
};

}  // namespace

ParticleSurfaceCoupling::ParticleSurfaceCoupling(const CouplingDef& def, const Vec2& lo,
                                                 const Vec2& hi, Real cell_size)
    : Coupling(def) {
  // A point can close at most about a cell in one step (CFL), so pairs reach a cell out.
  search_.init(lo, hi, cell_size, cell_size, def.verlet_distance);
}

void ParticleSurfaceCoupling::correctGridVelocity(CouplingStep& s) {
  Particles& P = s.particles;  // SPH particles take their impulses on their own velocity
  ContactBodies& B = s.bodies;
  Grid& G = s.grid;
  search_.update(P, B);
  records_.clear();
  active_ = 0;
  on_material_.setZero();
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    search_.forEachContact(P, B, [&](const ContactPair& c, int b, const CoreDistance& d) {
      const int p = c.particle;
      const Vec2 x(P.x[p], P.y[p]);
      // Eq. 40 between the block's rounded surface and the material's: the point stands for
      // material up to its depth below its body's outline, at most r_p, as in IMP's eq. 44
      // (materialReach). Measured from the point's centre, a body's lattice touched a flat block
      // along a whole row of points, a flat face that friction could not tip.
      const Real reach = materialReach(P, p, def_.contact_radius);
      const Real gap = d.distance - B.rounding(b) - reach;
      const Vec2 point = d.point + B.rounding(b) * d.normal;
      // The body's trial velocity at the contact: many contacts on one body share its momentum.
      const Vec2 vc = B.trialVelocityAt(b, point);
      // Eq. 43: the point's trial velocity from the updated grid, carried to the contact point
      // (a spinning body's surface moves faster than its points). Along the normal, with the
      // point's velocity gradient of the last transfer; along the surface, read from the
      // grid at the contact point itself with the weights W_I = S_Ip + d . grad S_Ip.
      const Vec2 dp = point - x;
      const Vec2 t(-d.normal.y(), d.normal.x());
      if (s.isSph(p)) {
        // An SPH particle: its own trial velocity v + kick a carried to the contact point, its
        // own mass as its response, and the impulse on its velocity.
        const Vec2 trial(P.vx[p] + s.kick * s.sph_ax[p] + P.lxx[p] * dp.x() + P.lxy[p] * dp.y(),
                         P.vy[p] + s.kick * s.sph_ay[p] + P.lyx[p] * dp.x() + P.lyy[p] * dp.y());
        const Vec2 u = trial - vc;
        const Real target = -std::fmax(gap, Real(0)) / s.dt;
        if (!(u.dot(d.normal) < target)) return;
        const Mat2 Km = Mat2::Identity() / P.mass[p] + B.inverseMass(b, point);
        const detail::Exchange e = detail::exchange(Km, u, d.normal, target, B.friction(b));
        P.vx[p] += e.impulse.x() / P.mass[p];
        P.vy[p] += e.impulse.y() / P.mass[p];
        B.applyImpulse(b, -e.impulse, point, s.dt);
        on_material_ += e.impulse / s.dt;
        records_.push_back({p, b, gap, d.normal, e.impulse, target, e.relative_after, e.stuck});
        ++active_;
        return;
      }
      const OffsetWeights<K> at_contact(G, x, P.half_size[p], dp);
      const Vec2 along_normal =
          detail::gridVelocityAt<K>(G, x, P.half_size[p]) +
          Vec2(P.lxx[p] * dp.x() + P.lxy[p] * dp.y(), P.lyx[p] * dp.x() + P.lyy[p] * dp.y());
      const Vec2 u = along_normal.dot(d.normal) * d.normal + at_contact.velocity(G).dot(t) * t - vc;
      // The gap must not close past zero by the end of the step (eq. 40, g >= 0); a point
      // already inside may not go deeper.
      const Real target = -std::fmax(gap, Real(0)) / s.dt;
      if (!(u.dot(d.normal) < target)) return;
      // Eq. 48 with each side's response at the contact: the block's, and the material's as its
      // nodes give it (eq. 54 then G2P), not 1 / m_p alone. The normal impulse is spread with
      // S_Ip (eq. 54) and the friction impulse with W_I: with S_Ip it acted at the point's
      // centre, a depth below the surface, while its reaction turned the block at the contact
      // point, so 4% of the friction's moment never reached the material (a thrown disk spun up
      // at 0.940 of 2 mu g / R; 0.973-0.978 now). Spreading the normal impulse with W_I as well
      // let a resting square's contact points creep at 150 um/s.
      const Mat2 Kb = B.inverseMass(b, point);
      const Mat2 Km =
          detail::particleGridInverseMass<K>(G, P, p) * d.normal * d.normal.transpose() +
          at_contact.inverseMass(G) * t * t.transpose() + Kb;
      const detail::Exchange e = detail::exchange(Km, u, d.normal, target, B.friction(b));
      detail::addParticleImpulse<K>(G, P, p, e.impulse.dot(d.normal) * d.normal);
      at_contact.addImpulse(G, e.impulse.dot(t) * t);
      B.applyImpulse(b, -e.impulse, point, s.dt);
      on_material_ += e.impulse / s.dt;
      records_.push_back({p, b, gap, d.normal, e.impulse, target, e.relative_after, e.stuck});
      ++active_;
    });
  });
}

std::string ParticleSurfaceCoupling::settings() const {
  char text[96];
  std::snprintf(text, sizeof text, "no contact stiffness, Verlet distance %g m",
                def_.verlet_distance);
  return text;
}

void ParticleSurfaceCoupling::saveState(cereal::BinaryOutputArchive& ar) {
  search_.stateIo(ar);
  ar(records_);
}

void ParticleSurfaceCoupling::loadState(cereal::BinaryInputArchive& ar) {
  search_.stateIo(ar);
  ar(records_);
}

}  // namespace mpm_sdem
