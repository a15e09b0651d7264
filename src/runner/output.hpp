// CSV outputs of the headless runner. Rows are flushed as they are written, so a run that stops
// early keeps everything up to its last sample. A resumed run (resume_after >= 0, the
// checkpoint's time) keeps an existing file's rows up to that time and continues it, so that its
// files are those of a run that never stopped. The series are outputs of the run's Simulation:
// a row per sample (its first state, every output.interval, the end).
#pragma once

#include <fstream>
#include <string>
#include <vector>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/sim/simulation.hpp"

namespace mpm_sdem::runner {

// One row per sample: energies, momenta, the step, and a <name>_mass column per gauge (kg/m).
// The step is the one sim last chose.
class TimeSeriesWriter : public RunOutput {
 public:
  TimeSeriesWriter(const std::string& path, const Simulation& sim, Real resume_after = -1,
                   std::vector<MassGauge> gauges = {});
  void sample(const World& world, const Diagnostics& d) override;

 private:
  const Simulation& sim_;
  std::vector<MassGauge> gauges_;
  std::ofstream out_;
};

// One row per block per sample: pose, velocity, what the material did to it, and the box around
// its rounded outline (min_x is a block's left face in the wooden-block scene).
class BlockSeriesWriter : public RunOutput {
 public:
  explicit BlockSeriesWriter(const std::string& path, Real resume_after = -1);
  void sample(const World& world, const Diagnostics&) override;

 private:
  std::ofstream out_;
};

// FEM bodies, one row per node (fem_nodes.csv: position and displacement) and per element
// (fem_elements.csv: Cauchy stress at the start of the step, von Mises) per sample.
class FemSeriesWriter : public RunOutput {
 public:
  FemSeriesWriter(const std::string& nodes_path, const std::string& elements_path,
                  Real resume_after = -1);
  void sample(const World& world, const Diagnostics&) override;

 private:
  std::ofstream nodes_, elements_;
};

void writeParticles(const World& world, const std::string& path);
void writeProfile(const World& world, const std::string& path);
// The run's footprint, written last: its exit status (0 done), the time reached, steps, points
// and wall-clock seconds of the whole run. A sweep counts a run done when this says status 0.
void writeSummary(const World& world, int status, double wall_seconds, const std::string& path);

}  // namespace mpm_sdem::runner
