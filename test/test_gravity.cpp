// World::setGravity (a bed tilted or spun while running, the node's dynamic_reconfigure gravity):
// from the next step on, the material, a dynamic block and an FEM body in free flight each gain
// the momentum M g T of the new gravity; the change is logged as a command that applyCommand
// replays to the same bits; out-of-range gravity is refused and leaves the world as it was; a
// checkpoint carries it (test_checkpoint's ChangedGravityResumesBitIdentically).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

// A patch of material, a dynamic block and an FEM plate, far from each other and the walls.
const char* kScene = R"(
name: free_flight
domain: {min: [0.0, 0.0], max: [1.0, 1.0]}
grid: {cell_size: 0.02}
solver: {gravity: [0.0, -9.81]}
time: {end: 0.05, dt: auto, cfl: 0.3}
materials:
  - {name: rubber, model: linear_elastic, density: 1000, youngs_modulus: 1.0e5, poisson_ratio: 0.3}
bodies:
  - {name: patch, material: rubber, shape: rectangle, min: [0.1, 0.6], max: [0.2, 0.7]}
blocks:
  - {name: rock, type: dynamic, shape: box, size: [0.05, 0.05], rounding: 0.002,
     position: [0.5, 0.65], density: 2000}
coupling: {scheme: imp}
fem_bodies:
  - {name: plate, shape: box, size: [0.06, 0.02], position: [0.8, 0.65], element_size: 0.01,
     model: corotational, density: 1100, youngs_modulus: 1.0e6, poisson_ratio: 0.3}
)";

struct Momenta {
  Vec2 material{0, 0}, block{0, 0}, fem{0, 0};
  Real material_mass = 0, block_mass = 0, fem_mass = 0;
};

Momenta momenta(const World& w) {
  Momenta m;
  const Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    m.material += P.mass[p] * Vec2(P.vx[p], P.vy[p]);
    m.material_mass += P.mass[p];
  }
  m.block_mass = 1;  // the velocity of its centre of mass
  m.block = w.blocks()->state(0).velocity;
  const FemBodies& f = *w.femBodies();
  for (int k = 0; k < f.totalNodes(); ++k) {
    m.fem += f.nodeMass(k) * f.velocity(k);
    m.fem_mass += f.nodeMass(k);
  }
  return m;
}

}  // namespace

TEST(Gravity, EveryBodyFallsUnderTheNewGravityFromTheNextStep) {
  World w(parseScene(kScene, "free_flight").world);
  runUntil(w, 0.01);
  const Momenta before = momenta(w);
  const Time t0 = w.time(), v0 = w.velocityTime();
  const Vec2 g(3.0, -2.0);
  std::vector<WorldCommand> log;
  w.setCommandLog([&](const WorldCommand& c) { log.push_back(c); });
  w.setGravity(g);
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(log[0].kind, WorldCommand::Kind::kSetGravity);
  EXPECT_EQ(log[0].vector, g);
  EXPECT_EQ(log[0].time, t0);
  EXPECT_EQ(w.def().solver.gravity, g);
  runUntil(w, 0.03);
  const Momenta after = momenta(w);
  // The material's velocities lag its positions by half a step (leapfrog): they gained over
  // their own times' span. A change of gravity acts from the next kick on, which starts at the
  // velocities' time.
  const Real T = w.time() - t0, Tv = w.velocityTime() - v0;
  // Free flight: only gravity changes the momentum. The material's and the FEM body's are sums
  // in double precision (1e-9 relative). The block's velocity is Box2D's single precision,
  // which rounds each step's gain g h by up to 6e-8 of the speed (0.3 m/s): over the 330 steps
  // of T that is up to 3e-4 m/s^2 of the mean acceleration (1.75e-4 measured with g = -9.81).
  auto expectGain = [&](const Vec2& p0, const Vec2& p1, Real mass, Real T, Real tol,
                        const char* what) {
    const Vec2 gain = (p1 - p0) / (mass * T);
    EXPECT_NEAR(gain.x(), g.x(), tol) << what;
    EXPECT_NEAR(gain.y(), g.y(), tol) << what;
  };
  expectGain(before.material, after.material, before.material_mass, Tv, 1e-9, "material");
  expectGain(before.fem, after.fem, before.fem_mass, T, 1e-9, "FEM plate");
  expectGain(before.block, after.block, before.block_mass, T, 1e-3, "block");
  std::printf("over %.4g s: material %.12g %.12g, block %.9g %.9g m/s^2\n", T,
              (after.material - before.material).x() / (before.material_mass * Tv),
              (after.material - before.material).y() / (before.material_mass * Tv),
              (after.block - before.block).x() / (before.block_mass * T),
              (after.block - before.block).y() / (before.block_mass * T));
}

TEST(Gravity, TheLoggedCommandReplaysToTheSameBits) {
  const WorldDef def = parseScene(kScene, "free_flight").world;
  World a(def), b(def);
  std::vector<WorldCommand> log;
  runUntil(a, 0.01);
  runUntil(b, 0.01);
  a.setCommandLog([&](const WorldCommand& c) { log.push_back(c); });
  b.setCommandLog([](const WorldCommand&) {});  // a logged world counts its commands
  a.setGravity({0.5, -20});
  ASSERT_EQ(log.size(), 1u);
  EXPECT_EQ(applyCommand(b, log[0]), "");
  runUntil(a, 0.02);
  runUntil(b, 0.02);
  EXPECT_TRUE(saveCheckpoint(a, "s") == saveCheckpoint(b, "s"));
}

TEST(Gravity, OutOfRangeIsRefusedAndChangesNothing) {
  World w(parseScene(kScene, "free_flight").world);
  const std::string before = saveCheckpoint(w, "s");
  for (const Vec2& g : {Vec2(0, -2e4), Vec2(std::nan(""), 0), Vec2(INFINITY, 0)}) {
    EXPECT_FALSE(World::gravityProblem(g).empty());
    EXPECT_THROW(w.setGravity(g), std::invalid_argument);
    WorldCommand c;
    c.kind = WorldCommand::Kind::kSetGravity;
    c.vector = g;
    EXPECT_NE(applyCommand(w, c).find("cannot set gravity"), std::string::npos);
  }
  EXPECT_TRUE(saveCheckpoint(w, "s") == before);
  EXPECT_TRUE(World::gravityProblem({0, -9.81}).empty());
}
