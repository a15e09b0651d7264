// A ParaView series as one of a run's outputs (sim/simulation.hpp): frames at the start, at every
// multiple of a period of simulated time and at a sound end.
#pragma once

#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/sim/simulation.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"

namespace mpm_sdem {

// A frame that cannot be written throws (the driver then drops the series and says why). The
// series stays its owner's.
class VtkOutput : public RunOutput {
 public:
  // rate: frames per simulated second (> 0).
  VtkOutput(VtkSeries& series, Real rate) : series_(series), clock_(rate) {}
  // The schedule starts with the first state's frame, or goes on from the frames a resumed run
  // left (the series kept them).
  void start(World& world, bool resumed) override {
    clock_.due(world.time(), resumed);
    if (!resumed) series_.write(world);
  }
  void step(World& world) override {
    if (clock_.due(world.time())) series_.write(world);
  }
  // The state the run ends in (written once: a frame at the last frame's time writes nothing).
  void finish(World& world, bool sound) override {
    if (sound) series_.write(world);
  }

 private:
  VtkSeries& series_;
  SampleClock clock_;
};

}  // namespace mpm_sdem
