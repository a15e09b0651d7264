// A bag as one of a run's outputs (sim/simulation.hpp): the runner's and the node's recording.
#pragma once

#include <functional>

#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/sim/simulation.hpp"

namespace mpm_sdem {

// Records every step (at the recorder's rates), the commands applied and the blocks' changes, and
// at a sound end the state reached as a checkpoint, to continue from. The recorder stays its
// owner's, who closes it.
class BagOutput : public RunOutput {
 public:
  // stats: what ~stats carries besides the world (the step chosen, the node's pause and pace).
  // continued: the recorder already holds the run up to the first state (BagRecorder::
  // continueFrom), which is then not recorded again.
  BagOutput(BagRecorder& bag, std::function<conversions::StatsInput()> stats, bool continued)
      : bag_(bag), stats_(std::move(stats)), continued_(continued) {}
  void start(World& world, bool) override {
    if (!continued_) bag_.record(world, stats_());
  }
  void step(World& world) override { bag_.record(world, stats_()); }
  void command(const WorldCommand& c) override { bag_.command(c); }
  void blocksChanged(const World& world) override { bag_.blocksChanged(world); }
  void finish(World& world, bool sound) override {
    if (sound) bag_.checkpoint(world);
  }

 private:
  BagRecorder& bag_;
  std::function<conversions::StatsInput()> stats_;
  bool continued_;
};

}  // namespace mpm_sdem
