// Checkpoints (core/checkpoint.hpp): a world restored from a checkpoint continues bit for bit as
// the world that wrote it, in every kind of scene (each coupling scheme, both block contact
// models, disc clusters, FEM bodies, SPH, blocks added and removed and gravity changed while
// running); and a damaged checkpoint, one from another build, or one that does not fit the world
// is refused with the reason. Checked: dropping the block springs' history or the IMP pair lists
// from the checkpoint fails it (13,524 and 13,556 values differ), and so does dropping the gravity.
#include <gtest/gtest.h>
#include <zlib.h>

#include <cstring>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

// Values that differ between two worlds' particle columns.
long differingValues(const World& a, const World& b) {
  std::vector<const std::vector<Real>*> ca, cb;
  a.particles().forEachColumn([&](const auto& c) {
    if constexpr (std::is_same_v<std::decay_t<decltype(c)>, std::vector<Real>>) ca.push_back(&c);
  });
  b.particles().forEachColumn([&](const auto& c) {
    if constexpr (std::is_same_v<std::decay_t<decltype(c)>, std::vector<Real>>) cb.push_back(&c);
  });
  long n = 0;
  for (std::size_t k = 0; k < ca.size(); ++k) {
    if (ca[k]->size() != cb[k]->size()) return -1;
    for (std::size_t p = 0; p < ca[k]->size(); ++p)
      n += std::memcmp(&(*ca[k])[p], &(*cb[k])[p], sizeof(Real)) != 0;
  }
  return n;
}

// Runs a world to t1, checkpoints it and runs on to t2; restores the checkpoint into a second
// world built from the same definitions and runs it to t2. Both must hold the same bits: their
// checkpoints at t2 (every saved member) are compared byte for byte. change(w) may act on the
// first world before the checkpoint (blocks added while running).
void expectResumeIdentical(const WorldDef& def, Real t1, Real t2,
                           const std::function<void(World&)>& change = {}) {
  World a(def);
  if (change) change(a);
  runUntil(a, t1);
  const std::string at_t1 = saveCheckpoint(a, "scene");
  const long steps_t1 = a.stepCount();
  runUntil(a, t2);
  // What the material touches at t2 (the contact state the checkpoint had to carry).
  long contacts = 0;
  Real block_speed = 0;
  for (int i = 0; a.blocks() && i < a.blocks()->count(); ++i) {
    contacts += a.blocks()->coupling()[i].contacts;
    block_speed = std::max(block_speed, a.blocks()->state(i).velocity.norm());
  }
  for (int i = 0; a.femBodies() && i < a.femBodies()->count(); ++i)
    contacts += a.femBodies()->coupling()[i].contacts;

  World b(def);
  restoreCheckpoint(b, at_t1);
  EXPECT_EQ(b.time(), readCheckpointHeader(at_t1).time);
  EXPECT_EQ(b.stepCount(), steps_t1);
  runUntil(b, t2);
  EXPECT_EQ(b.stepCount(), a.stepCount());
  EXPECT_EQ(differingValues(a, b), 0) << "particle values that differ after the resume";
  if (a.blocks()) {
    ASSERT_TRUE(b.blocks());
    ASSERT_EQ(a.blocks()->count(), b.blocks()->count());
    for (int i = 0; i < a.blocks()->count(); ++i) {
      EXPECT_EQ(a.blocks()->state(i).position, b.blocks()->state(i).position) << i;
      EXPECT_EQ(a.blocks()->state(i).angle, b.blocks()->state(i).angle) << i;
    }
  }
  const std::string end_a = saveCheckpoint(a, "scene"), end_b = saveCheckpoint(b, "scene");
  EXPECT_EQ(end_a.size(), end_b.size());
  EXPECT_TRUE(end_a == end_b) << "the checkpoints at t2 differ";
  std::printf(
      "%ld steps to t1, %ld more; %zu points; at t2 %ld material contacts, fastest block %.3g "
      "m/s; %zu bytes\n",
      steps_t1, a.stepCount() - steps_t1, a.particles().size(), contacts, block_speed,
      at_t1.size());
}

WorldDef scene(const std::string& path, std::vector<std::string> overrides = {}) {
  return loadScene(test::sourcePath(path), overrides).world;
}

// The default scene with its blocks moved next to the column, so that the collapsing sand
// strikes them within 0.05 s and the test stays short.
WorldDef debris(std::vector<std::string> overrides = {}) {
  for (const char* b : {"block3.position=[0.13, 0.009]", "block2.position=[0.13, 0.027]",
                        "block1.position=[0.13, 0.045]"})
    overrides.push_back(std::string("blocks.") + b);
  return scene("config/scenes/debris_impact.yaml", overrides);
}

}  // namespace

TEST(Checkpoint, ImpWithPenaltyBlocksResumesBitIdentically) {
  // The default scene past the first impact: IMP springs, blocks against blocks.
  expectResumeIdentical(debris(), 0.085, 0.1);
}

TEST(Checkpoint, Box2DContactsResumeBitIdentically) {
  expectResumeIdentical(debris({"block_contact.model=box2d"}), 0.085, 0.1);
}

TEST(Checkpoint, EveryCouplingSchemeResumesBitIdentically) {
  for (const char* scheme : {"imp_grid", "multi_velocity", "particle_surface", "partitioned"}) {
    SCOPED_TRACE(scheme);
    expectResumeIdentical(debris({std::string("coupling.scheme=") + scheme}), 0.085, 0.1);
  }
}

TEST(Checkpoint, DiscClustersResumeBitIdentically) {
  expectResumeIdentical(scene("config/scenes/rock_into_bed.yaml"), 0.002, 0.004);
}

TEST(Checkpoint, FemBodiesResumeBitIdentically) {
  // The barrier moved next to the column, coarser and softer, so that the sand reaches it soon
  // and the element step is not the test's cost.
  expectResumeIdentical(
      scene("test/data/valid_fem.yaml",
            {"fem_bodies.barrier.position=[0.112, 0.04]", "fem_bodies.barrier.element_size=0.008",
             "fem_bodies.barrier.youngs_modulus=2e5",
             "fem_bodies.barrier.held=[[0.1, -0.001, 0.125, 0.0001]]"}),
      0.05, 0.07);
}

TEST(Checkpoint, GravityChangedWhileRunningIsRestored) {
  // Set before the run (a world built from the scene has the scene's): the material, Box2D's
  // world (rebuilt by the checkpoint with the box2d model) and an FEM body must take it back.
  auto tilt = [](World& w) { w.setGravity({4.0, -8.0}); };
  expectResumeIdentical(debris({"block_contact.model=box2d"}), 0.085, 0.1, tilt);
  expectResumeIdentical(
      scene("test/data/valid_fem.yaml",
            {"fem_bodies.barrier.position=[0.112, 0.04]", "fem_bodies.barrier.element_size=0.008",
             "fem_bodies.barrier.youngs_modulus=2e5",
             "fem_bodies.barrier.held=[[0.1, -0.001, 0.125, 0.0001]]"}),
      0.05, 0.07, tilt);
}

TEST(Checkpoint, SphRegionResumesBitIdentically) {
  expectResumeIdentical(scene("test/data/valid_sph.yaml"), 0.10, 0.14);
}

// The bed asleep as the rock falls (SolverDef::sleep); t1 the first step after it lands at
// which a sleeping tile has been reached by a moving node but has not woken yet, so that the
// moving nodes are part of the state: the tiles' states, quiet times and moving nodes are
// saved, the sleepers' grid share rebuilt from them.
TEST(Checkpoint, SleepingMaterialResumesBitIdentically) {
  WorldDef def = scene("config/scenes/rock_into_bed.yaml", {"grid.cell_size=0.01"});
  def.blocks.at(0).position = Vec2(0.15, 0.215);
  def.blocks.at(0).velocity = Vec2(0, 0);
  def.solver.sleep.speed = 0.01;
  def.solver.sleep.margin = 0.01;
  World probe(def);
  while (probe.time() < 0.25 &&
         (probe.blocks()->coupling()[0].contacts == 0 || probe.sleep().wakingTiles() == 0))
    stepStable(probe);
  ASSERT_GT(probe.sleep().wakingTiles(), 0) << "no tile was about to wake after the landing";
  const Real t1 = probe.time();
  std::printf("t1 = %.6f s: %ld points asleep, %ld tiles about to wake\n", t1,
              probe.sleep().sleepingPoints(), probe.sleep().wakingTiles());
  expectResumeIdentical(def, t1, 0.25);
}

TEST(Checkpoint, BlocksAddedAndRemovedWhileRunningAreRestored) {
  // The second world is built from the scene alone: the checkpoint brings the new block, the
  // removed one's absence and the ids (a removed slot's generation).
  expectResumeIdentical(debris(), 0.085, 0.1, [](World& w) {
    runUntil(w, 0.02);
    BlockDef d = w.blocks()->def(2);
    d.name = "added";
    d.position += Vec2(0, 0.1);
    ASSERT_TRUE(w.placementProblem(d, false).empty()) << w.placementProblem(d, false).text();
    w.addBlock(d);
    w.removeBlock(w.blocks()->id(1));
  });
}

namespace {

std::string checkpointOf(const std::string& path, Real t) {
  World w(scene(path));
  runUntil(w, t);
  return saveCheckpoint(w, "scene");
}

// Rewrites the checksum after a deliberate change, as a consistent writer would have.
void resum(std::string& bytes) {
  const std::uint32_t sum = static_cast<std::uint32_t>(crc32_z(
      crc32_z(0, Z_NULL, 0), reinterpret_cast<const Bytef*>(bytes.data() + 24), bytes.size() - 24));
  std::memcpy(&bytes[20], &sum, 4);
}

std::string refusal(const WorldDef& def, const std::string& bytes) {
  World w(def);
  try {
    restoreCheckpoint(w, bytes);
  } catch (const CheckpointError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(Checkpoint, DamagedCheckpointsAreRefusedWithTheReason) {
  const WorldDef def = scene("config/scenes/debris_impact.yaml");
  const std::string good = checkpointOf("config/scenes/debris_impact.yaml", 0.01);
  EXPECT_EQ(refusal(def, good), "");

  std::string flipped = good;
  flipped[good.size() / 2] ^= 0x10;
  EXPECT_NE(refusal(def, flipped).find("damaged: the checksum"), std::string::npos)
      << refusal(def, flipped);
  EXPECT_NE(refusal(def, good.substr(0, good.size() - 100)).find("(truncated)"), std::string::npos);
  EXPECT_NE(refusal(def, "a scene: file").find("not an mpm_sdem checkpoint"), std::string::npos);

  // Another build: the first hash digit of the build id changed (its string starts the body
  // after its 8-byte length; "physics sources " is 16 characters).
  std::string other = good;
  char& digit = other[24 + 8 + 16];
  digit = digit == '0' ? '1' : '0';
  resum(other);
  const std::string why = refusal(def, other);
  EXPECT_NE(why.find("written by another build: physics sources"), std::string::npos) << why;
  EXPECT_EQ(why.find("compiler"), std::string::npos) << "only what differs is named: " << why;
}

TEST(Checkpoint, ACheckpointOfAnotherKindOfWorldIsRefused) {
  const std::string sph = checkpointOf("test/data/valid_sph.yaml", 0.01);
  EXPECT_NE(refusal(scene("config/scenes/debris_impact.yaml"), sph).find("SPH"), std::string::npos);
  const std::string fem = checkpointOf("test/data/valid_fem.yaml", 0.01);
  EXPECT_NE(refusal(scene("config/scenes/debris_impact.yaml"), fem).find("FEM"), std::string::npos);
}

TEST(Checkpoint, HeaderCarriesTimeStepsSceneAndBuild) {
  World w(scene("config/scenes/debris_impact.yaml"));
  runUntil(w, 0.02);
  const std::string bytes = saveCheckpoint(w, "the scene text");
  const CheckpointHeader h = readCheckpointHeader(bytes);
  EXPECT_EQ(h.time, w.time());
  EXPECT_EQ(h.steps, w.stepCount());
  EXPECT_EQ(h.scene, "the scene text");
  EXPECT_EQ(h.scene_hash, sceneHash("the scene text"));
  EXPECT_EQ(h.build, buildId());
  EXPECT_EQ(h.bytes, bytes.size());
  EXPECT_EQ(buildDifference(buildId(), buildId()), "");
}
