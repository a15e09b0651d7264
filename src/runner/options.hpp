// Command line of mpm_sdem_run.
#pragma once

#include <string>
#include <vector>

namespace mpm_sdem::runner {

struct Options {
  std::string scene;
  std::string out_dir;  // empty: out/<scene file stem>
  std::vector<std::string> overrides;
  int threads = 0;  // 0: chosen while running (ThreadTuner), up to the OpenMP default
  bool quiet = false;
  std::string bag;                 // write a rosbag like the node's (empty: none)
  double bag_cloud_rate = 10;      // Hz of simulation time (the node's default, RecordDef)
  double bag_state_rate = 100;     // Hz
  double bag_checkpoint_rate = 1;  // Hz
  double checkpoint_every = 0;     // s of simulation time between checkpoint files (0: none)
  std::string resume;              // continue from: FILE, FOLDER or BAG[@TIME] (empty: no)
  std::string replay;              // a bag whose recorded commands to apply (empty: none)
  double vtk_every = 0;            // s of simulated time between ParaView frames (0: none)
  double perturb = 0;              // m: every point moved by up to this along x and y (0: none)
  unsigned seed = 1;               // of the perturbation
};

// Returns false and fills error on a bad command line; help is set for --help.
bool parseOptions(int argc, char** argv, Options& out, std::string& error, bool& help);
const char* usage();

}  // namespace mpm_sdem::runner
