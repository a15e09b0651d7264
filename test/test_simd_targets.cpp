// Issue 42: the point sweeps (sweeps.cpp) and the stress batch (stress_batch.cpp) are compiled once
// per SIMD target and the running CPU's best is chosen at run time. Forcing each compiled target
// in turn, as on a machine without AVX-512 or without AVX2, must give the same physics: the
// targets run the same source and differ only in how the compiler orders and fuses the
// arithmetic, so a collapsing Drucker-Prager column must end at the same positions to round-off
// amplified over the steps. A target that computed something else (a lane lost, a branch
// missed) would move points by the scale of their displacement, centimetres here.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "helpers.hpp"
#include "hwy/targets.h"
#include "mpm/sweeps.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

struct End {
  std::vector<Real> x, y, vx, vy;
  long steps = 0;
};

// A 0.1 x 0.2 m column of Drucker-Prager sand collapsing for 0.1 s (800 points): every sweep
// and both Drucker-Prager returns run.
End collapse(StressUpdate update, TransferScheme transfer, Vec2 size = Vec2(0.1, 0.2),
             int points_per_cell = 2, Real asflip_relaxation = 0) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.6, 0.3), 0.01);
  def.materials.push_back(test::druckerPrager(1500, 1e6, 0.3, 30, 0));
  def.bodies.push_back(test::rectangle(Vec2(0, 0), size, points_per_cell));
  def.solver.stress_update = update;
  def.solver.transfer = transfer;
  def.solver.asflip_relaxation_time = asflip_relaxation;
  World w(def);
  runUntil(w, 0.1);
  const Particles& P = w.particles();
  return {P.x, P.y, P.vx, P.vy, w.stepCount()};
}

// Runs the column under every target the build compiled and the CPU supports and compares
// each one's points with the first (the best) target's. A -march=native build compiles one
// target only: the portable build (MPM_SDEM_NATIVE=OFF, the default) compiles them all.
void expectSameOnEveryTarget(StressUpdate update, TransferScheme transfer) {
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  ASSERT_FALSE(targets.empty());
  End first;
  for (std::size_t k = 0; k < targets.size(); ++k) {
    hwy::SetSupportedTargetsForTest(targets[k]);
    const End end = collapse(update, transfer);
    if (k == 0) {
      first = end;
      continue;
    }
    ASSERT_EQ(end.x.size(), first.x.size());
    Real largest = 0;
    for (std::size_t p = 0; p < end.x.size(); ++p)
      largest = std::max(largest, std::hypot(end.x[p] - first.x[p], end.y[p] - first.y[p]));
    std::printf("%s against %s: %ld / %ld steps, largest distance %.3g m\n",
                hwy::TargetName(targets[k]), hwy::TargetName(targets[0]), end.steps, first.steps,
                largest);
    // Measured 2.5e-16 m after 1,015 steps (USF, APIC) and 8.8e-17 m after 1,042 (USL,
    // ASFLIP) between AVX-512 and SSE4 or the SSE2 fallback, AVX2 bit for bit; 1e-9 m leaves
    // room for other compilers and CPUs. A velocity 1e-4 too large in one target's APIC G2P
    // moved points by 0.84 mm.
    EXPECT_LT(largest, 1e-9) << hwy::TargetName(targets[k]);
  }
  hwy::SetSupportedTargetsForTest(0);  // back to the CPU's own choice
  std::printf("%zu targets compared\n", targets.size());
}

// G2P of the quadratic B-spline runs across points, its sums gathered from the nodes
// (laneSums in sweeps.cpp); the other kernels, and the points of tiles with SPH, one point at a
// time with rows of four nodes (rowSums). Both orders of the same arithmetic, so the column
// must end with the same bits either way: a difference in one rounding grows over the 1,000
// steps into a difference in the last digits, so this tells apart any change of an operation,
// its order or a fused multiply-add. 495 points (3 x 3 per cell): the last vector holds fewer
// points than lanes on every target (8, 4 or 2 lanes).
void expectLanesEqualRows(StressUpdate update, TransferScheme transfer, Real relaxation = 0) {
  const Vec2 size(0.05, 0.11);
  detail::setRowSweepsForTest(true);
  const End rows = collapse(update, transfer, size, 3, relaxation);
  detail::setRowSweepsForTest(false);
  const End lanes = collapse(update, transfer, size, 3, relaxation);
  ASSERT_EQ(lanes.steps, rows.steps);
  ASSERT_EQ(lanes.x.size(), rows.x.size());
  long differ = 0;
  for (std::size_t p = 0; p < rows.x.size(); ++p)
    differ += lanes.x[p] != rows.x[p] || lanes.y[p] != rows.y[p] || lanes.vx[p] != rows.vx[p] ||
              lanes.vy[p] != rows.vy[p];
  std::printf("%s: %ld steps, %ld of %zu points differ\n", detail::simdTarget(), rows.steps, differ,
              rows.x.size());
  EXPECT_EQ(differ, 0);
}

}  // namespace

// Every scheme, USF and USL, on the CPU's own target, and ASFLIP with its departure relaxed
// (keep < 1, as the granular scenes); APIC with USF and ASFLIP with USL, as the tests below, on
// every other target compiled.
TEST(SimdTargets, G2pAcrossPointsEqualsRowsBitForBit) {
  for (const TransferScheme t : {TransferScheme::kPic, TransferScheme::kFlip, TransferScheme::kApic,
                                 TransferScheme::kAsflip}) {
    expectLanesEqualRows(StressUpdate::kUsf, t);
    expectLanesEqualRows(StressUpdate::kUsl, t);
  }
  expectLanesEqualRows(StressUpdate::kUsl, TransferScheme::kAsflip, 0.03);  // departure relaxed
  const std::vector<int64_t> targets = hwy::SupportedAndGeneratedTargets();
  for (std::size_t k = 1; k < targets.size(); ++k) {
    hwy::SetSupportedTargetsForTest(targets[k]);
    expectLanesEqualRows(StressUpdate::kUsf, TransferScheme::kApic);
    expectLanesEqualRows(StressUpdate::kUsl, TransferScheme::kAsflip);
  }
  hwy::SetSupportedTargetsForTest(0);
}

TEST(SimdTargets, UsfApicColumnIsTheSameOnEveryTarget) {
  expectSameOnEveryTarget(StressUpdate::kUsf, TransferScheme::kApic);
}

TEST(SimdTargets, UslAsflipColumnIsTheSameOnEveryTarget) {
  expectSameOnEveryTarget(StressUpdate::kUsl, TransferScheme::kAsflip);
}
