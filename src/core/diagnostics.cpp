#include "mpm_sdem/core/diagnostics.hpp"

#include <cmath>
#include <cstdio>
#include <vector>

#include "mpm_sdem/core/fem/fem_bodies.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"

namespace mpm_sdem {

Real gaugeMass(const Particles& P, const MassGauge& g) {
  Real m = 0;
  const bool below = g.side == MassGauge::Side::kBelow;
  for (std::size_t p = 0; p < P.size(); ++p)
    m += (below ? P.y[p] < g.at : P.x[p] > g.at) ? P.mass[p] : 0;
  return m;
}

Diagnostics measure(const World& world) {
  const Particles& P = world.particles();
  const auto& params = world.materialParams();
  const Vec2 g = world.def().solver.gravity;
  const Vec2 base = world.def().domain.min;
  const bool apic = carriesAffine(world.def().solver.transfer);
  std::vector<char> reports_mach;  // per material, looked up once
  for (const MaterialParams& mp : params)
    reports_mach.push_back(materialTraits(mp.model).reports_mach);
  Diagnostics d;
  Real mx = 0, my = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Real m = P.mass[p];
    const Real v2 = P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p];
    d.kinetic += Real(0.5) * m * v2;
    const Stress s{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]};
    d.elastic += P.volume0[p] * P.J[p] * elasticEnergyDensity(params[P.material[p]], s);
    d.gravity -= m * (g.x() * (P.x[p] - base.x()) + g.y() * (P.y[p] - base.y()));
    d.momentum += m * Vec2(P.vx[p], P.vy[p]);
    // x_p x m v_p plus the affine part m (B_yx - B_xy), which is what the APIC transfer
    // carries to the grid as angular momentum.
    d.angular_momentum += m * (P.x[p] * P.vy[p] - P.y[p] * P.vx[p]);
    if (apic) d.angular_momentum += m * (P.byx[p] - P.bxy[p]);
    mx += m * P.x[p];
    my += m * P.y[p];
    d.mass += m;
    d.max_speed = std::fmax(d.max_speed, std::sqrt(v2));
    const MaterialParams& mp = params[P.material[p]];
    if (reports_mach[P.material[p]])
      d.max_mach = std::fmax(d.max_mach, std::sqrt(v2 / squaredWaveSpeed(mp, P.J[p])));
  }
  if (d.mass > 0) d.center_of_mass = Vec2(mx, my) / d.mass;
  if (const Blocks* B = world.blocks()) {
    for (int b = 0; b < B->count(); ++b) {
      if (B->def(b).type != BodyType::kDynamic) continue;
      const BlockState& s = B->state(b);
      const MassProperties& m = B->massProperties(b);
      const Real ke = Real(0.5) * (m.mass * s.velocity.squaredNorm() +
                                   m.inertia * s.angular_velocity * s.angular_velocity);
      d.block_kinetic += ke;
      d.kinetic += ke;
      d.gravity -= m.mass * g.dot(s.position - base);
      d.block_momentum += m.mass * s.velocity;
      d.angular_momentum += m.mass * cross(s.position, s.velocity) + m.inertia * s.angular_velocity;
    }
    d.momentum += d.block_momentum;
  }
  if (const FemBodies* F = world.femBodies()) {
    d.fem_kinetic = F->kineticEnergy();
    d.fem_strain = F->strainEnergy();
    d.kinetic += d.fem_kinetic;
    d.elastic += d.fem_strain;
    for (int k = 0; k < F->totalNodes(); ++k) {
      const Real m = F->nodeMass(k);
      const Vec2 x = F->position(k), v = F->velocity(k);
      d.gravity -= m * g.dot(x - base);
      d.momentum += m * v;
      d.angular_momentum += m * cross(x, v);
    }
  }
  d.finite = std::isfinite(d.kinetic) && std::isfinite(d.elastic) && std::isfinite(d.gravity) &&
             std::isfinite(d.angular_momentum) && d.momentum.allFinite() &&
             d.center_of_mass.allFinite();
  return d;
}

std::string machWarning(const Diagnostics& d, Real t) {
  if (!(d.max_mach > kMachWarning)) return "";
  char text[320];
  std::snprintf(text, sizeof text,
                "a fluid point reached Mach %.3f at t = %.4f s (its speed over its sound speed): "
                "density errs by about %.2g%%. Raise the material's sound_speed to 10 times the "
                "fastest flow (docs/scene_reference.md, fluid).",
                d.max_mach, t, 50 * d.max_mach * d.max_mach);
  return text;
}

}  // namespace mpm_sdem
