// The step loop of the runner and the node (sim/simulation.hpp): its samples land on every
// multiple of the interval and on the end time, its guards stop a run whose energy grows or whose
// state becomes non-finite before any output sees that state, an output that fails is dropped
// and named while the others go on, and the world's commands reach the outputs.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/sim/simulation.hpp"

using namespace mpm_sdem;

namespace {

// An elastic block settling under gravity: 2 cm cells, a few hundred points.
WorldDef settlingBlock() {
  WorldDef d = test::box({0, 0}, {0.4, 0.4}, 0.02);
  d.materials.push_back(test::elastic(1000, 1e5, 0.3));
  d.bodies.push_back(test::rectangle({0.1, 0.02}, {0.3, 0.12}, 2));
  return d;
}

// One thread (bit-identical to two, and no tuner); samples every sample_interval s.
RunDef oneThread(Real sample_interval = 0) {
  RunDef def;
  def.sample_interval = sample_interval;
  def.threads = 1;
  return def;
}

// Records what it is told; throws from step() at the step numbered fail_at (0: never).
struct Recorder : RunOutput {
  std::vector<Real> samples, steps;
  std::vector<WorldCommand> commands;
  int starts = 0, finishes = 0;
  bool finished_sound = false;
  long fail_at = 0;
  void start(World&, bool) override { ++starts; }
  void step(World& w) override {
    if (fail_at > 0 && w.stepCount() == fail_at) throw std::runtime_error("disk full");
    steps.push_back(w.time());
  }
  void sample(const World& w, const Diagnostics& d) override {
    EXPECT_TRUE(d.finite);
    samples.push_back(w.time());
  }
  void command(const WorldCommand& c) override { commands.push_back(c); }
  void finish(World&, bool sound) override {
    ++finishes;
    finished_sound = sound;
  }
};

}  // namespace

// Samples at t = 0 and every 2 ms to the end at 10 ms, landed within rounding; the last step
// lands on the end time exactly as runUntil does (one rule: stepTowards).
TEST(Simulation, SamplesEveryIntervalAndLandsOnTheEnd) {
  World w(settlingBlock());
  RunDef def = oneThread(0.002);
  def.end_time = 0.01;
  Simulation sim(w, def);
  Recorder out;
  sim.attach(out);
  EXPECT_EQ(sim.start(false), "");
  int steps = 0;
  while (!sim.ended()) {
    const RunStep s = sim.advance();
    ASSERT_EQ(s.problem, "") << "at t = " << w.time();
    ++steps;
  }
  EXPECT_EQ(sim.finish(true), "");
  ASSERT_EQ(out.samples.size(), 6u);
  // The step (about 0.5 ms here) does not divide 2 ms: a sample is the first step at or past
  // each multiple, less than one step after it.
  const Real dt = sim.stableStep().dt;
  for (int k = 0; k < 6; ++k) {
    EXPECT_GE(out.samples[k], 0.002 * k - 1e-9) << k;
    EXPECT_LT(out.samples[k], 0.002 * k + dt * 1.01) << k;
  }
  EXPECT_NEAR(w.time(), 0.01, 1e-15);
  EXPECT_EQ(out.steps.size(), static_cast<std::size_t>(steps));
  EXPECT_EQ(out.starts, 1);
  EXPECT_EQ(out.finishes, 1);
  EXPECT_TRUE(out.finished_sound);
  // The same world stepped by the core's loop lands on the same state, bit for bit.
  World bare(settlingBlock());
  runUntil(bare, 0.01);
  EXPECT_EQ(bare.stepCount(), w.stepCount());
  EXPECT_EQ(bare.particles().x, w.particles().x);
}

// Energy put in from outside (every point's velocity scaled by 1.05 before each step) trips the
// guard at the first sample past the limit (+50% of the first state's energy); the sample that
// shows it is written, no step output after.
TEST(Simulation, EnergyGrowthStopsTheRun) {
  World w(settlingBlock());
  for (Real& vx : w.particles().vx) vx = 0.1;
  RunDef def = oneThread(0.001);
  def.energy_growth = 0.5;
  Simulation sim(w, def);
  Recorder out;
  sim.attach(out);
  sim.start(false);
  RunStep s;
  for (int k = 0; k < 200 && s.problem.empty(); ++k)
    s = sim.advance([&](Real) {
      for (Real& vx : w.particles().vx) vx *= 1.05;
    });
  ASSERT_NE(s.problem, "");
  EXPECT_NE(s.problem.find("limits.energy_growth"), std::string::npos) << s.problem;
  EXPECT_TRUE(s.sampled);
  EXPECT_EQ(out.samples.back(), w.time());  // the sample showing the growth
  EXPECT_LT(out.steps.back(), w.time());    // but no step output of the stopped state
  const Diagnostics d = measure(w);
  EXPECT_GT(d.total(), 1.5 * sim.initial().total());
}

// Without the energy guard (the node's), the same run goes on past that point.
TEST(Simulation, NoEnergyGuardByDefault) {
  World w(settlingBlock());
  for (Real& vx : w.particles().vx) vx = 0.1;
  Simulation sim(w, oneThread(0.001));
  sim.start(false);
  for (int k = 0; k < 80; ++k) {
    const RunStep s = sim.advance([&](Real) {
      for (Real& vx : w.particles().vx) vx *= 1.05;
    });
    ASSERT_EQ(s.problem, "") << k;
  }
  EXPECT_GT(measure(w).total(), 1.5 * sim.initial().total());
}

// A non-finite velocity stops the run at that step, before any output is told of it.
TEST(Simulation, NonFiniteStateStopsBeforeTheOutputs) {
  World w(settlingBlock());
  Simulation sim(w, oneThread());
  Recorder out;
  sim.attach(out);
  sim.start(false);
  ASSERT_EQ(sim.advance().problem, "");
  const RunStep s = sim.advance([&](Real) { w.particles().vx[3] = NAN; });
  EXPECT_NE(s.problem.find("non-finite"), std::string::npos) << s.problem;
  EXPECT_EQ(out.steps.size(), 1u);
  sim.finish(false);
  EXPECT_FALSE(out.finished_sound);
}

// An output that throws is dropped and named once; the others and the run go on, and a dropped
// output is not finished.
TEST(Simulation, AFailingOutputIsDroppedAndNamed) {
  World w(settlingBlock());
  Simulation sim(w, oneThread());
  Recorder failing, fine;
  failing.fail_at = 3;
  sim.attach(failing);
  sim.attach(fine);
  sim.start(false);
  std::vector<std::string> problems;
  for (int k = 0; k < 6; ++k) {
    const RunStep s = sim.advance();
    ASSERT_EQ(s.problem, "");
    problems.push_back(s.output_problem);
  }
  EXPECT_EQ(problems[2], "disk full");
  for (int k : {0, 1, 3, 4, 5}) EXPECT_EQ(problems[k], "") << k;
  EXPECT_EQ(failing.steps.size(), 2u);
  EXPECT_EQ(fine.steps.size(), 6u);
  sim.finish(true);
  EXPECT_EQ(failing.finishes, 0);
  EXPECT_EQ(fine.finishes, 1);
}

// The world's commands (here a block's velocity set between steps) reach every output once.
TEST(Simulation, CommandsReachTheOutputs) {
  World w(cases::restingSquare(0.02, 0.3));
  ASSERT_NE(w.blocks(), nullptr);
  Simulation sim(w, oneThread());
  Recorder out;
  sim.attach(out);
  sim.start(false);
  w.setBlockVelocity(w.blocks()->id(0), Vec2(0.1, 0), 0);
  ASSERT_EQ(out.commands.size(), 1u);
  EXPECT_EQ(out.commands[0].kind, WorldCommand::Kind::kSetVelocity);
}
