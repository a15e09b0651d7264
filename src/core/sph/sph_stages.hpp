// Seed 001's SPH particles as World runs them: their state built from the scene's definition,
// and the stages World calls in its step (sph_sort, sph_gradient, sph_forces, sph_move in
// step_stages.hpp; World times them). World passes what it holds (SphWorld) at each call: it is
// movable, so nothing here keeps a reference to it. Internal header of the core library.
#pragma once

#include <memory>
#include <vector>

#include "mpm/sweeps.hpp"
#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/sph/sph.hpp"
#include "sph/sph_step.hpp"

namespace mpm_sdem::detail {

// The parts of a World the SPH stages read and change.
struct SphWorld {
  Particles& particles;
  Grid& grid;
  Tiles& tiles;
  const std::vector<MaterialParams>& materials;
  const SolverDef& solver;
  const SphDef& sph;
  int bodies;  // the world's bodies of material (sph.bodies index them)
  Vec2 domain_min, domain_max;
};

// The state of the SPH particles named by w.sph (its checks made by World: sphProblem and the
// coupling scheme's), the points' kinds set and binned for the first step's bound. Throws
// std::invalid_argument for a body index out of range.
std::unique_ptr<SphState> startSph(const SphWorld& w);
// Kinds (a point may cross a region's edge), the bins by kind, and the transition band of
// seed 001 sec. 4 before the grid sums.
void binWithSph(SphState& s, const SphWorld& w);
// The SPH particles' velocity gradient, stress and volume over stress_dt (first pass).
void sphStress(SphState& s, const SphWorld& w, Real stress_dt);
// Their accelerations (second pass; before any point moves: the pairs are read at x^n).
void sphForces(SphState& s, const SphWorld& w);
// Their kick and drift over dt (kick: the velocity update's span).
void sphMove(SphState& s, const SphWorld& w, Real dt, Real kick, long& clamped, bool& finite);
// The SPH term of the stable step, kappa_1 h_s over the fastest signal speed (infinite when
// nothing moves).
Real sphStableStep(const SphState& s, const Particles& P, const Tiles& T,
                   const std::vector<MaterialParams>& materials, Real cfl);

}  // namespace mpm_sdem::detail
