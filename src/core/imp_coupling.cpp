#include "mpm_sdem/core/imp_coupling.hpp"

#include <cmath>

#include "transfer.hpp"

namespace mpm_sdem {

ImpCoupling::ImpCoupling(const CouplingDef& def, const Vec2& lo, const Vec2& hi, Real cell_size)
    : Coupling(def) {
  search_.init(lo, hi, cell_size, def.contact_radius, def.verlet_distance);
}

void ImpCoupling::beforeStep(CouplingStep& s) {
  const Particles& P = s.particles;
  Blocks& B = s.blocks;
  search_.update(P, B);
  B.clearCoupling();
  active_ = 0;
  on_material_.setZero();
  const Real kn = def_.normal_stiffness, kt = def_.tangential_stiffness, rp = def_.contact_radius;
  for (ContactPair& c : search_.pairs()) {
    const int b = c.block, p = c.particle;
    const BlockDef& bd = B.def(b);
    const Vec2 x(P.x[p], P.y[p]);
    const CoreDistance d = closestOnCore(B.vertices(b), B.vertexCount(b), x);
    const Real xi = bd.rounding + rp - d.distance;  // eq. 44
    if (xi <= 0) {
      c.history.setZero();
      c.force.setZero();
      continue;
    }
    // Contact point: the middle of the overlap along the normal (eq. 41 for a disk).
    c.point = d.point + (bd.rounding - xi / 2) * d.normal;
    const Vec2 v = Vec2(P.vx[p], P.vy[p]) - B.velocityAt(b, c.point);
    const Real vn = v.dot(d.normal);
    const Real mp = P.mass[p];
    const Real m = bd.type == BodyType::kDynamic
                       ? mp * B.massProperties(b).mass / (mp + B.massProperties(b).mass)
                       : mp;
    const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(kn * m);
    const Real fn = std::fmax(kn * xi - gamma * vn, Real(0));
    c.history += (v - vn * d.normal) * s.dt;
    c.history -= c.history.dot(d.normal) * d.normal;
    Vec2 ft = -kt * c.history;
    const Real cap = bd.friction * fn;
    if (ft.norm() > cap) {
      ft *= ft.norm() > 0 ? cap / ft.norm() : 0;
      c.history = -ft / kt;
    }
    c.force = fn * d.normal + ft;              // eq. 43 on the point
    B.addMaterialForce(b, -c.force, c.point);  // eq. 49-50, equal and opposite
    on_material_ += c.force;
    ++active_;
  }
}

void ImpCoupling::addGridForces(CouplingStep& s) {
  const bool at_point = def_.scheme == CouplingScheme::kImpGrid;
  const Particles& P = s.particles;
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    for (const ContactPair& c : search_.pairs()) {
      if (c.force.x() == 0 && c.force.y() == 0) continue;
      // Fig. 17B: the nodes around the contact point that carry material; eq. 48 otherwise
      // (f_I += S_Ip f_p), also when no node around the contact point has mass.
      if (!at_point ||
          !detail::spreadPointLoad<K>(s.grid, c.point, P.half_size[c.particle], c.force))
        detail::spreadParticleForce<K>(s.grid, P, c.particle, c.force);
    }
  });
}

}  // namespace mpm_sdem
