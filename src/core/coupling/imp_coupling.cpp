#include "coupling/imp_coupling.hpp"

#include <cmath>

#include "mpm/transfer.hpp"
#include "mpm_sdem/core/coupling/restitution.hpp"

namespace mpm_sdem {

ImpCoupling::ImpCoupling(const CouplingDef& def, const Vec2& lo, const Vec2& hi, Real cell_size)
    : Coupling(def) {
  search_.init(lo, hi, cell_size, def.contact_radius, def.verlet_distance);
}

void ImpCoupling::beforeStep(CouplingStep& s) {
  const Particles& P = s.particles;
  ContactBodies& B = s.bodies;
  search_.update(P, B);
  active_ = 0;
  on_material_.setZero();
  const Real rp = def_.contact_radius;
  const bool exact = def_.normal_integration == ContactIntegration::kExact;
  search_.forEachContact(P, B, [&](ContactPair& c, int b, const CoreDistance& d) {
    const int p = c.particle;
    const Real a = B.rounding(b);
    const Vec2 x(P.x[p], P.y[p]);
    // Eq. 44 with the point's radius r_p capped at its depth below the body's outline: the
    // points of the outermost layer then reach exactly to the true surface. With r_p alone a
    // body's lattice staircase touches a flat block along a whole row of points, a flat face
    // that friction cannot tip (a disk of 10 cells per radius slid without spinning at
    // mu < 0.2), and it floats r_p - h/(2 ppc) above the block.
    const Real xi = a + materialReach(P, p, rp) - d.distance;
    auto release = [&c] {
      c.history.setZero();
      c.force.setZero();
    };
    if (xi <= 0 && !exact) return release();
    // Contact point: the middle of the overlap along the normal (eq. 41 for a disk), the
    // block's surface for a pair that only meets within the step.
    c.point = d.point + (a - std::fmax(xi, Real(0)) / 2) * d.normal;
    // The material's velocity at the contact point, not at the point's centre: v_p + L_p d
    // with the velocity gradient of the last transfer. A spinning body's centre moves slower
    // than its surface by omega times the depth, and a contact that read v_p saw a rolling
    // disk still slipping (it stopped slipping at omega (R - depth) = v, 5% too fast a spin at
    // 10 cells per radius).
    const Vec2 d_p = c.point - x;
    const Vec2 v_material(P.vx[p] + P.lxx[p] * d_p.x() + P.lxy[p] * d_p.y(),
                          P.vy[p] + P.lyx[p] * d_p.x() + P.lyy[p] * d_p.y());
    const Vec2 v = v_material - B.velocityAt(b, c.point);
    const Real vn = v.dot(d.normal);
    const Real scale = impSpringScale(def_.stiffness_per, P, p, s.grid.h);
    const Real kn = scale * def_.normal_stiffness, kt = scale * def_.tangential_stiffness;
    const Real m = reducedMass(P.mass[p], B.mass(b));
    const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(kn * m);
    // Eq. 43's normal force; exact: the step's mean force of the same spring-dashpot.
    const Real fn = exact ? clippedSpringImpulse(m, kn, gamma, xi, -vn, s.dt) / s.dt
                          : std::fmax(kn * xi - gamma * vn, Real(0));
    if (xi <= 0 && fn == 0) return release();
    c.history += (v - vn * d.normal) * s.dt;
    c.history -= c.history.dot(d.normal) * d.normal;
    Vec2 ft = -kt * c.history;
    const Real cap = B.friction(b) * fn;
    if (ft.norm() > cap) {
      ft *= ft.norm() > 0 ? cap / ft.norm() : 0;
      c.history = -ft / kt;
    }
    c.force = fn * d.normal + ft;        // eq. 43 on the point
    B.applyForce(b, -c.force, c.point);  // eq. 49-50, equal and opposite
    on_material_ += c.force;
    ++active_;
  });
}

void ImpCoupling::addGridForces(CouplingStep& s) {
  const bool at_point = def_.scheme == CouplingScheme::kImpGrid;
  const Particles& P = s.particles;
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    for (const ContactPair& c : search_.pairs()) {
      if (c.force.x() == 0 && c.force.y() == 0) continue;
      if (s.isSph(c.particle)) {  // the whole force on the particle, at its centre
        s.sph_ax[c.particle] += c.force.x() / P.mass[c.particle];
        s.sph_ay[c.particle] += c.force.y() / P.mass[c.particle];
        continue;
      }
      // Fig. 17B: the nodes around the contact point that carry material; eq. 48 otherwise
      // (f_I += S_Ip f_p), also when no node around the contact point has mass.
      if (!at_point ||
          !detail::spreadPointLoad<K>(s.grid, c.point, P.half_size[c.particle], c.force)) {
        const Vec2 x(P.x[c.particle], P.y[c.particle]);
        detail::spreadParticleForce<K>(s.grid, P, c.particle, c.force, c.point - x);
      }
    }
  });
}

}  // namespace mpm_sdem
