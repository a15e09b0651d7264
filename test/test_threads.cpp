// The step does not depend on the thread count: P2G sums every node colour by colour and, inside
// a tile, in particle order (Tiles), the sort is the serial stable one, and the other stages
// either work point by point or reduce with max / or. So one and two threads must give the same
// bits, in a pure-MPM scene and in the coupled default scene (IMP contacts, substepped blocks).
#include <gtest/gtest.h>
#include <omp.h>

#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

struct Snapshot {
  std::vector<std::vector<Real>> columns;
  std::vector<BlockState> blocks;
  long steps = 0;
};

Snapshot run(WorldDef def, int threads, Real end_time) {
  omp_set_num_threads(threads);
  def.solver.parallel_min_points = 0;  // share the work of these small worlds too
  World w(def);
  runUntil(w, end_time);
  const Particles& P = w.particles();
  Snapshot s;
  s.columns = {P.x, P.y, P.vx, P.vy, P.bxx, P.bxy, P.byx, P.byy, P.sxx, P.syy, P.sxy, P.szz, P.J};
  if (w.blocks()) {
    for (int b = 0; b < w.blocks()->count(); ++b) s.blocks.push_back(w.blocks()->state(b));
  }
  s.steps = w.stepCount();
  return s;
}

void expectIdentical(const Snapshot& a, const Snapshot& b) {
  ASSERT_EQ(a.steps, b.steps);
  ASSERT_EQ(a.columns.size(), b.columns.size());
  long differing = 0;
  for (std::size_t c = 0; c < a.columns.size(); ++c) {
    ASSERT_EQ(a.columns[c].size(), b.columns[c].size());
    for (std::size_t p = 0; p < a.columns[c].size(); ++p)
      differing += a.columns[c][p] != b.columns[c][p];
  }
  EXPECT_EQ(differing, 0) << "particle values that differ between 1 and 2 threads";
  ASSERT_EQ(a.blocks.size(), b.blocks.size());
  for (std::size_t k = 0; k < a.blocks.size(); ++k) {
    EXPECT_EQ(a.blocks[k].position.x(), b.blocks[k].position.x()) << "block " << k;
    EXPECT_EQ(a.blocks[k].position.y(), b.blocks[k].position.y()) << "block " << k;
    EXPECT_EQ(a.blocks[k].angle, b.blocks[k].angle) << "block " << k;
  }
  std::printf("%ld steps, %zu points, %zu blocks: %ld values differ\n", a.steps,
              a.columns[0].size(), a.blocks.size(), differing);
}

}  // namespace

// 1,600 points, 1,225 steps.
TEST(Threads, ElasticColumnIsBitIdenticalOnOneAndTwoThreads) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.6, 0.3), 0.01);
  def.materials.push_back(test::elastic(1000, 1e6, 0.3));
  def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(0.2, 0.2), 2));
  const Snapshot one = run(def, 1, 0.1), two = run(def, 2, 0.1);
  expectIdentical(one, two);
}

// 800 points, 2,633 steps to 0.35 s.
TEST(Threads, DebrisImpactIsBitIdenticalOnOneAndTwoThreads) {
  const WorldDef def =
      loadScene(test::sourcePath("config/scenes/debris_impact.yaml")).world;  // 800 points
  const Snapshot one = run(def, 1, 0.35), two = run(def, 2, 0.35);  // past the first impact
  ASSERT_FALSE(one.blocks.empty());
  EXPECT_GT(one.blocks[2].position.x(), 0.3105) << "block2 should have been pushed by then";
  expectIdentical(one, two);
}

TEST(Threads, SphRegionIsBitIdenticalOnOneAndTwoThreads) {
  // A granular column collapsing into an SPH region: points change kind as they cross it.
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.6, 0.3), 0.01);
  def.materials.push_back(test::druckerPrager(1500, 1e6, 0.3, 30, 0));
  def.bodies.push_back(test::rectangle(Vec2(0, 0), Vec2(0.1, 0.2), 2));
  def.sph = cases::sphBox(Vec2(0.06, 0.02), Vec2(0.5, 0.15));
  const Snapshot one = run(def, 1, 0.15), two = run(def, 2, 0.15);
  expectIdentical(one, two);
}

// The rock of test_sleep lands on a sleeping bed (SolverDef::sleep): the awake points' runs in
// G2P and the sleepers' grid share are shared among threads.
TEST(Threads, SleepingBedIsBitIdenticalOnOneAndTwoThreads) {
  WorldDef def =
      loadScene(test::sourcePath("config/scenes/rock_into_bed.yaml"), {"grid.cell_size=0.01"})
          .world;
  def.blocks.at(0).position = Vec2(0.15, 0.215);
  def.blocks.at(0).velocity = Vec2(0, 0);
  def.solver.sleep.speed = 0.01;
  def.solver.sleep.margin = 0.01;
  const Snapshot one = run(def, 1, 0.25), two = run(def, 2, 0.25);  // asleep, then woken
  expectIdentical(one, two);
}
