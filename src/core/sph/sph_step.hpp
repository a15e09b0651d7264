// The SPH side of seed 001's coupled step: particle kinds, the transition band, and the SPH sums
// for the velocity gradient (eq. 2.9), the stress (the MPM side's constitutive models) and the
// momentum equation (eq. 2.6-2.8). Internal header of the core library; sph_stages.hpp calls these
// for World's step.
#pragma once

#include <cstdint>
#include <vector>

#include "mpm/transfer.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/sph/sph.hpp"

namespace mpm_sdem::detail {

// Per-particle columns the SPH sums keep between their two passes; sized like the particles and
// read only at SPH particles.
struct SphColumns {
  std::vector<Real> cxx, cxy, cyx, cyy;  // kernel gradient correction C_a (identity: none)
  std::vector<Real> ax, ay;              // acceleration of the last force pass (m/s^2)
  void resize(std::size_t n);
};

// The neighbour pairs of the first pass, kept for the second: both read the positions x^n, so
// the second pass reads the pairs (in the first pass's order) instead of searching again. Each
// thread appends to its own list; an SPH particle's pairs are count[a] entries of list[a]'s
// list from start[a]. Scratch of one step, not checkpointed (each step's first pass fills it).
struct SphPairs {
  struct Pair {
    int b;
    Real gx, gy;  // grad W_ab with respect to x_a (1/m^3)
  };
  // One per thread, each on cache lines of its own: a push writes the list's end, and two
  // threads writing one line would pass it between their cores at every pair.
  struct alignas(64) List {
    std::vector<Pair> pairs;
  };
  std::vector<List> lists;
  std::vector<int> list, start, count;  // per particle, read only at SPH particles
};

struct SphSettings {
  SphKernel kernel = SphKernel::kCubicSpline;
  Real support = 0;  // kernel radius R (m), at most Tiles::kSize cells
  Real alpha = 0, beta = 0;
  bool corrected = true;
  Real smoothingLength() const { return Real(0.5) * support; }  // h_s = R / 2
};

// The World's SPH state: settings, which bodies are SPH, the columns and the last force pass.
struct SphState {
  SphSettings settings;
  std::vector<char> sph_body;  // per body: all its points are SPH particles
  SphColumns columns;
  SphPairs pairs;                    // the first pass's pairs for the second (scratch)
  std::vector<std::uint32_t> stamp;  // markBand's node scratch
  std::uint32_t now = 0;
  Real mu_max = 0;  // the last force pass's largest approach |mu_ab| (m/s)
  // What a checkpoint keeps (the stamps are scratch of each step's band).
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(columns.cxx, columns.cxy, columns.cyx, columns.cyy, columns.ax, columns.ay, mu_max);
  }
};

// Sets each particle's kind from its body (sph_body[b] != 0) and the regions; a particle that
// changes kind starts without an APIC affine matrix (only material points carry one).
void assignKinds(const std::vector<ShapeDef>& regions, const std::vector<char>& sph_body,
                 Particles& P);

// The transition band of seed 001 sec. 4: an SPH particle takes part in the grid sums when its
// MPM stencil reaches a node that a material point's stencil reaches, so that every node a
// material point reads has its whole partition of unity; with the seed's linear shape functions
// that is the one cell width the seed names, with the quadratic B-spline one and a half. Moves
// those particles to the front of their tile's SPH entries and sets Tiles::grid_end; stamp is a
// per-node scratch (a node is reached when stamp == now).
void markBand(const Particles& P, const Grid& G, KernelType kernel, Tiles& T,
              std::vector<std::uint32_t>& stamp, std::uint32_t now);

// First pass over the SPH particles: L_a from the velocities of every neighbour within R,
// material points included (eq. 2.9 with the correction), then the stress and volume over
// stress_dt by the material's own update (updatePointStress), as the material points do in
// stressAndInternalForce.
// The pairs it finds are kept in pairs for the second pass.
void sphVelocityGradient(Particles& P, const Tiles& T, const Grid& G, const SphSettings& s,
                         const std::vector<MaterialParams>& materials, Real stress_dt,
                         SphColumns& c, SphPairs& pairs);

// Second pass: each SPH particle's acceleration from the stresses of its neighbours (eq. 2.6)
// with the artificial viscosity (eq. 2.7-2.8) and gravity, into c.ax, c.ay, over the first
// pass's pairs. Returns the largest |mu_ab| of an approaching pair (m/s), for the viscous term
// of the time step.
Real sphAcceleration(const Particles& P, const Tiles& T, const SphSettings& s,
                     const std::vector<MaterialParams>& materials, const Vec2& gravity,
                     SphColumns& c, const SphPairs& pairs);

// v += kick a (with local damping, as the grid's nodes get it), x += dt v.
void sphKickDrift(Particles& P, const Tiles& T, const SphColumns& c, Real kick, Real damping,
                  const G2PSettings& s, long& clamped, bool& finite);

// The largest signal speed over the SPH particles, c_a + |v_a| + 1.2 (alpha c_a + beta mu_max)
// (Monaghan's 1992 bound with the artificial viscosity), for dt = kappa_1 h_s / that.
Real sphSignalSpeed(const Particles& P, const Tiles& T, const SphSettings& s,
                    const std::vector<MaterialParams>& materials, Real mu_max);

}  // namespace mpm_sdem::detail
