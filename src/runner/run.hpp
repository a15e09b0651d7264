// What one mpm_sdem_run run holds (the scene, its world and step loop, what it resumes and
// replays, its output files), how it is set up from the command line and how it ends. main.cpp
// holds the loop.
#pragma once

#include <filesystem>
#include <memory>
#include <string>

#include "checkpoint_files.hpp"
#include "mpm_sdem/ros/bag_output.hpp"
#include "mpm_sdem/ros/checkpoint_source.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "mpm_sdem/sim/simulation.hpp"
#include "mpm_sdem/vtk/vtk_output.hpp"
#include "options.hpp"
#include "output.hpp"
#include "replay.hpp"

namespace mpm_sdem::runner {

// The files a run writes, each an output of its Simulation (--bag, --vtk-every and
// --checkpoint-every add theirs to the CSV series). A resumed run continues the files of the
// run it resumes (their rows, frames and messages up to the checkpoint).
struct RunFiles {
  std::unique_ptr<TimeSeriesWriter> series;
  std::unique_ptr<BlockSeriesWriter> blocks;  // with blocks
  std::unique_ptr<FemSeriesWriter> fem;       // with FEM bodies
  std::unique_ptr<BagRecorder> bag;
  std::unique_ptr<BagOutput> bag_output;
  std::unique_ptr<VtkSeries> vtk;
  std::unique_ptr<VtkOutput> vtk_output;
  std::unique_ptr<CheckpointFiles> checkpoints;  // last: written after every other output
};

struct Run {
  Scene scene;
  std::unique_ptr<World> world;
  std::unique_ptr<Simulation> sim;
  CheckpointSource resumed;  // empty bytes: a fresh run
  std::unique_ptr<CommandReplay> replay;
  std::filesystem::path out;
  RunFiles files;
  bool fresh() const { return resumed.bytes.empty(); }
};

// The scene, the world (perturbed, resumed), the replay, the output directory and files, all
// attached to the started Simulation; false after saying on stderr what is wrong (exit 1).
bool prepare(const Options& opt, Run& run);
// After the loop: the outputs' ends (a last frame, checkpoint and bag checkpoint unless status
// is 3, an unsound state), particles.csv, profile.csv, summary.csv and the closing lines.
// Returns the exit status (1 when an output could not be finished).
int finish(Run& run, int status, double wall_seconds);

}  // namespace mpm_sdem::runner
