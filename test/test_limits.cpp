// The robustness pieces of the core: ranges and names (limits.hpp), the block rules shared by the
// parser and the node (block_checks.hpp), the real-time meter that leaves pauses out, and the
// thread tuner that leaves a loaded core.
#include <gtest/gtest.h>
#include <omp.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/real_time_meter.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/thread_tuner.hpp"

using namespace mpm_sdem;

TEST(Limits, RangesRefuseNaNInfinityAndTheirEnds) {
  using limits::kRestitution;
  EXPECT_EQ(limits::rangeProblem(0.5, kRestitution).text(), "");
  EXPECT_EQ(limits::rangeProblem(1, kRestitution).text(), "");
  EXPECT_EQ(limits::rangeProblem(0, kRestitution).text(), "must be in (0, 1], got 0");
  EXPECT_NE(limits::rangeProblem(std::nan(""), limits::kDensity).text(), "");
  EXPECT_NE(limits::rangeProblem(INFINITY, limits::kDensity).text(), "");
  EXPECT_EQ(limits::rangeProblem(1e300, limits::kDensity).text(),
            "must be in [0.1, 100000] kg/m^3, got 1e+300");
}

TEST(Limits, NamesAreRosNamesOfBoundedLength) {
  EXPECT_EQ(limits::nameProblem("block_1").text(), "");
  EXPECT_EQ(limits::nameProblem(std::string(64, 'a')).text(), "");
  for (const std::string bad : {"", "1block", "block 1", "a/b", "../../etc/passwd", "a\nb", "_a"})
    EXPECT_NE(limits::nameProblem(bad).text(), "") << bad;
  const std::string huge = limits::nameProblem(std::string(10 << 20, 'x')).message;
  EXPECT_NE(huge.find("at most 64"), std::string::npos);
  EXPECT_LT(huge.size(), 200u) << "the message must not echo the name";
}

TEST(Limits, ThreadsFromZeroToTheCores) {
  EXPECT_EQ(limits::threadsProblem(0).text(), "");
  EXPECT_EQ(limits::threadsProblem(limits::logicalCores()).text(), "");
  EXPECT_NE(limits::threadsProblem(limits::logicalCores() + 1).text(), "");
  EXPECT_NE(limits::threadsProblem(100000).text(), "");
  EXPECT_NE(limits::threadsProblem(-1).text(), "");
}

TEST(Limits, MemoryEstimateNamesTheSize) {
  EXPECT_EQ(limits::memoryProblem(1e6, 1e6).text(), "");  // a few hundred MB
  const Problem p = limits::memoryProblem(1e12, 0);
  EXPECT_NE(p.message.find("GiB"), std::string::npos) << p.message;
  EXPECT_NE(limits::memoryProblem(INFINITY, 0).text(), "");
}

TEST(Limits, OutputFilesMustBeFilesInAWritableDirectory) {
  namespace fs = std::filesystem;
  const fs::path tmp = fs::temp_directory_path();
  EXPECT_EQ(limits::outputFileProblem((tmp / "run.bag").string(), {".bag"}).text(), "");
  EXPECT_NE(limits::outputFileProblem(tmp.string(), {".bag"}).message.find("directory"),
            std::string::npos);
  EXPECT_NE(
      limits::outputFileProblem((tmp / "run.txt").string(), {".bag"}).message.find("end in .bag"),
      std::string::npos);
  EXPECT_NE(
      limits::outputFileProblem("/no/such/dir/run.bag", {".bag"}).message.find("does not exist"),
      std::string::npos);
  EXPECT_NE(limits::outputFileProblem("", {".bag"}).text(), "");
}

namespace {

BlockDef square(BodyType type) {
  BlockDef b;
  b.name = "box";
  b.core = {Vec2(-0.01, -0.01), Vec2(0.01, -0.01), Vec2(0.01, 0.01), Vec2(-0.01, 0.01)};
  b.rounding = 0.002;
  b.position = Vec2(0.2, 0.1);
  b.type = type;
  return b;
}

}  // namespace

// The stop for a collapsed step: measured from the first step after a (re)base, at the scene's
// fraction of it; below the absolute floor always, also as the first step.
TEST(StepGuard, StopsBelowTheFractionOfTheFirstStepAndBelowTheFloor) {
  StepGuard guard(1e-3);
  const auto step = [](Real dt) { return TimeStepChoice{dt, StepLimit::kCfl}; };
  EXPECT_EQ(guard.problem(step(3e-5)), "");
  EXPECT_EQ(guard.reference(), 3e-5);
  EXPECT_EQ(guard.problem(step(3.1e-8)), "");  // 1.03e-3 of the first
  EXPECT_EQ(guard.problem(step(6e-5)), "");    // a longer step does not move the reference
  EXPECT_EQ(guard.reference(), 3e-5);
  const std::string p = guard.problem(step(2.9e-8));
  EXPECT_NE(p.find("fell to 2.9e-08 s (cfl term)"), std::string::npos) << p;
  EXPECT_NE(p.find("limits.step_collapse"), std::string::npos) << p;
  guard.rebase();  // e.g. a light obstacle spawned in the node
  EXPECT_EQ(guard.problem(step(2.9e-8)), "");
  EXPECT_EQ(guard.reference(), 2.9e-8);
  StepGuard fresh(1e-3);
  EXPECT_NE(fresh.problem(step(5e-10)).find("time would stand still"), std::string::npos);
  EXPECT_NE(fresh.problem(step(std::nan(""))).find("time would stand still"), std::string::npos);
}

TEST(BlockChecks, EachValueIsJudgedUnderItsKey) {
  const auto key = [](BlockDef b) { return blockProblem(b, BlockContactModel::kPenalty).key; };
  EXPECT_EQ(key(square(BodyType::kDynamic)), "");
  BlockDef b = square(BodyType::kDynamic);
  b.density = 1e300;  // overflowed Box2D's float mass (m_I > 0 assertion)
  EXPECT_EQ(key(b), "density");
  b.density = 1e-300;  // a zero step
  EXPECT_EQ(key(b), "density");
  b = square(BodyType::kStatic);
  b.density = 0;  // unused for a static block
  EXPECT_EQ(key(b), "");
  b.velocity = Vec2(0.1, 0);
  EXPECT_EQ(key(b), "velocity") << "a static block with a twist";
  b = square(BodyType::kKinematic);
  b.angular_velocity = 1e6;  // 1e6 rad/s at 16 mm reach: 16 km/s
  EXPECT_EQ(key(b), "angular_velocity");
  b = square(BodyType::kKinematic);
  b.core[1].x() = 1e300;
  EXPECT_EQ(key(b), "vertices");
  b = square(BodyType::kKinematic);
  b.angle = 1e300;  // a float infinity in Box2D: b2IsValid(angle) aborted (found by fuzz_requests)
  EXPECT_EQ(key(b), "angle");
  b = square(BodyType::kKinematic);
  b.name = "box 1";
  EXPECT_EQ(key(b), "name");
  b = square(BodyType::kDynamic);
  b.adhesion = 30;
  EXPECT_EQ(blockProblem(b, BlockContactModel::kBox2D).key, "adhesion");
}

TEST(BlockChecks, SpeedLimitCountsTheSpin) {
  const BlockDef b = square(BodyType::kKinematic);
  const Real reach = std::sqrt(2.0) * 0.01 + 0.002;
  EXPECT_TRUE(twistProblem(b, Vec2(999, 0), 0).empty());
  EXPECT_FALSE(twistProblem(b, Vec2(1001, 0), 0).empty());
  EXPECT_TRUE(twistProblem(b, Vec2(0, 0), 999 / reach).empty());
  EXPECT_FALSE(twistProblem(b, Vec2(0, 0), 1001 / reach).empty());
  EXPECT_FALSE(twistProblem(b, Vec2(std::nan(""), 0), 0).empty());
}

TEST(BlockChecks, OnlyAStaticBlockMayReachOutsideTheDomain) {
  const Vec2 lo(0, 0), hi(0.4, 0.2);
  BlockDef b = square(BodyType::kDynamic);
  EXPECT_TRUE(domainProblem(b, lo, hi).empty());
  b.position = Vec2(0.4, 0.1);  // half outside
  EXPECT_FALSE(domainProblem(b, lo, hi).empty());
  b.type = BodyType::kStatic;
  EXPECT_TRUE(domainProblem(b, lo, hi).empty()) << "a boundary block touching the domain";
  b.position = Vec2(5, 0.1);
  EXPECT_FALSE(domainProblem(b, lo, hi).empty()) << "a static block away from the domain";
}

// The acceleration of the fastest point from a load: |F| / M for a force at the centre of mass,
// tau R / I for a torque, and the lever of a force off the centre counted at its full length
// (the load's frame may turn against the block). A block without mass takes no load.
TEST(BlockChecks, LoadAccelerationIsThatOfTheFastestPoint) {
  BlockDef b = square(BodyType::kDynamic);
  b.density = 500;
  const MassProperties m = blockMass(b);
  const Real R = std::sqrt(2.0) * 0.01 + 0.002;  // corner of the core plus the rounding
  EXPECT_NEAR(loadAcceleration(b, Vec2(3, 4), m.centroid, 0), 5 / m.mass, 1e-12);
  EXPECT_NEAR(loadAcceleration(b, Vec2(0, 0), m.centroid, 0.01), 0.01 * R / m.inertia, 1e-9);
  const Vec2 lever(0.005, 0);
  EXPECT_NEAR(loadAcceleration(b, Vec2(0, 2), m.centroid + lever, 0),
              2 / m.mass + 0.005 * 2 * R / m.inertia, 1e-9);
  EXPECT_EQ(loadAcceleration(square(BodyType::kKinematic), Vec2(1, 0), Vec2(0, 0), 0), INFINITY);
}

// Loads held together: accelerations add up to at most 1e4 m/s^2 (kLoadAcceleration), and the
// speed the ending ones add, a d summed, to at most 1000 m/s (kSpeed); one held until cleared
// counts only for the first.
TEST(BlockChecks, HeldLoadsBoundTheAccelerationAndTheSpeedTheyAdd) {
  const Real forever = INFINITY;
  EXPECT_TRUE(heldLoadsProblem({{9e3, 0.1}}).empty());  // 900 m/s
  EXPECT_EQ(heldLoadsProblem({{9e3, 0.2}}).key, "duration");
  EXPECT_NE(heldLoadsProblem({{9e3, 0.2}}).message.find("1800 m/s"), std::string::npos);
  EXPECT_EQ(heldLoadsProblem({{2e4, 1e-3}}).key, "wrench");
  EXPECT_TRUE(heldLoadsProblem({{5e3, forever}}).empty());
  EXPECT_EQ(heldLoadsProblem({{6e3, forever}, {5e3, 0.01}}).key, "wrench");
  EXPECT_EQ(heldLoadsProblem({{4e3, 0.1}, {5e3, 0.1}, {1, forever}}).key, "");
  EXPECT_EQ(heldLoadsProblem({{5e3, 0.1}, {5e3, 0.11}}).key, "duration");
  for (Real a : {Real(1e30), Real(1e300), Real(INFINITY), Real(std::nan(""))})
    EXPECT_EQ(heldLoadsProblem({{a, 1e-3}}).key, "wrench") << a;
}

// A kinematic block stops at the walls: a velocity that would carry its box across a side in
// the step is cut to what reaches the side, none once it is outside, away from the wall is
// kept; a spin whose sweep would cross a side is dropped.
TEST(BlockChecks, MovingBlocksStopAtTheDomainsWalls) {
  const Vec2 lo(0, 0), hi(0.4, 0.2);
  const Box box{Vec2(0.1, 0.05), Vec2(0.2, 0.1)};
  const Real h = 0.01;
  Vec2 v(50, -1);
  Real w = 0;
  EXPECT_TRUE(keepInsideDomain(box, 0.1, h, lo, hi, v, w));
  EXPECT_DOUBLE_EQ(v.x(), 20);  // (0.4 - 0.2) / 0.01
  EXPECT_EQ(v.y(), -1);
  v = Vec2(-5, 4);
  EXPECT_FALSE(keepInsideDomain(box, 0.1, h, lo, hi, v, w));
  EXPECT_EQ(v, Vec2(-5, 4));
  const Box outside{Vec2(0.35, 0.15), Vec2(0.45, 0.25)};
  v = Vec2(5, 3);
  EXPECT_TRUE(keepInsideDomain(outside, 0.1, h, lo, hi, v, w));
  EXPECT_EQ(v, Vec2(0, 0));
  v = Vec2(-3, -2);
  EXPECT_FALSE(keepInsideDomain(outside, 0.1, h, lo, hi, v, w)) << "back inside is free";
  const Box near{Vec2(0.1, 0.05), Vec2(0.395, 0.1)};
  v = Vec2(0, 0);
  w = 10;  // sweeps 10 * 0.01 * 0.1 = 1 cm, the wall is 5 mm away
  EXPECT_TRUE(keepInsideDomain(near, 0.1, h, lo, hi, v, w));
  EXPECT_EQ(w, 0);
  w = 4;  // 4 mm
  EXPECT_FALSE(keepInsideDomain(near, 0.1, h, lo, hi, v, w));
  EXPECT_EQ(w, 4);
}

TEST(RealTimeMeter, LeavesPausesOutAndSlidesItsWindow) {
  using Clock = RealTimeMeter::Clock;
  const Clock::time_point t0{};
  const auto at = [&](double s) {
    return t0 + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(s));
  };
  RealTimeMeter m;
  m.setRunning(true, at(0));
  for (int k = 0; k <= 10; ++k) m.sample(0.1 * k, at(0.1 * k));  // 1 x real time for 1 s
  EXPECT_NEAR(m.factor(), 1.0, 1e-9);
  m.setRunning(false, at(1));
  m.setRunning(true, at(101));  // a 100 s pause
  m.sample(1.1, at(101.1));
  EXPECT_NEAR(m.factor(), 1.0, 1e-9) << "the pause counted";
  for (int k = 1; k <= 40; ++k) m.sample(1.1 + 0.05 * k, at(101.1 + 0.1 * k));  // 0.5 x
  EXPECT_NEAR(m.factor(), 0.5, 1e-9) << "the window still holds the 1 x part";
}

TEST(ThreadTuner, LeavesACountThatIsSlowerAndComesBack) {
  if (limits::logicalCores() < 2) GTEST_SKIP() << "one core: nothing to choose";
  const int before = omp_get_max_threads();
  ThreadTuner t(2);
  // Loaded: two threads take 10 ms a step, one takes 2 ms.
  auto run = [&](double two, double one, double seconds) {
    for (double s = 0; s < seconds;) {
      t.beforeStep();
      const double step = t.threads() == 2 ? two : one;
      t.afterStep(step);
      s += step;
    }
  };
  run(0.010, 0.002, 3 * ThreadTuner::kPeriod);
  EXPECT_EQ(t.best(), 1);
  // The load goes away: two threads now take 1 ms.
  run(0.001, 0.002, 3 * ThreadTuner::kPeriod);
  EXPECT_EQ(t.best(), 2);
  // A trial of a count that is within kGain of the best does not switch.
  run(0.0019, 0.002, 3 * ThreadTuner::kPeriod);
  EXPECT_EQ(t.best(), 2);
  omp_set_num_threads(before);
}
