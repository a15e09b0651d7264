// What a sweep's runs measured, gathered from their folders (DIR/runs/<id>/, the runner's CSVs):
// results.csv, one row per run, and summary.csv, the ensemble statistics per setting.
#pragma once

#include <string>
#include <vector>

#include "sweep_file.hpp"

namespace mpm_sdem::sweep {

// The folder of run r under the sweep's output folder.
std::string runDir(const std::string& out_dir, const Run& r);
// True when the run finished (its summary.csv says status 0).
bool runDone(const std::string& run_dir);

// One output read from a finished run's folder; throws SweepError naming the file and column.
double measureOutput(const std::string& run_dir, const Output& o);

struct Gathered {
  int runs = 0, done = 0;
  std::vector<std::string> problems;  // a run not done, or an output it lacks: one line each
};

// Writes DIR/results.csv and DIR/summary.csv from the finished runs. Runs not done are left
// out of both and listed in problems.
Gathered gather(const SweepDef& sweep, const std::string& out_dir);

}  // namespace mpm_sdem::sweep
