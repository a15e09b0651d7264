// What every case of mpm_sdem_validate shares: the options, the results file (one row per
// measured quantity), and the cases by topic (one file each in validation/report/).
#pragma once

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases.hpp"
#include "mpm_sdem/core/coupling/coupling.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::report {

struct Options {
  std::string out = "validation_out";
  bool fast = false;
  /// A case split into runs (one per resolution or member: its `parts` in validate.cpp) runs
  /// only its run `part` (mpm_sdem_validate --cases name.part), or all of them when -1.
  int part = -1;
  /// Whether run i of a split case is to be run now.
  bool runs(int i) const { return part < 0 || part == i; }
};

class Results {
 public:
  /// Rows to `path`, a new file with its header, or appended to a report's (a split case's
  /// combined rows, mpm_sdem_validate --combine).
  explicit Results(const std::string& path, bool append = false)
      : f_(std::fopen(path.c_str(), append ? "a" : "w")) {
    if (f_ && !append)
      std::fprintf(
          f_, "case,quantity,value,reference,unit,source,error,wall_s,settings,points,steps\n");
  }
  ~Results() { close(); }
  /// Ends the file (before it is read again).
  void close() {
    if (f_) std::fclose(f_);
    f_ = nullptr;
  }
  bool ok() const { return f_ != nullptr; }
  int nonFinite() const { return non_finite_; }
  void add(const std::string& c, const std::string& quantity, double value, double reference,
           const std::string& unit, const std::string& source, double wall,
           const std::string& settings, long points = 0, long steps = 0) {
    const double error =
        reference != 0 ? std::abs(value - reference) / std::abs(reference) : std::abs(value);
    if (!std::isfinite(value)) ++non_finite_;
    std::fprintf(f_, "%s,\"%s\",%.8g,%.8g,%s,\"%s\",%.6g,%.4g,\"%s\",%ld,%ld\n", c.c_str(),
                 quantity.c_str(), value, reference, unit.c_str(), source.c_str(), error, wall,
                 settings.c_str(), points, steps);
    std::fflush(f_);
    std::printf("  %-36s %12.6g  (reference %.6g %s, error %.3g)\n", quantity.c_str(), value,
                reference, unit.c_str(), error);
    std::fflush(stdout);
  }

 private:
  FILE* f_;
  int non_finite_ = 0;
};

// A case's numeric table as it wrote it (<out>/<case>*.csv, header and rows), read back by a
// split case's combine step, which fits across the runs that wrote its rows.
class Table {
 public:
  explicit Table(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read " + path + " (were the case's runs gathered?)");
    std::string line;
    for (bool first = true; std::getline(in, line); first = false) {
      std::vector<std::string> cells;
      std::stringstream ss(line);
      for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
      if (first) {
        header_ = cells;
        continue;
      }
      std::vector<double> row;
      for (const std::string& c : cells) row.push_back(std::stod(c));
      if (row.size() != header_.size())
        throw std::runtime_error(path + ": a row of " + std::to_string(row.size()) + " cells");
      rows_.push_back(std::move(row));
    }
  }
  std::size_t size() const { return rows_.size(); }
  /// Row i's value in the column named `name`.
  double at(std::size_t i, const std::string& name) const {
    for (std::size_t c = 0; c < header_.size(); ++c)
      if (header_[c] == name) return rows_.at(i)[c];
    throw std::runtime_error("no column " + name);
  }

 private:
  std::vector<std::string> header_;
  std::vector<std::vector<double>> rows_;
};

// Every coupling scheme, in the order of coupling.hpp's table.
inline std::vector<CouplingScheme> allSchemes() {
  std::vector<CouplingScheme> out;
  for (const SchemeTraits& t : couplingSchemes()) out.push_back(t.scheme);
  return out;
}

/// A cell size as the rows name it: "2.5 mm" for 0.0025 m.
inline std::string millimetres(double metres) {
  char t[32];
  std::snprintf(t, sizeof t, "%g mm", 1000 * metres);
  return t;
}

inline double seconds(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The least-squares line of the cases (cases.hpp), for the fits across runs.
using cases::LineFit;

namespace contact {
void collision(const Options& o, Results& r);
void forces(const Options& o, Results& r);
void drop(const Options& o, Results& r);
void incline(const Options& o, Results& r);
void contactSchemes(const Options& o, Results& r);
void rolling(const Options& o, Results& r);
int rollingRuns(bool fast);
void clusters(const Options& o, Results& r);
}  // namespace contact
namespace hard_cases {
void stability(const Options& o, Results& r);
}  // namespace hard_cases
namespace cross_solver {
void chute(const Options& o, Results& r);
int chuteRuns(bool fast);
void column(const Options& o, Results& r);
int columnRuns(bool fast);
void silo(const Options& o, Results& r);
int siloRuns(bool fast);
}  // namespace cross_solver
namespace granular {
void siloDischarge(const Options& o, Results& r);
void siloConvergence(const Options& o, Results& r);
void siloConvergenceFits(const Options& o, Results& r);
int siloConvergenceRuns(bool fast);
void siloGranular(const Options& o, Results& r);
void siloGranularAsflip(const Options& o, Results& r);
void siloGranularFit(const Options& o, Results& r);
void compression(const Options& o, Results& r);
void chuteFlow(const Options& o, Results& r);
int chuteFlowRuns(bool fast);
void columnCollapse(const Options& o, Results& r);
int columnCollapseRuns(bool fast);
void columnSidewalls(const Options& o, Results& r);
int columnSidewallsRuns(bool fast);
}  // namespace granular
namespace sph {
void bar(const Options& o, Results& r);
void sph(const Options& o, Results& r);
}  // namespace sph
namespace debris {
void debris(const Options& o, Results& r);
void debrisSweep(const Options& o, Results& r);
void debrisEnsemble(const Options& o, Results& r);
void debrisGranular(const Options& o, Results& r);
void debrisGranularEnsembles(const Options& o, Results& r);
void debrisGranularFit(const Options& o, Results& r);
int debrisGranularFitRuns(bool fast);
void debrisGranularFitEnsembles(const Options& o, Results& r);
int debrisGranularRuns(bool fast);
void debrisSeed003(const Options& o, Results& r);
void debrisTimeStep(const Options& o, Results& r);
void debrisFlow(const Options& o, Results& r);
}  // namespace debris
namespace fem {
void femCantilever(const Options& o, Results& r);
void femIncline(const Options& o, Results& r);
void flexibleBarrier(const Options& o, Results& r);
void waterGate(const Options& o, Results& r);
int waterGateRuns(bool fast);
}  // namespace fem
namespace robots {
void wheel(const Options& o, Results& r);
void wheelGranular(const Options& o, Results& r);
int wheelRuns(bool fast);
void blade(const Options& o, Results& r);
void bladeGranular(const Options& o, Results& r);
// N/m^3: the upright plate's drag at its converged limit, alpha_x (intrusion_drag: Richardson
// over 2.5 and 1.25 mm; docs/robots.md).
inline constexpr Real kDragLimit = 102.3e3;
void intrusion(const Options& o, Results& r);
int intrusionRuns(bool fast);
void intrusionFits(const Options& o, Results& r);
void intrusionTransfer(const Options& o, Results& r);
int intrusionTransferRuns(bool fast);
void intrusionTransferFits(const Options& o, Results& r);
void intrusionRefinement(const Options& o, Results& r);
int intrusionRefinementRuns(bool fast);
void intrusionRefinementFits(const Options& o, Results& r);
void intrusionDrag(const Options& o, Results& r);
int intrusionDragRuns(bool fast);
void intrusionDiagnosis(const Options& o, Results& r);
int intrusionDiagnosisRuns(bool fast);
void intrusionDiagnosisFits(const Options& o, Results& r);
void intrusionFrontier(const Options& o, Results& r);
void intrusionFrontierFits(const Options& o, Results& r);
int intrusionFrontierRuns(bool fast);
void intrusionDragFits(const Options& o, Results& r);
void intrusionAngles(const Options& o, Results& r);
int intrusionAnglesRuns(bool fast);
void intrusionAnglesFits(const Options& o, Results& r);
}  // namespace robots

}  // namespace mpm_sdem::report
