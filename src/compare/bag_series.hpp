// What mpm_sdem_compare reads from a recorded run: the block states, particle positions and
// energies over time, found in the bag by message type (so any node name works).
#pragma once

#include <mpm_sdem/BlockStates.h>

#include <string>
#include <vector>

namespace mpm_sdem::compare {

struct Cloud {
  double time = 0;        // s
  std::vector<float> xy;  // x0, y0, x1, y1, ... (m)
  // The SPH particles' positions alone (the cloud's field kind == 1; seed 001); empty without.
  std::vector<float> sph_xy;
};

struct EnergySample {
  double time = 0;     // s
  double total = 0;    // J/m
  double kinetic = 0;  // J/m
};

struct RunSeries {
  std::string path;
  std::vector<mpm_sdem::BlockStates> blocks;  // in time order
  std::vector<Cloud> clouds;
  std::vector<Cloud> fem_nodes;  // the FEM bodies' nodes (topic .../fem_nodes), in mesh order
  std::vector<EnergySample> energy;
};

// Throws std::runtime_error naming the file when it cannot be read or holds no block states,
// clouds or stats.
RunSeries readRun(const std::string& path);

}  // namespace mpm_sdem::compare
