// The runner's checkpoint files (--checkpoint-every): the whole state every interval of
// simulated time and at the end, written whole or not at all (a temporary file renamed), so a
// run killed at any moment leaves its latest complete checkpoint; the two latest are kept. An
// output of the run's Simulation: checked after every step, written last of the step's outputs.
#pragma once

#include <string>

#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/sim/simulation.hpp"

namespace mpm_sdem::runner {

class CheckpointFiles : public RunOutput {
 public:
  // interval: s of simulated time (> 0). state_text: the scene's Scene::state_text.
  CheckpointFiles(const std::string& dir, Real interval, const std::string& state_text);
  // A resumed run continues the schedule after the checkpoint it resumed from; a fresh one
  // starts it (the first state is not written).
  void start(World& world, bool resumed) override {
    if (resumed) clock_.due(world.time(), true);
  }
  void step(World& world) override { write(world); }
  // The state reached, to continue from (a longer run, or an interrupted one).
  void finish(World& world, bool sound) override {
    if (sound) write(world, true);
  }
  // Writes one when due at the world's time (force: now). Throws std::runtime_error when the
  // file cannot be written.
  void write(World& world, bool force = false);
  const std::string& dir() const { return dir_; }

 private:
  std::string dir_, state_text_;
  SampleClock clock_;
  Real last_ = -1;  // time of the last one written
};

}  // namespace mpm_sdem::runner
