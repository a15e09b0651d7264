// A sweep: one base scene run at many settings (the --set values swept as a grid or zipped) and,
// for chaotic scenes, as an ensemble of perturbed members at each setting; what to measure in
// each run and what to compare it with. Read strictly from YAML, as scenes are
// (docs/sweep_reference.md): an unknown key, a missing one or a bad value names its line.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mpm_sdem::sweep {

// One message, formatted as "file:line:column: key: problem".
class SweepError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// One dimension of the sweep: a scene key and its values, or a group of keys whose k-th values
// go together (one value of the dimension sets them all).
struct Parameter {
  std::vector<std::string> keys;                 // scene keys as --set takes them
  std::vector<std::vector<std::string>> values;  // values[k][j]: key j's k-th (YAML flow text)
};

struct Ensemble {
  int members = 1;
  double perturbation = 0;  // m: each point moved by up to this along x and y
  bool in_cells = false;    // perturbation given in cells of each setting's grid
  unsigned seed = 1;        // member m (from 0) is drawn from seed + m
};

// A number read from one run's output files (the runner's CSVs, docs/running.md).
struct Output {
  std::string name;    // its column in results.csv
  std::string file;    // timeseries.csv | blocks.csv | particles.csv | summary.csv
  std::string column;  // a column of that file
  std::string block;   // blocks.csv: whose row
  double at = -1;      // s: the first row at or after this time; < 0: the last row
  std::string reduce;  // particles.csv: max | min | mean | sum over the points
  // timeseries.csv: instead of one row, the least-squares slope against time (unit/s) over the
  // rows whose value lies in [first, second] (a discharge rate over part of the discharge).
  std::optional<std::pair<double, double>> rate_between;
  // error = |value - reference| / |reference|; one for every setting, or one per setting.
  std::vector<double> reference;
  bool hasReference() const { return !reference.empty(); }
  double referenceAt(int setting) const {
    return reference.size() == 1 ? reference[0] : reference.at(setting);
  }
};

// A validation sweep: the report's cases (mpm_sdem_validate), one run per case, instead of a
// scene's settings; what each measured is its folder's results.csv and series files.
struct ValidationCases {
  bool fast = false;               // the CI resolution (mpm_sdem_validate --fast)
  std::vector<std::string> cases;  // mpm_sdem_validate --list names them
};

struct SweepDef {
  std::string name;
  std::string source;                         // the sweep file
  std::optional<ValidationCases> validation;  // set: a validation sweep (no scene, no outputs)
  std::string scene;                          // the base scene, absolute
  std::vector<std::string> fixed;             // key=value for every run
  std::vector<Parameter> parameters;
  bool zip = false;  // false: every combination; true: the k-th values together
  Ensemble ensemble;
  std::vector<Output> outputs;
  std::vector<double> cell_sizes;  // m, per setting, when the perturbation is in cells
};

// One run: a setting (one value of each parameter) and an ensemble member.
struct Run {
  std::string id;  // s<setting>_m<member>, zero-padded: its folder under runs/
  int setting = 0, member = 0;
  unsigned seed = 0;
  std::vector<std::string> values;     // one per parameter key
  std::vector<std::string> overrides;  // the fixed ones, then the parameters'
  double perturbation = 0;             // m
  std::string validation_case;         // a validation sweep's run: its case (and id)
};

// Throws SweepError. Also loads the base scene at every setting, so that a value the scene
// refuses is reported now, with its setting, and not by a job hours later.
SweepDef loadSweep(const std::string& path);
std::vector<Run> expandRuns(const SweepDef& sweep);
// Every parameter key, groups' included, in the order of Run::values.
std::vector<std::string> parameterKeys(const SweepDef& sweep);

}  // namespace mpm_sdem::sweep
