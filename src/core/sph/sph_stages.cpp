#include "sph/sph_stages.hpp"

#include <limits>
#include <stdexcept>

namespace mpm_sdem::detail {

std::unique_ptr<SphState> startSph(const SphWorld& w) {
  const SphDef& d = w.sph;
  const Real R = 2 * (d.smoothing_length > 0 ? d.smoothing_length : w.grid.h);
  auto s = std::make_unique<SphState>();
  s->settings = {d.kernel, R, d.viscosity_alpha, d.viscosity_beta, d.corrected_gradient};
  s->sph_body.assign(w.bodies, 0);
  for (int b : d.bodies) {
    if (b < 0 || b >= w.bodies) throw std::invalid_argument("sph.bodies names no body");
    s->sph_body[b] = 1;
  }
  s->columns.resize(w.particles.size());
  assignKinds(d.regions, s->sph_body, w.particles);
  w.tiles.binByKind(w.particles, w.grid);  // the SPH ranges for the first step's bound
  w.tiles.activate();
  return s;
}

void binWithSph(SphState& s, const SphWorld& w) {
  assignKinds(w.sph.regions, s.sph_body, w.particles);
  w.tiles.binByKind(w.particles, w.grid);
  markBand(w.particles, w.grid, w.solver.kernel, w.tiles, s.stamp, ++s.now);
  w.tiles.activate();
}

void sphStress(SphState& s, const SphWorld& w, Real stress_dt) {
  sphVelocityGradient(w.particles, w.tiles, w.grid, s.settings, w.materials, stress_dt, s.columns,
                      s.pairs);
}

void sphForces(SphState& s, const SphWorld& w) {
  s.mu_max = sphAcceleration(w.particles, w.tiles, s.settings, w.materials, w.solver.gravity,
                             s.columns, s.pairs);
}

void sphMove(SphState& s, const SphWorld& w, Real dt, Real kick, long& clamped, bool& finite) {
  const G2PSettings g2p{w.solver.pic_fraction, dt, w.domain_min, w.domain_max};
  sphKickDrift(w.particles, w.tiles, s.columns, kick, w.solver.damping, g2p, clamped, finite);
}

Real sphStableStep(const SphState& s, const Particles& P, const Tiles& T,
                   const std::vector<MaterialParams>& materials, Real cfl) {
  // The SPH particles' signal speed over their smoothing length h_s = R / 2.
  const Real fastest = sphSignalSpeed(P, T, s.settings, materials, s.mu_max);
  return fastest > 0 ? cfl * s.settings.smoothingLength() / fastest
                     : std::numeric_limits<Real>::infinity();
}

}  // namespace mpm_sdem::detail
