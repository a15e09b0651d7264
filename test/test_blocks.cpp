// Rigid blocks on their own: spheropolygon mass properties against closed forms, refusal of bad
// cores, a stack of three blocks that must come to rest under both contact models, momentum
// conserved in a free collision, and blocks added, moved and removed while running.
#include <gtest/gtest.h>

#include <chrono>

#include "block_helpers.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

TEST(Spheropolygon, DiskMass) {
  const MassProperties m = spheropolygonMass({Vec2(0.3, -0.2)}, 0.5, 2.0);
  EXPECT_NEAR(m.area, M_PI * 0.25, 1e-12);
  EXPECT_NEAR(m.centroid.x(), 0.3, 1e-12);
  EXPECT_NEAR(m.inertia, 0.5 * m.mass * 0.25, 1e-12);
}

TEST(Spheropolygon, RoundedRectangleMass) {
  // Core w x h swept by a: the area is wh + 2a(w + h) + pi a^2; the inertia is the sum of the
  // core, four edge strips and four quarter disks about the centre.
  const Real w = 2, h = 1, a = 0.25, rho = 3;
  const MassProperties m = spheropolygonMass(
      {Vec2(-w / 2, -h / 2), Vec2(w / 2, -h / 2), Vec2(w / 2, h / 2), Vec2(-w / 2, h / 2)}, a, rho);
  EXPECT_NEAR(m.area, w * h + 2 * a * (w + h) + M_PI * a * a, 1e-12);
  EXPECT_NEAR(m.centroid.norm(), 0, 1e-12);
  auto rect = [](Real bx, Real by, Real cx, Real cy) {  // polar moment about the origin
    return bx * by * (bx * bx + by * by) / 12 + bx * by * (cx * cx + cy * cy);
  };
  // Quarter disk of radius a at a corner (cx, cy): polar moment about its centre pi a^4 / 8, its
  // centroid 4a/(3 pi) along both axes outward.
  const Real qa = M_PI * a * a / 4, d = 4 * a / (3 * M_PI);
  const Real quarter_c = M_PI * a * a * a * a / 8 - qa * 2 * d * d;
  const Real corner = quarter_c + qa * ((w / 2 + d) * (w / 2 + d) + (h / 2 + d) * (h / 2 + d));
  const Real polar = rect(w, h, 0, 0) + 2 * rect(w, a, 0, h / 2 + a / 2) +
                     2 * rect(a, h, w / 2 + a / 2, 0) + 4 * corner;
  EXPECT_NEAR(m.inertia, rho * polar, 1e-12 * rho * polar);
}

TEST(Spheropolygon, OffCentreTriangleCentroid) {
  // Shifting the core shifts the centroid and leaves the inertia about it unchanged.
  const std::vector<Vec2> tri{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)};
  std::vector<Vec2> moved;
  for (const Vec2& v : tri) moved.push_back(v + Vec2(5, -3));
  const MassProperties a = spheropolygonMass(tri, 0.1, 1), b = spheropolygonMass(moved, 0.1, 1);
  EXPECT_NEAR((b.centroid - a.centroid - Vec2(5, -3)).norm(), 0, 1e-12);
  EXPECT_NEAR(b.inertia, a.inertia, 1e-9);
}

TEST(Spheropolygon, BadCoresAreRefused) {
  EXPECT_NE(coreProblem({}).text(), "");
  EXPECT_NE(coreProblem({Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0.8, 0.3)}).text(),
            "");                                                                        // concave
  EXPECT_NE(coreProblem({Vec2(0, 0), Vec2(1, 1), Vec2(1, 0), Vec2(0, 1)}).text(), "");  // crossing
  EXPECT_NE(coreProblem({Vec2(0, 0), Vec2(1, 0), Vec2(2, 0)}).text(), "");              // zero area
  std::vector<Vec2> nine;
  for (int i = 0; i < 9; ++i)
    nine.push_back(Vec2(std::cos(i * 2 * M_PI / 9), std::sin(i * 2 * M_PI / 9)));
  EXPECT_NE(coreProblem(nine).text(), "");
  nine.pop_back();
  EXPECT_EQ(coreProblem(nine).text(), "");
  EXPECT_EQ(coreProblem({Vec2(0, 0)}).text(), "");
  EXPECT_EQ(coreProblem({Vec2(0, 0), Vec2(1, 0)}).text(), "");
}

namespace {

// Three 2 cm x 1.8 cm wooden blocks (seed 003 Table 1: 500 kg/m^3) stacked on a static floor.
Real stackDrift(BlockContactModel model) {
  std::vector<BlockDef> defs;
  const Real a = 0.001;
  defs.push_back(test::boxBlock("floor", Vec2(0, -0.05), 0.4, 0.1, a, BodyType::kStatic, 500));
  for (int k = 0; k < 3; ++k) {
    defs.push_back(test::boxBlock("b" + std::to_string(k), Vec2(0, 0.009 + 0.018 * k), 0.02, 0.018,
                                  a, BodyType::kDynamic, 500));
    defs.back().restitution = 0.05;
    defs.back().friction = 0.6;
  }
  BlockContactDef contact;
  contact.model = model;
  contact.normal_stiffness = 1e6;
  contact.tangential_stiffness = 5e5;
  Blocks blocks(defs, contact, Vec2(0, -9.81));
  const Real m = blocks.massProperties(1).mass;
  const Real dt =
      contactTimeStep(0.5 * m, contact.normal_stiffness, restitutionDampingRatio(0.05), 4, 0.1);
  for (int n = 0; n < static_cast<int>(1.0 / dt); ++n) blocks.step(dt);
  // After 1 s: the stack is at rest and in place.
  Real worst = 0;
  for (int k = 1; k <= 3; ++k) {
    worst = std::max(worst, blocks.state(k).velocity.norm());
    worst = std::max(worst, std::abs(blocks.state(k).position.x()));
    worst = std::max(worst, std::abs(blocks.state(k).angle) * Real(0.02));
  }
  return worst;
}

}  // namespace

TEST(BlockStack, PenaltyModelHoldsAtRest) {
  // Velocities below 1 mm/s, sideways drift and tilt (as arc length) below 1 mm after 1 s.
  EXPECT_LT(stackDrift(BlockContactModel::kPenalty), 1e-3);
}

TEST(BlockStack, Box2DModelHoldsAtRest) {
  EXPECT_LT(stackDrift(BlockContactModel::kBox2D), 1e-3);
}

namespace {

// Two free disks, no gravity, nearly head-on at 1 m/s, restitution 0.8, penalty springs 1e6 N/m.
std::vector<BlockDef> collidingDisks() {
  std::vector<BlockDef> defs{test::diskBlock("a", Vec2(0, 0), 0.05, BodyType::kDynamic, 1000),
                             test::diskBlock("b", Vec2(0.2, 0.01), 0.05, BodyType::kDynamic, 1000)};
  defs[0].velocity = Vec2(1, 0);
  defs[0].restitution = defs[1].restitution = 0.8;
  return defs;
}

BlockContactDef stiffPenalty() {
  BlockContactDef contact;
  contact.normal_stiffness = 1e6;
  return contact;
}

}  // namespace

TEST(BlockCollision, PenaltyConservesMomentum) {
  // Momentum is exchanged, not created.
  Blocks blocks(collidingDisks(), stiffPenalty(), Vec2(0, 0));
  const Real m = blocks.massProperties(0).mass;
  const Vec2 p0 = m * blocks.state(0).velocity;
  for (int n = 0; n < 4000; ++n) {
    blocks.step(5e-5);
    const Vec2 p = m * (blocks.state(0).velocity + blocks.state(1).velocity);
    ASSERT_LT((p - p0).norm(), 1e-5 * p0.norm()) << "step " << n;  // single-precision Box2D
  }
  EXPECT_GT(blocks.state(1).velocity.x(), 0.5);  // they did collide
}

// Substeps (World steps longer than the block-block bound): one step of 4 dt in 4 substeps is
// the same Box2D sequence as 4 steps of dt, so the collision comes out the same up to the
// single-precision rounding of dt.
TEST(BlockCollision, SubstepsMatchShortSteps) {
  Blocks short_steps(collidingDisks(), stiffPenalty(), Vec2(0, 0));
  Blocks substeps(collidingDisks(), stiffPenalty(), Vec2(0, 0));
  const Real dt = 5e-5;
  ASSERT_LT(dt, short_steps.stableStep(0.1));
  for (int n = 0; n < 1000; ++n) {
    for (int k = 0; k < 4; ++k) short_steps.step(dt);
    ASSERT_EQ(substeps.step(4 * dt, dt * (1 + 1e-9)), 4);
  }
  EXPECT_GT(substeps.state(1).velocity.x(), 0.5);  // they did collide
  for (int b = 0; b < 2; ++b) {
    EXPECT_NEAR((substeps.state(b).position - short_steps.state(b).position).norm(), 0, 1e-6);
    EXPECT_NEAR((substeps.state(b).velocity - short_steps.state(b).velocity).norm(), 0, 1e-5);
  }
}

namespace {

// A disk of 0.2 mm at 1 kg/m^3 inside valid.yaml's domain, above its material.
BlockDef lightGrain() {
  BlockDef grain;
  grain.name = "grain";
  grain.core = {Vec2(0, 0)};
  grain.rounding = 2e-4;
  grain.density = 1;
  grain.position = Vec2(0.3, 0.15);
  return grain;
}

}  // namespace

// Subcycled springs do not bound the material's step, but one step holds at most 1000 of their
// substeps: a spawned obstacle too light for its springs (here 0.2 mm at 1 kg/m^3; the fuzzer
// found a light block whose 3 steps took over 10 s) shortens the step instead, as explicit
// springs do. Without the bound the limit stays the CFL term's.
TEST(RuntimeBlocks, ALightObstacleShortensTheSubcycledStep) {
  WorldDef def = loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/valid.yaml").world;
  def.coupling.normal_integration = ContactIntegration::kSubcycled;
  World world(def);
  const Real material = world.chooseTimeStep().dt;
  const BlockDef grain = lightGrain();
  ASSERT_EQ(world.placementProblem(grain, false).text(), "");
  world.addBlock(grain);
  const TimeStepChoice dt = world.chooseTimeStep();
  EXPECT_EQ(dt.limit, StepLimit::kContact);
  EXPECT_LT(dt.dt, material);
  const auto start = std::chrono::steady_clock::now();
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(stepStable(world).finite);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 1.0);
}

// The runner's and the node's step (Stepper): the light obstacle above shortens the step for
// good, and the guard measures from the first step after the blocks' layout changed, so the run
// goes on (in the node a spawn, in the runner a spawn replayed from a bag); a guard that kept the
// run's first step stops it at the same fraction. The steps land on the end time exactly.
TEST(RuntimeBlocks, TheStepGuardMeasuresFromTheFirstStepAfterASpawn) {
  WorldDef def = loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/valid.yaml").world;
  def.coupling.normal_integration = ContactIntegration::kSubcycled;
  World world(def);
  const Real fraction = 0.5;
  Stepper stepper(world, fraction);
  StepGuard kept(fraction);
  std::string problem;
  PlannedStep step = stepper.plan();
  ASSERT_EQ(step.problem, "");
  ASSERT_EQ(kept.problem(step.stable), "");
  stepper.take(step, problem);
  ASSERT_EQ(problem, "");
  const BlockDef grain = lightGrain();
  world.addBlock(grain);
  step = stepper.plan();
  ASSERT_LT(step.stable.dt, fraction * kept.reference());  // shortened below the stop
  EXPECT_EQ(step.problem, "");
  EXPECT_NE(kept.problem(step.stable).find("limits.step_collapse"), std::string::npos);
  const Time end = world.time() + 7.3 * step.stable.dt;
  while (world.time() < end) {
    step = stepper.plan(end);
    ASSERT_EQ(step.problem, "");
    ASSERT_TRUE(stepper.take(step, problem).finite);
    ASSERT_EQ(problem, "");
  }
  EXPECT_EQ(world.time(), end);
}

// Blocks added and removed while running (the node's obstacle services), in a scene that started
// without any: placement is checked, the block falls freely under Box2D's symplectic Euler
// (v += g dt, then y += v dt) until removed, and the time step follows: with explicit springs
// (the default) the block's contact term sets it; subcycled the material's term keeps it.
TEST(RuntimeBlocks, AddedToASceneWithoutBlocksFallsAndIsRemoved) {
  WorldDef def = loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/valid.yaml").world;
  {
    WorldDef sub = def;
    sub.coupling.normal_integration = ContactIntegration::kSubcycled;
    World subcycled(sub);
    BlockDef disk;
    disk.name = "stone";
    disk.core = {Vec2(0, 0)};
    disk.rounding = 0.01;
    disk.position = Vec2(0.3, 0.15);
    subcycled.addBlock(disk);
    EXPECT_EQ(subcycled.chooseTimeStep().limit, StepLimit::kCfl);
  }
  World world(def);  // explicit: one Box2D step per step
  ASSERT_EQ(world.blocks(), nullptr);
  EXPECT_EQ(world.chooseTimeStep().limit, StepLimit::kCfl);
  BlockDef disk;
  disk.name = "stone";
  disk.core = {Vec2(0, 0)};
  disk.rounding = 0.01;
  disk.position = Vec2(0.05, 0.05);  // inside the column of material
  EXPECT_NE(world.placementProblem(disk, false).text().find("material"), std::string::npos);
  disk.position = Vec2(0.395, 0.15);  // reaches past the right wall
  EXPECT_NE(world.placementProblem(disk, false).text().find("domain"), std::string::npos);
  disk.position = Vec2(0.3, 0.15);
  ASSERT_EQ(world.placementProblem(disk, false).text(), "");
  const BlockId id = world.addBlock(disk);
  ASSERT_EQ(world.blocks()->count(), 1);
  EXPECT_EQ(world.chooseTimeStep().limit, StepLimit::kContact);
  Real y = 0.15, v = 0;
  for (int n = 0; n < 2000; ++n) {
    const Real dt = world.chooseTimeStep().dt;
    world.step(dt);
    v += -9.81 * dt;
    y += v * dt;
  }
  // Box2D works in single precision: 2000 steps of rounding 6e-8 of ~8 units (56 units/m) add
  // up to 3e-6 m at worst; measured 2e-7 m.
  std::printf("after %.4f s: y %.7f m, symplectic Euler %.7f m\n", world.time(),
              world.blocks()->state(0).position.y(), y);
  EXPECT_NEAR(world.blocks()->state(0).position.y(), y, 1e-5);
  EXPECT_NEAR(world.blocks()->state(0).position.x(), 0.3, 1e-6);
  EXPECT_LT(y, 0.15 - 1e-2);  // it did fall
  world.removeBlock(id);
  EXPECT_EQ(world.blocks()->count(), 0);
  EXPECT_EQ(world.chooseTimeStep().limit, StepLimit::kCfl);
  EXPECT_TRUE(stepStable(world).finite);
}

// Static blocks may overlap (a wall of parts, as the silo's plates reaching into its walls),
// spawned as in a scene; a moving block may not start inside one (mayOverlap).
TEST(RuntimeBlocks, OnlyStaticBlocksMayOverlap) {
  WorldDef def = loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/valid.yaml").world;
  World world(def);
  world.addBlock(test::boxBlock("wall", Vec2(0.3, 0.1), 0.02, 0.1, 0.002, BodyType::kStatic));
  BlockDef plate = test::boxBlock("plate", Vec2(0.26, 0.06), 0.1, 0.02, 0.002, BodyType::kStatic);
  EXPECT_EQ(world.placementProblem(plate, false).text(), "");
  plate.type = BodyType::kDynamic;
  EXPECT_NE(world.placementProblem(plate, false).text().find("overlaps block 'wall'"),
            std::string::npos);
  plate.type = BodyType::kKinematic;
  EXPECT_NE(world.placementProblem(plate, false).text().find("overlaps block 'wall'"),
            std::string::npos);
}

// The step names a moving block whose centre leaves the domain (a disk thrown out of its top)
// while the state stays finite, and one whose state is no longer finite (a load of 1e300 N/m,
// beyond what single-precision Box2D holds). Neither a static floor reaching outside nor a disk
// resting on it, its outline pressed past the domain's bottom, is named.
TEST(RuntimeBlocks, StepNamesABlockOutsideTheDomainOrNotFinite) {
  World world(loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/test/data/valid.yaml").world);
  world.addBlock(test::boxBlock("floor", Vec2(0.2, -0.01), 0.5, 0.02, 0.002, BodyType::kStatic));
  const BlockId stone =
      world.addBlock(test::diskBlock("stone", Vec2(0.37, 0.05), 0.01, BodyType::kDynamic, 1000));
  StepInfo info;
  while (world.time() < 0.3 && info.block_problem.empty()) info = stepStable(world);
  EXPECT_EQ(info.block_problem, "");
  EXPECT_LT(world.blocks()->blockBounds(1).min.y(), 0) << "resting, pressed past the bottom";
  EXPECT_NEAR(world.blocks()->state(1).velocity.norm(), 0, 1e-3);
  world.setBlockPose(stone, Vec2(0.37, 0.185), 0);
  world.setBlockVelocity(stone, Vec2(0, 5), 0);
  for (int n = 0; n < 100 && info.block_problem.empty(); ++n) info = stepStable(world);
  EXPECT_TRUE(info.finite);
  EXPECT_NE(info.block_problem.find("block 'stone'"), std::string::npos) << info.block_problem;
  EXPECT_NE(info.block_problem.find("left the domain"), std::string::npos);
  world.setBlockPose(stone, Vec2(0.37, 0.1), 0);
  world.setBlockVelocity(stone, Vec2(0, 0), 0);
  world.addBlockLoad(stone, Vec2(1e300, 0), Vec2(0.37, 0.1), 0);
  info = stepStable(world);
  EXPECT_FALSE(info.finite);
  EXPECT_NE(info.block_problem.find("block 'stone': its position, angle or velocity is no longer "
                                    "finite"),
            std::string::npos)
      << info.block_problem;
}

// A kinematic block moves with its twist exactly: its pose is summed in double and handed to
// Box2D, whose own single-precision sum of these 10,000 steps drifts by 93 um and 2e-5 rad
// (measured). Left: one rounding of the pose to single precision, 6e-8 of 7 Box2D units (25
// units per metre here): 2e-8 m.
TEST(RuntimeBlocks, KinematicBlockFollowsItsTwist) {
  BlockDef blade = test::boxBlock("blade", Vec2(0.2, 0.1), 0.02, 0.02, 0.002, BodyType::kKinematic);
  blade.velocity = Vec2(0.05, -0.01);
  blade.angular_velocity = 0.3;
  Blocks blocks({blade, test::boxBlock("b", Vec2(0, 0), 0.04, 0.04, 0.002, BodyType::kDynamic)},
                BlockContactDef(), Vec2(0, 0));
  for (int n = 0; n < 10000; ++n) blocks.step(1.37e-4);
  const Real t = 1.37;
  EXPECT_NEAR((blocks.state(0).position - Vec2(0.2 + 0.05 * t, 0.1 - 0.01 * t)).norm(), 0, 5e-8);
  EXPECT_NEAR(blocks.state(0).angle, 0.3 * t, 1e-6);
}
