// Where a sweep's runs execute: on this machine through GNU parallel, or on a Slurm cluster as a
// job array with a dependent gather job. Both run the same command per run (commands.txt), each
// run writing into its own folder; runs already done are not run again.
#pragma once

#include <string>
#include <vector>

#include "sweep_file.hpp"

namespace mpm_sdem::sweep {

struct Launch {
  std::string out_dir;  // absolute
  std::string runner;   // mpm_sdem_run, absolute
  std::string self;     // mpm_sdem_sweep, absolute (the gather job calls it)
  int jobs = 0;         // runs at once (local: 0 = one per core; slurm: 0 = no limit)
  int threads_per_run = 1;
  std::string partition;   // slurm: empty = the cluster's default
  std::string time_limit;  // slurm: --time of each run, empty = the partition's
  bool submit = true;      // slurm: false writes the scripts only
};

// The shell command of one run: the runner with the sweep's --set values (and the member's
// perturbation), its outputs and log in the run's folder.
std::string runCommand(const SweepDef& sweep, const Run& run, const Launch& launch);

// Creates the run folders and writes commands.txt (every run) and pending.txt (the runs not
// done yet); returns the pending runs.
std::vector<Run> prepare(const SweepDef& sweep, const Launch& launch);

// Runs the pending commands with GNU parallel (progress bar on a terminal). Returns parallel's
// exit status (the number of failed runs, up to 100) or -1 when parallel cannot be started.
int runLocal(const std::vector<Run>& pending, const Launch& launch);

// Writes slurm/array.sh (one array task per pending run) and slurm/gather.sh, and submits them
// with sbatch, the gather job after the whole array (afterany). Returns 0, or 1 after saying
// why on stderr (no sbatch, a refused submission).
int submitSlurm(const SweepDef& sweep, const std::vector<Run>& pending, const Launch& launch);

}  // namespace mpm_sdem::sweep
