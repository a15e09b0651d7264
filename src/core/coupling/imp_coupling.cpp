#include "coupling/imp_coupling.hpp"

#include <cmath>
#include <cstdio>

#include "mpm/transfer.hpp"
#include "mpm_sdem/core/coupling/restitution.hpp"
#include "state_archive.hpp"

namespace mpm_sdem {

ImpCoupling::ImpCoupling(const CouplingDef& def, const Vec2& lo, const Vec2& hi, Real cell_size)
    : Coupling(def) {
  search_.init(lo, hi, cell_size, def.contact_radius, def.verlet_distance);
}

bool ImpCoupling::springForce(ContactPair& c, int b, const CoreDistance& d, const Vec2& x,
                              const Vec2& v_centre, bool affine, const Particles& P,
                              const ContactBodies& B, Real dt, Real cell_size, Vec2& point,
                              Vec2& force) const {
  const int p = c.particle;
  const Real a = B.rounding(b);
  const bool exact = def_.normal_integration == ContactIntegration::kExact;
  // Eq. 44 with the point's radius r_p capped at its depth below the body's outline: the
  // points of the outermost layer then reach exactly to the true surface. With r_p alone a
  // body's lattice staircase touches a flat block along a whole row of points, a flat face
  // that friction cannot tip (a disk of 10 cells per radius slid without spinning at
  // mu < 0.2), and it floats r_p - h/(2 ppc) above the block.
  const Real xi = a + materialReach(P, p, def_.contact_radius) - d.distance;
  auto release = [&c] {
    c.history.setZero();
    return false;
  };
  if (xi <= 0 && !exact) return release();
  // Contact point: the middle of the overlap along the normal (eq. 41 for a disk), the
  // block's surface for a pair that only meets within the step.
  point = d.point + (a - std::fmax(xi, Real(0)) / 2) * d.normal;
  // The material's velocity at the contact point, not at the point's centre: v_p + L_p d
  // with the velocity gradient of the last transfer. A spinning body's centre moves slower
  // than its surface by omega times the depth, and a contact that read v_p saw a rolling
  // disk still slipping (it stopped slipping at omega (R - depth) = v, 5% too fast a spin at
  // 10 cells per radius).
  const Vec2 d_p = affine ? Vec2(point - x) : Vec2(0, 0);
  const Vec2 v_material(v_centre.x() + P.lxx[p] * d_p.x() + P.lxy[p] * d_p.y(),
                        v_centre.y() + P.lyx[p] * d_p.x() + P.lyy[p] * d_p.y());
  const Vec2 v = v_material - B.velocityAt(b, point);
  const Real vn = v.dot(d.normal);
  const Real scale = impSpringScale(def_.stiffness_per, P, p, cell_size);
  const Real kn = scale * def_.normal_stiffness, kt = scale * def_.tangential_stiffness;
  const Real m = reducedMass(P.mass[p] * inertia_scale_, B.mass(b));  // the point's inertia
  const Real gamma = 2 * B.dampingRatio(b) * std::sqrt(kn * m);
  // Eq. 43's normal force; exact: the step's mean force of the same spring-dashpot.
  const Real fn = exact ? clippedSpringImpulse(m, kn, gamma, xi, -vn, dt) / dt
                        : std::fmax(kn * xi - gamma * vn, Real(0));
  if (xi <= 0 && fn == 0) return release();
  c.history += (v - vn * d.normal) * dt;
  c.history -= c.history.dot(d.normal) * d.normal;
  Vec2 ft = -kt * c.history;
  const Real cap = B.friction(b) * fn;
  if (ft.norm() > cap) {
    ft *= ft.norm() > 0 ? cap / ft.norm() : 0;
    c.history = -ft / kt;
  }
  force = fn * d.normal + ft;  // eq. 43 on the point
  return true;
}

void ImpCoupling::beforeStep(CouplingStep& s) {
  const Particles& P = s.particles;
  ContactBodies& B = s.bodies;
  search_.update(P, B);
  active_ = 0;
  on_material_.setZero();
  if (subcycles()) return;  // the forces come in the substeps (correctGridVelocity)
  search_.forEachContact(P, B, [&](ContactPair& c, int b, const CoreDistance& d) {
    const int p = c.particle;
    const Vec2 x(P.x[p], P.y[p]);
    if (!springForce(c, b, d, x, Vec2(P.vx[p], P.vy[p]), true, P, B, s.dt, s.grid.h, c.point,
                     c.force)) {
      c.force.setZero();
      return;
    }
    B.applyForce(b, -c.force, c.point);  // eq. 49-50, equal and opposite
    on_material_ += c.force;
    ++active_;
  });
}

void ImpCoupling::addGridForces(CouplingStep& s) {
  if (subcycles()) return;
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

void ImpCoupling::beginSubcycle(CouplingStep& s) {
  const Particles& P = s.particles;
  Grid& G = s.grid;
  const bool at_point = def_.scheme == CouplingScheme::kImpGrid;
  substepping_.clear();
  detail::withKernel(s.kernel, [&](auto k) {
    using K = decltype(k);
    std::vector<ContactPair>& pairs = search_.pairs();
    search_.forEachContact(P, s.bodies, [&](ContactPair& c, int b, const CoreDistance& d) {
      c.force.setZero();
      Substepping g;
      g.pair = static_cast<int>(&c - pairs.data());
      const int p = c.particle;
      g.velocity = Vec2(P.vx[p], P.vy[p]);
      g.sph = s.isSph(p);
      if (!g.sph) {
        // The force's map to the grid is built where the point would touch the outline now;
        // it holds for the step, as the point's own stencil does in the transfers.
        const Vec2 x(P.x[p], P.y[p]);
        const Vec2 at = d.point + s.bodies.rounding(b) * d.normal;
        if (!at_point || !detail::pointLoadStencil<K>(G, at, P.half_size[p], g.stencil))
          detail::particleForceStencil<K>(G, P, p, at - x, g.stencil);
        // The grid's velocity at the contact (its mean rotation about the point included),
        // not the point's own: a FLIP-like transfer leaves the point a residual that does not
        // move it, and a spring reading it would push against motion that never happens.
        g.start = g.stencil.gather([&G](int i) { return Vec2(G.vel0_x[i], G.vel0_y[i]); });
        g.velocity = g.start;
        g.ramp = g.stencil.gather(
            [&G](int i) { return Vec2(G.vel_x[i] - G.vel0_x[i], G.vel_y[i] - G.vel0_y[i]); });
      }
      // A pair that cannot close its gap within the step takes no part in the substeps (most
      // of the Verlet list): the gap against twice the relative speed the step starts with
      // and gains from the held forces.
      const Real gap = d.distance - s.bodies.rounding(b) - materialReach(P, p, def_.contact_radius);
      const Real speed = g.velocity.norm() + g.ramp.norm() + s.bodies.velocityAt(b, d.point).norm();
      g.apart = gap > 2 * s.dt * speed;
      if (g.apart) c.history.setZero();  // as a substep that saw it apart would
      substepping_.push_back(g);
    });
  });
  if (impulse_x_.size() != G.mass.size()) {  // the first step, or a grid of another size
    impulse_x_.assign(G.mass.size(), 0);
    impulse_y_.assign(G.mass.size(), 0);
  }
}

void ImpCoupling::correctGridVelocity(CouplingStep& s) {
  if (!subcycles()) return;
  Particles& P = s.particles;
  ContactBodies& B = s.bodies;
  Grid& G = s.grid;
  beginSubcycle(s);
  const int n =
      s.dt > s.contact_substep ? static_cast<int>(std::ceil(s.dt / s.contact_substep)) : 1;
  const Real h = s.dt / n;
  auto where = [&](int g, int p) -> Vec2 { return Vec2(P.x[p], P.y[p]) + substepping_[g].shift; };
  // The velocity the grid's nodes have gained from the springs so far: impulse over mass.
  auto gained = [this, &G](int i) -> Vec2 {
    return G.mass[i] > 0 ? Vec2(impulse_x_[i], impulse_y_[i]) / G.mass[i] : Vec2(0, 0);
  };
  for (int k = 0; k < n; ++k) {
    // Eq. 43 at the substep's start, the reactions on the bodies (eq. 49-50), the impulses on
    // the grid around each point.
    search_.forEachContactAt(
        B, where,
        [&](int g, ContactPair& c, int b, const CoreDistance& d) {
          Substepping& sub = substepping_[g];
          const Vec2 x = where(g, c.particle);
          Vec2 point, force;
          if (!springForce(c, b, d, x, sub.velocity, sub.sph, P, B, h, G.h, point, force)) return;
          B.pushForce(b, -force, point);
          c.point = point;
          sub.impulse += h * force;
          if (!sub.sph) sub.stencil.spread(impulse_x_, impulse_y_, h * force);
        },
        [this](int g) { return substepping_[g].apart; });
    B.substep(h, s.body_substep, h / s.dt);
    // The points move with their grid over the substep: the held part of the step's velocity
    // change, and what the springs gave.
    const Real ramp = Real(k + 1) / n;
    for (Substepping& sub : substepping_) {
      if (sub.apart) continue;
      const int p = search_.pairs()[sub.pair].particle;
      sub.velocity = sub.sph ? Vec2(Vec2(P.vx[p], P.vy[p]) + sub.impulse / P.mass[p])
                             : Vec2(sub.start + ramp * sub.ramp + sub.stencil.gather(gained));
      sub.shift += h * sub.velocity;
    }
  }
  // The grid keeps the sum of the substeps' impulses; the blocks had minus each.
  for (Substepping& sub : substepping_) {
    for (int k = 0; k < sub.stencil.count; ++k) {
      const int i = sub.stencil.node[k];
      const Vec2 dv = gained(i);
      G.vel_x[i] += dv.x();
      G.vel_y[i] += dv.y();
      impulse_x_[i] = impulse_y_[i] = 0;  // once per node
    }
    ContactPair& c = search_.pairs()[sub.pair];
    if (sub.impulse.x() == 0 && sub.impulse.y() == 0) continue;
    c.force = sub.impulse / s.dt;  // the step's mean, for outputs and the records
    B.recordForce(c.shape, -c.force, c.point);
    if (sub.sph) {  // its own kick spans s.kick
      s.sph_ax[c.particle] += sub.impulse.x() / (P.mass[c.particle] * s.kick);
      s.sph_ay[c.particle] += sub.impulse.y() / (P.mass[c.particle] * s.kick);
    }
    on_material_ += c.force;
    ++active_;
  }
}

std::string ImpCoupling::settings() const {
  char text[160];
  std::snprintf(text, sizeof text, "contact radius %g m, Verlet distance %g m, k_n %g N/m",
                def_.contact_radius, def_.verlet_distance, def_.normal_stiffness);
  return text;
}

void ImpCoupling::saveState(cereal::BinaryOutputArchive& ar) {
  search_.stateIo(ar);
}
void ImpCoupling::loadState(cereal::BinaryInputArchive& ar) {
  search_.stateIo(ar);
}

}  // namespace mpm_sdem
