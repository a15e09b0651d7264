// Sleeping material (SolverDef::sleep, docs/method.md, Sleeping material): a bed at rest sleeps,
// keeps its share of the grid and wakes before a load reaches it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "block_helpers.hpp"
#include "helpers.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

// The rock_into_bed scene's bed (Drucker-Prager sand, 8 cm deep) at 1 cm cells, its rock let
// go at rest 12 cm above the bed: the bed comes to rest (and may sleep) before the rock lands
// at 1.5 m/s.
struct Drop {
  Real deepest = 1e9;     // lowest centre of the rock (m)
  Real rest = 0;          // its centre at the end (m)
  Real peak_force = 0;    // largest upward force of the bed on the rock (N/m)
  Real impact_force = 0;  // mean upward force over the first 20 ms after landing (N/m)
  Real final_force = 0;   // mean upward force over the last 0.1 s (N/m)
  long asleep_at_impact = 0, fewest_asleep = 1 << 30, asleep_at_end = 0, steps = 0;
};

Drop drop(Real sleep_speed, Real margin, Real step_factor) {
  WorldDef def =
      loadScene(test::sourcePath("config/scenes/rock_into_bed.yaml"), {"grid.cell_size=0.01"})
          .world;
  def.blocks.at(0).position = Vec2(0.15, 0.215);
  def.blocks.at(0).velocity = Vec2(0, 0);
  def.time_step.cfl *= step_factor;
  def.time_step.contact_factor *= step_factor;
  def.solver.sleep.speed = sleep_speed;
  def.solver.sleep.margin = margin;
  World w(def);
  Drop d;
  Real impulse = 0, span = 0, impact = 0, landing = 0;
  bool landed = false;
  while (w.time() < 0.6 - 1e-12) {
    const StepInfo s = stepStable(w, 0.6);
    EXPECT_TRUE(s.finite);
    if (!s.finite) break;
    ++d.steps;
    const BlockState& b = w.blocks()->state(0);
    d.deepest = std::min(d.deepest, b.position.y());
    const Real force = w.blocks()->coupling()[0].force.y();
    d.peak_force = std::max(d.peak_force, force);
    if (!landed && force > 0) {
      landed = true;
      landing = w.time() - s.dt;
      d.asleep_at_impact = w.sleep().sleepingPoints();
    }
    if (landed && w.time() <= landing + 0.02) impact += force * s.dt;
    if (landed) d.fewest_asleep = std::min(d.fewest_asleep, w.sleep().sleepingPoints());
    if (w.time() > 0.5) {
      impulse += force * s.dt;
      span += s.dt;
    }
  }
  d.rest = w.blocks()->state(0).position.y();
  d.final_force = impulse / span;
  d.impact_force = impact / 0.02;
  d.asleep_at_end = w.sleep().sleepingPoints();
  std::printf(
      "sleep %g m/s, margin %g m, step x%g: %ld steps, %ld points asleep at impact, %ld fewest "
      "after, %ld at the end; deepest "
      "%.3f mm, rest %.3f mm, peak force %.1f N/m, impact %.1f N/m, final %.2f N/m\n",
      sleep_speed, margin, step_factor, d.steps, d.asleep_at_impact, d.fewest_asleep,
      d.asleep_at_end, 1e3 * d.deepest, 1e3 * d.rest, d.peak_force, d.impact_force, d.final_force);
  return d;
}

}  // namespace

// The rock lands on a bed that sleeps but for the tiles within 1 cm of the rock's box, so the
// wave of the impact must wake the rest in time. Each figure must stay closer to the awake run's
// than the awake run is to itself at half the step (its own discretisation error).
TEST(Sleep, ARockLandsOnASleepingBedAsOnAnAwakeOne) {
  const Drop awake = drop(0, 0, 1), asleep = drop(0.01, 0.01, 1), half = drop(0, 0, 0.5);
  EXPECT_GT(asleep.asleep_at_impact, 800) << "of 960 points: the bed did not sleep";
  EXPECT_LT(asleep.fewest_asleep, asleep.asleep_at_impact) << "the impact woke no tile";
  EXPECT_GT(asleep.asleep_at_end, 0) << "the bed did not sleep again";
  EXPECT_LT(std::abs(asleep.deepest - awake.deepest), std::abs(half.deepest - awake.deepest));
  EXPECT_LT(std::abs(asleep.rest - awake.rest), std::abs(half.rest - awake.rest));
  EXPECT_LT(std::abs(asleep.impact_force - awake.impact_force),
            std::abs(half.impact_force - awake.impact_force));
  // At rest the bed carries the rock's weight, sleeping or not.
  EXPECT_NEAR(asleep.final_force / awake.final_force, 1, 0.005);
}

// The weight of the sleepers reaches the floor through the grid share alone: an elastic column
// (test_column_stress's, 1 m high) settles under gravity with local damping; a static disc 5 cm
// above its top keeps the top two tiles awake (SleepDef::margin), so that the awake points rest
// on sleeping ones. If their share lacked the sleepers' mass or stress (or counted it twice), the
// awake points would fall or rise, wake the sleepers and never rest.
TEST(Sleep, AwakePointsRestOnASleepingColumn) {
  const Real W = 0.1, H = 1.0, rho = 1000, g = 9.81, h = 0.025;
  auto column = [&](Real sleep_speed) {
    WorldDef def = test::box(Vec2(0, 0), Vec2(W, 1.3 * H), h);
    def.domain.bottom.type = WallType::kSticky;
    def.solver.kernel = KernelType::kGimp;  // no boundary layer at the floor (ColumnStress)
    def.solver.transfer = TransferScheme::kPic;
    def.solver.gravity = Vec2(0, -g);
    def.solver.damping = 0.1;
    def.solver.sleep.speed = sleep_speed;
    def.materials.push_back(test::elastic(rho, 2e6, 0.3));
    def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(W, H), 2));
    def.blocks.push_back(
        test::diskBlock("guard", Vec2(0.5 * W, H + 0.07), 0.02, BodyType::kStatic, 2500));
    return def;
  };
  World awake(column(0)), sleeping(column(1e-3));
  const std::vector<Real> y0 = awake.particles().y;
  runUntil(awake, 2.0);
  runUntil(sleeping, 2.0);
  const Particles &A = awake.particles(), &S = sleeping.particles();
  Real wa = 0, ws = 0;
  for (std::size_t p = 0; p < y0.size(); ++p) {
    const Real exact = -rho * g * (H - y0[p]);
    wa = std::fmax(wa, std::abs(A.syy[p] - exact));
    ws = std::fmax(ws, std::abs(S.syy[p] - exact));
  }
  std::printf("worst stress error: awake %.3f%%, sleeping %.3f%% of rho g H\n",
              100 * wa / (rho * g * H), 100 * ws / (rho * g * H));
  const long n = static_cast<long>(S.size()), asleep = sleeping.sleep().sleepingPoints();
  std::printf("%ld of %ld points asleep at 2 s\n", asleep, n);
  ASSERT_GT(asleep, n / 2) << "the column did not sleep";
  ASSERT_LT(asleep, n) << "the guard did not keep the top awake";
  Real worst = 0;
  for (long p = 0; p < n; ++p) worst = std::fmax(worst, std::abs(S.syy[p] - A.syy[p]));
  std::printf("stress: largest difference from the awake column %.3g%% of rho g H\n",
              100 * worst / (rho * g * H));
  // Then one more second: the awake top stays at rest on the sleepers.
  const std::vector<Real> y = S.y;
  runUntil(sleeping, 3.0);
  Real moved = 0, fastest = 0;
  for (long p = 0; p < n; ++p) {
    moved = std::fmax(moved, std::abs(S.y[p] - y[p]));  // reported: the damped top still settles
    fastest = std::fmax(fastest, std::hypot(S.vx[p], S.vy[p]));
  }
  std::printf("over the next second: %ld asleep, largest move %.3g m, fastest point %.3g m/s\n",
              sleeping.sleep().sleepingPoints(), moved, fastest);
  EXPECT_EQ(sleeping.sleep().sleepingPoints(), asleep) << "the sleepers woke";
  EXPECT_LT(fastest, 1e-2 * 1e-3) << "the awake top is not at rest on the sleepers";
  // A sleeper keeps the stress it had when it fell asleep, which may hold a wave of particle
  // speed up to the sleep speed v_s: rho c v_s (c the P-wave speed, 51.9 m/s here, so 52 Pa or
  // 0.53% of rho g H); twice that for two waves crossing.
  const Real c = std::sqrt(2e6 * (1 - 0.3) / ((1 + 0.3) * (1 - 2 * 0.3)) / rho);
  EXPECT_LT(worst, 2 * rho * c * 1e-3);
}

// bodies[].initial_stress: geostatic. The blade's bed (Drucker-Prager sand, 16 cm at 5 mm cells)
// started at its own weight is at rest, where an unstressed one rings as its weight comes on;
// so only a bed started at rest can sleep at once.
TEST(Sleep, ABedStartedAtItsWeightIsAtRest) {
  auto fastestAt = [](bool geostatic, Real t) {
    WorldDef def = loadScene(test::sourcePath("config/scenes/excavator_blade.yaml")).world;
    def.blocks.clear();  // a level bed alone
    def.solver.sleep = SleepDef{};
    def.bodies.at(0) = test::rectangle(Vec2(0, 0), Vec2(0.4, 0.16), 2);
    def.bodies.at(0).geostatic = geostatic;
    World w(def);
    runUntil(w, t);
    Real fastest = 0;
    const Particles& P = w.particles();
    for (std::size_t p = 0; p < P.size(); ++p)
      fastest = std::fmax(fastest, std::hypot(P.vx[p], P.vy[p]));
    return fastest;
  };
  const Real unstressed = fastestAt(false, 0.05), at_rest = fastestAt(true, 0.05);
  std::printf("fastest point at 0.05 s: %.3g m/s unstressed, %.3g m/s from its weight\n",
              unstressed, at_rest);
  // The robot scenes' sleep speed is 5 mm/s: the bed from its weight must be below it.
  EXPECT_LT(at_rest, 0.005);
  EXPECT_GT(unstressed, 0.005);
}
