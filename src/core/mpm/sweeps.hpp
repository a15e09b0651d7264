// The three sweeps over the points that make up most of an MPM step (issue 42): P2G, the USF
// stress-and-force sweep and G2P. Each is compiled once per SIMD target in sweeps.cpp (Google
// Highway's foreach_target: SSE4, AVX2, AVX-512 and a portable fallback) and the running CPU's
// best is chosen at run time, so that a build without -march=native runs them at the native
// build's speed and the same binary runs on any x86-64. Internal header of the core library.
#pragma once

#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/material.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/mpm/sleep.hpp"
#include "mpm_sdem/core/mpm/solver.hpp"
#include "mpm_sdem/core/mpm/tiles.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::detail {

// What P2G deposits: mass and momentum (eq. 18-19, with APIC's affine term of eq. 30 when
// affine), the internal force (eq. 13), or both.
struct P2GParts {
  bool momentum = true;
  bool force = true;
  bool affine = false;
};

struct G2PSettings {
  Real pic_fraction;  // kFlip: alpha of eq. 28
  Real dt;
  Vec2 lo, hi;              // domain box: points are kept inside it
  bool periodic_x = false;  // a point leaving by the left or right side enters by the other
  Real keep = 1;            // kAsflip: share of the departure kept this step (asflipKeep)
  const std::vector<PointRun>* awake = nullptr;  // only these points (some sleep), or all
};

// P2G over the tiles T (the SPH particles of the transition band included, seed 001 sec. 4).
void particleToGrid(KernelType kernel, P2GParts parts, const Particles& P, Grid& G, const Tiles& T);

// The side walls' load (transfer.hpp, sidewallForce) a stress sweep adds to load (N per metre,
// per node; the caller zeroes it), with coefficient 2 mu_w / W; none without load.
struct SidewallLoad {
  Real coefficient = 0;  // 1/m
  Real* load = nullptr;
};

// USF's middle (seed 000 sec. 2.2): each point's L_p from the pre-kick grid velocity, its stress
// over dt (none when dt = 0) and the new stress's internal force on the nodes; and, given walls,
// the new pressure's side-wall load. With gradient_given, each point's L_p is taken as it is
// (set beforehand: volumetric_average.hpp) instead of summed from the grid.
void stressAndInternalForce(KernelType kernel, Particles& P, Grid& G, const Tiles& T,
                            const std::vector<MaterialParams>& materials, Real dt,
                            SidewallLoad walls = {}, bool gradient_given = false);

// G2P in the scheme's way, moving every point; with gradient (USL) also L_p from the post-kick
// velocity. Points outside the domain box are clamped onto it (counted in clamped); a
// non-finite position is not taken and clears finite. Without T every particle in storage
// order; with it (SPH present) the material points of each tile.
void gridToParticle(KernelType kernel, TransferScheme scheme, bool gradient, Particles& P,
                    const Grid& G, const G2PSettings& s, long& clamped, bool& finite,
                    const Tiles* T = nullptr);

// Tests only: G2P one point at a time with rows of four nodes instead of across points, the
// two ways test_simd_targets checks give the same bits.
void setRowSweepsForTest(bool rows);
bool rowSweepsForTest();

// The SIMD target the sweeps run on here, as Highway names it ("AVX3", "AVX2", "SSE4", ...):
// the targets round differently (fused multiply-adds), so checkpoints record it.
const char* simdTarget();

}  // namespace mpm_sdem::detail
