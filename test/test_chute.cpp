// Issue 41: granular flows with the mu(I) material.
//  - Steady uniform chute flow (periodic in x, rough base, gravity tilted by theta): the Bagnold
//    profile u(z) = (2/3) (I_theta / d) sqrt(phi g cos theta) [h^1.5 - (h - z)^1.5] with
//    I_theta = I_0 (tan theta - mu_s) / (mu_2 - tan theta) (Jop, Forterre & Pouliquen 2006).
//  - The side walls' friction (domain.sidewalls): the layer loses momentum at
//    2 mu_w / W sum_p p_p V_p, and stops when that has taken its momentum.
//  - Column collapse on a rough floor against the quasi-2D experiments' fits (disabled: open).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <vector>

#include "cases.hpp"
#include "helpers.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

namespace {
constexpr Real kG = 9.81, kDensity = 1500;
}  // namespace

// Glass beads of 4 mm (the continuum solution does not care; larger grains make the flow settle
// within 4 s: 0.39 m/s at the surface) 5 cm deep at 24 deg, from rest (cases::chute): the mean
// speed per layer against Bagnold's at 5 and 2.5 mm cells. Measured: 3.6% and 1.8% of the
// surface speed, the profile shifted up by a slip of about half a cell's shear at the base
// (first order). The bound, 2%, at the finer cell, and the error must shrink. (The
// report's `chute` case adds angles and cells: docs/method.md, Granular flows.) The start is
// symmetric and the rows of points stay alike; from a perturbed start see the disabled test below.
TEST(Chute, SteadyFlowFollowsBagnoldsProfile) {
  // The two cells at once (test/parallel_runs.hpp).
  const std::vector<cases::ChuteProfile> error = test::runAll<cases::ChuteProfile>(2, [](int k) {
    cases::Chute c;
    c.cell_size = k == 0 ? 0.005 : 0.0025;
    World w(cases::chute(c));
    runUntil(w, 4.0);
    return cases::chuteProfile(w, c);
  });
  for (int k = 0; k < 2; ++k) {
    cases::Chute c;
    c.cell_size = k == 0 ? 0.005 : 0.0025;
    std::printf("cell %.4g m: worst %.4f of the surface speed, top layer %.4f of Bagnold's\n",
                c.cell_size, error[k].worst, error[k].surface);
  }
  EXPECT_LT(error[1].worst, 0.02);
  EXPECT_LT(error[1].worst, error[0].worst);
}

// The same flow from a start perturbed by up to 10 um (2.5 mm cells): it should hold Bagnold's
// profile as the symmetric start does. It does not: the disturbance grows from the start, the
// points crowd while their J grows, and the top runs away (1.6% at 2.5 s, 32% at 4 s, 121% at
// 6 s; docs/method.md, Granular flows). Open in issue 41; kept disabled so that the fix has its
// test waiting (--gtest_also_run_disabled_tests runs it).
TEST(Chute, DISABLED_PerturbedStartStaysOnBagnoldsProfile) {
  cases::Chute c;
  c.cell_size = 0.0025;
  World w(cases::chute(c));
  perturbPositions(w.particles(), 1e-5, 1);
  runUntil(w, 6.0);
  const cases::ChuteProfile error = cases::chuteProfile(w, c);
  std::printf("perturbed: worst %.4f of the surface speed, top layer %.4f of Bagnold's\n",
              error.worst, error.surface);
  EXPECT_LT(error.worst, 0.02);
}

// The same box with the beads swapped for a Newtonian film (weakly compressible fluid, eta such
// that Nusselt's surface speed rho g sin(theta) h^2 / (2 eta) is Bagnold's, Re about 7): a film
// in a periodic box shorter than its depth is stable (Kapitza's waves are long), so the points'
// vertical speed, zero in the uniform film, must stay small; 1% of the surface speed is far above
// what the start from rest leaves (the symmetric start: below 1e-4 m/s at 1.25 s) and far below
// what grows today with ASFLIP (0.35 m/s at 2 s; APIC 0.011, docs/method.md, Granular flows). This
// is the sand's instability without the rheology; kept disabled until it is fixed.
TEST(Chute, DISABLED_PerturbedNewtonianFilmStaysUniform) {
  cases::Chute c;
  c.theta = 27 * M_PI / 180;
  c.cell_size = 0.0025;
  WorldDef def = cases::chute(c);
  MaterialDef& m = def.materials[0];
  const Real surface = cases::bagnold(c, c.depth, c.depth);
  m.model = MaterialModel::kFluid;
  m.viscosity = m.density * kG * std::sin(c.theta) * c.depth * c.depth / (2 * surface);
  m.tensile_strength = 100;
  World w(def);
  perturbPositions(w.particles(), 1e-5, 1);
  runUntil(w, 2.0);
  const Particles& P = w.particles();
  Real vy = 0;
  for (std::size_t p = 0; p < P.size(); ++p) vy = std::max(vy, std::abs(P.vy[p]));
  std::printf("film: max |v_y| %.4f m/s, surface speed %.4f m/s\n", vy, surface);
  EXPECT_LT(vy, 0.01 * surface);
}

// ASFLIP keeps every point's departure from the grid's field, and points whose grains have
// separated carry no stress, so nothing takes the agitation of a collapsed column's front away:
// with pure ASFLIP it still churns at 0.8 m/s after 3 s (1 cm cells, aspect 1). With the
// departure relaxed over 0.03 s (cases::granularColumn, as the granular scene) the deposit is at
// rest, every point below 1 cm/s, within 1.5 s, as the grains are within about a second.
TEST(ColumnCollapse, RelaxedAsflipDepositComesToRest) {
  cases::GranularColumn c;
  c.aspect = 1;
  c.cell_size = 0.01;
  for (const Real relaxation : {0.03, 0.0}) {
    WorldDef def = cases::granularColumn(c);
    def.solver.asflip_relaxation_time = relaxation;
    World w(def);
    const cases::ColumnDeposit d = cases::collapseColumn(w, c, relaxation > 0 ? 1.5 : 3.0);
    std::printf("relaxation %g s: fastest %.4f m/s at %.2f s\n", relaxation, d.max_speed, d.time);
    if (relaxation > 0)
      EXPECT_TRUE(d.at_rest);
    else
      EXPECT_GT(d.max_speed, 0.1);  // the case can fail: without relaxation it does not rest
  }
}

// A column of aspect ratio 1 (10 cm, 5 mm cells) collapses on a rough floor: the experiments
// (Lube et al. 2005, quasi-2D) find the run-out (L_inf - L0) / L0 = 1.2 a and the back wall's
// height kept, H_inf = H0 (a < 1.15). The bounds, 20% and 10%, are looser than the experiments'
// scatter about their fits and than the 2.5 mm run's difference from this one should be; the
// material must also be at rest (every point below 1 cm/s) by 3 s, as the grains are within
// about 1 s. It fails today: run-out 2.15, height 0.73, at rest at 0.96 s (docs/method.md, Granular
// flows); kept disabled until the granular material is fixed.
TEST(ColumnCollapse, DISABLED_AspectOneRunsOutAsTheExperiments) {
  cases::GranularColumn c;
  c.aspect = 1;
  World w(cases::granularColumn(c));
  const cases::ColumnDeposit d = cases::collapseColumn(w, c, 3.0);
  std::printf("run-out %.3f, height %.3f of L0, fastest %.3f m/s at %.2f s\n",
              (d.runout - c.length) / c.length, d.height / c.length, d.max_speed, d.time);
  EXPECT_NEAR((d.runout - c.length) / c.length / cases::lubeRunout(1), 1, 0.2);
  EXPECT_NEAR(d.height / c.length / cases::lubeHeight(1), 1, 0.1);
  EXPECT_TRUE(d.at_rest);
}

// A layer 5 cm deep sliding at 0.5 m/s on a slip floor (periodic in x) between side walls 20 cm
// apart with mu_w = 0.3: the walls take 2 mu_w / W sum_p p_p V_p of its momentum per second
// (each node's share of it, which sums to that by the partition of unity), within 1% over the
// sliding (the stress the load is read from lags the kick by a step); then the layer stops when
// that rate has taken its momentum, and stays stopped. Measured: the momentum lost over 0.1-0.4 s
// is the walls' impulse within 1.3e-4.
TEST(Sidewalls, TakeTheLayersMomentumAndStopItWithoutReversing) {
  const Real cell = 0.005, h = 0.05, v0 = 0.5;
  WorldDef def = test::box(Vec2(0, 0), Vec2(10 * cell, 1.6 * h), cell);
  def.domain.left.type = def.domain.right.type = WallType::kPeriodic;
  def.domain.sidewalls = {0.2, 0.3};
  def.solver.gravity = Vec2(0, -kG);
  def.solver.transfer = TransferScheme::kAsflip;
  def.materials = cases::chute(cases::Chute{}).materials;  // the chute's glass beads
  def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(10 * cell, h), 2));
  def.bodies[0].velocity = Vec2(v0, 0);
  World w(def);
  const Real p0 = measure(w).momentum.x();
  auto wallForce = [&] {
    const Particles& P = w.particles();
    Real f = 0;
    for (std::size_t p = 0; p < P.size(); ++p)
      f += std::fmax(0, -(P.sxx[p] + P.syy[p] + P.szz[p]) / 3) * P.volume0[p] * P.J[p];
    return 2 * 0.3 / 0.2 * f;
  };
  Real impulse = 0, lowest = p0, stopped_at = -1;
  Real window_start = -1, window_impulse = 0;
  while (w.time() < 1.5) {
    const Real dt = w.chooseTimeStep().dt;
    const Real f = wallForce();
    const Real before = measure(w).momentum.x();
    w.step(dt);
    const Real after = measure(w).momentum.x();
    lowest = std::min(lowest, after);
    if (w.time() > 0.1 && w.time() < 0.4) {  // sliding, the stress settled under its weight
      if (window_start < 0) window_start = before;
      window_impulse += f * dt;
      impulse = window_start - after;
    }
    if (stopped_at < 0 && after < 1e-6 * p0) stopped_at = w.time();
  }
  std::printf(
      "momentum lost over 0.1-0.4 s %.5f N s/m, the walls' load's impulse %.5f; stopped at "
      "%.3f s; lowest momentum %.3g of the start\n",
      impulse, window_impulse, stopped_at, lowest / p0);
  EXPECT_NEAR(impulse / window_impulse, 1, 0.01);
  // Stops when the load's rate, constant while the depth is, has taken the start's momentum
  // (measured 0.819 s against 0.817 s).
  EXPECT_NEAR(stopped_at, p0 / (window_impulse / 0.3), 0.02 * stopped_at);
  // The walls never push back; the layer's own shear strain, stored while its top and bottom
  // were braked unequally, springs back by 1.8e-4 of the momentum (measured) and then rests.
  EXPECT_GT(lowest, -1e-3 * p0);
  EXPECT_LT(std::abs(measure(w).momentum.x()), 1e-6 * p0);
}

// Periodic sides (WallType::kPeriodic): a spinning elastic disk drifting at 1 m/s without
// gravity crosses the seam of a 10 cm periodic domain twice; the same disk in a 40 cm domain
// with plain walls never meets one. Both copies of a node on the seam hold the sum of what the
// points give them, so the disk must not feel the seam: its kinetic and elastic energy end as in
// the wide domain, to round-off (the sums are taken in another order: 1e-9). Measured: equal to
// 12 digits; without the seam's sums it was 2% off.
TEST(Periodic, ASpinningDiskCrossesTheSeamAsIfThereWereNone) {
  auto run = [](bool periodic) {
    const Real width = periodic ? 0.1 : 0.4;
    WorldDef def = test::box(Vec2(0, 0), Vec2(width, 0.1), 0.01);
    if (periodic) def.domain.left.type = def.domain.right.type = WallType::kPeriodic;
    def.solver.gravity = Vec2(0, 0);
    def.materials.push_back(test::elastic(kDensity, 1.5e6, 0.25));
    def.bodies.push_back(test::disk(Vec2(0.05, 0.05), 0.03, 2));
    World w(def);
    Particles& P = w.particles();
    for (std::size_t p = 0; p < P.size(); ++p) {
      P.vx[p] = 1 - 20 * (P.y[p] - 0.05);
      P.vy[p] = 20 * (P.x[p] - 0.05);
    }
    runUntil(w, 0.2);  // 20 cm: twice around the periodic domain
    const Diagnostics d = measure(w);
    return std::array<Real, 2>{d.kinetic, d.elastic};
  };
  const auto periodic = run(true), wide = run(false);
  std::printf("kinetic %.12g / %.12g, elastic %.12g / %.12g\n", periodic[0], wide[0], periodic[1],
              wide[1]);
  EXPECT_NEAR(periodic[0] / wide[0], 1, 1e-9);
  EXPECT_NEAR(periodic[1] / wide[1], 1, 1e-9);
}
