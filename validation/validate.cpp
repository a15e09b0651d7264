// mpm_sdem_validate: runs the seeds' verification and validation cases and writes what they
// measured for the report (scripts/validate turns it into docs/validation/REPORT.md):
//   <out>/results.csv   one row per quantity: case, quantity, value, reference, unit, source,
//                       error (relative to the reference, or absolute when the reference is 0),
//                       wall time of the run, settings, and the run's points and steps
//                       (0 when not counted) for its particle-steps per second;
//   <out>/<case>_*.csv  time series and sweeps for the plots;
//   <out>/summary.csv   written last: the exit status, the cases run and the wall time (a
//                       sweep's run is done when it says status 0: scripts/validate runs each
//                       case as a run of mpm_sdem_sweep, config/sweeps/ docs).
// --fast runs every case at CI resolution (seconds); without it, at the seeds' resolution.
// A long case is split into runs (one per resolution, or per ensemble member), each its own
// run of the sweep: --cases name.N runs only its run N; --list --runs names every run
// ("name" for a case that is one run, "name.0" ... for a split one). A split case that fits
// across its runs (a convergence order, an ensemble's mean) does so in a combine step from the
// tables its runs wrote: after them when the whole case runs, or, once the runs are gathered
// into one directory, by --combine --out DIR (adding to DIR/results.csv, after the case's rows).
// Exit status 3 when a measured quantity is not a finite number (an unstable run).
// Each case lives in validation/report/<topic>.cpp (its world in cases.hpp); this file holds the
// list of cases and the command line.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "report/report.hpp"

using namespace mpm_sdem;
using report::Options;
using report::Results;

namespace {

// A case of the report: its runs (1 unless split; at --fast or the report's resolution), and
// for a split case that fits across its runs, the step that does so from their tables.
struct Case {
  const char* name;
  std::function<void(const Options&, Results&)> run;
  std::function<int(bool fast)> runs = [](bool) { return 1; };
  std::function<void(const Options&, Results&)> combine = nullptr;
};

const std::vector<Case>& allCases() {
  static const std::vector<Case> all{
      {"collision", report::contact::collision},
      {"drop", report::contact::drop},
      {"forces", report::contact::forces},
      {"incline", report::contact::incline},
      {"contact_schemes", report::contact::contactSchemes},
      {"debris", report::debris::debris},
      {"debris_sweep", report::debris::debrisSweep},
      {"debris_ensemble", report::debris::debrisEnsemble},
      {"debris_seed003", report::debris::debrisSeed003},
      {"debris_timestep", report::debris::debrisTimeStep},
      {"debris_flow", report::debris::debrisFlow},
      {"rolling", report::contact::rolling, report::contact::rollingRuns},
      {"chute", report::granular::chuteFlow, report::granular::chuteFlowRuns},
      {"column_collapse", report::granular::columnCollapse, report::granular::columnCollapseRuns},
      {"column_sidewalls", report::granular::columnSidewalls,
       report::granular::columnSidewallsRuns},
      {"cross_chute", report::cross_solver::chute, report::cross_solver::chuteRuns},
      {"cross_column", report::cross_solver::column, report::cross_solver::columnRuns},
      {"cross_silo", report::cross_solver::silo, report::cross_solver::siloRuns},
      {"debris_granular", report::debris::debrisGranular, report::debris::debrisGranularRuns,
       report::debris::debrisGranularEnsembles},
      {"debris_granular_fit", report::debris::debrisGranularFit,
       report::debris::debrisGranularFitRuns, report::debris::debrisGranularFitEnsembles},
      {"clusters", report::contact::clusters},
      {"fem_cantilever", report::fem::femCantilever},
      {"fem_incline", report::fem::femIncline},
      {"flexible_barrier", report::fem::flexibleBarrier},
      {"water_gate", report::fem::waterGate, report::fem::waterGateRuns},
      {"bar", report::sph::bar},
      {"sph", report::sph::sph},
      {"silo", report::granular::siloDischarge},
      {"silo_convergence", report::granular::siloConvergence, report::granular::siloConvergenceRuns,
       report::granular::siloConvergenceFits},
      {"silo_granular", report::granular::siloGranular},
      {"silo_granular_asflip", report::granular::siloGranularAsflip},
      {"silo_granular_fit", report::granular::siloGranularFit},
      {"compression", report::granular::compression},
      {"wheel", report::robots::wheel, report::robots::wheelRuns},
      {"wheel_granular", report::robots::wheelGranular, report::robots::wheelRuns},
      {"blade", report::robots::blade},
      {"blade_granular", report::robots::bladeGranular},
      {"intrusion", report::robots::intrusion, report::robots::intrusionRuns,
       report::robots::intrusionFits},
      {"intrusion_transfer", report::robots::intrusionTransfer,
       report::robots::intrusionTransferRuns, report::robots::intrusionTransferFits},
      {"intrusion_refinement", report::robots::intrusionRefinement,
       report::robots::intrusionRefinementRuns, report::robots::intrusionRefinementFits},
      {"intrusion_drag", report::robots::intrusionDrag, report::robots::intrusionDragRuns,
       report::robots::intrusionDragFits},
      {"intrusion_diagnosis", report::robots::intrusionDiagnosis,
       report::robots::intrusionDiagnosisRuns, report::robots::intrusionDiagnosisFits},
      {"intrusion_frontier", report::robots::intrusionFrontier,
       report::robots::intrusionFrontierRuns, report::robots::intrusionFrontierFits},
      {"intrusion_angles", report::robots::intrusionAngles, report::robots::intrusionAnglesRuns,
       report::robots::intrusionAnglesFits},
      {"stability", report::hard_cases::stability}};
  return all;
}

// One entry of --cases: a case, and one of its runs or -1 for all of them.
struct Selected {
  const Case* c;
  int part;
};

// "name" or "name.N"; an empty `problem` when it names a case (and a run it has).
Selected select(const std::string& entry, bool fast, std::string& problem) {
  const std::size_t dot = entry.find('.');
  const std::string name = entry.substr(0, dot);
  for (const Case& c : allCases()) {
    if (name != c.name) continue;
    if (dot == std::string::npos) return {&c, -1};
    const std::string digits = entry.substr(dot + 1);
    const int n = c.runs(fast);
    if (n > 1 && !digits.empty() && digits.size() < 6 &&
        digits.find_first_not_of("0123456789") == std::string::npos && std::stoi(digits) < n)
      return {&c, std::stoi(digits)};
    problem = "'" + entry + "': " + name +
              (n > 1 ? " has runs " + name + ".0 to " + name + "." + std::to_string(n - 1)
                     : " is one run (no .N)") +
              (fast ? " with --fast" : " at the report's resolution");
    return {nullptr, -1};
  }
  problem = "unknown case '" + name + "'";
  return {nullptr, -1};
}

// results.csv's rows in the cases' order, each case's in the order written (the combined rows
// appended by --combine then follow their case's runs, as in a run of the whole case).
bool orderByCase(const std::string& path) {
  std::ifstream in(path);
  std::string header, line;
  std::getline(in, header);
  std::vector<std::pair<std::size_t, std::string>> rows;
  const std::vector<Case>& all = allCases();
  while (std::getline(in, line)) {
    const std::string name = line.substr(0, line.find(','));
    std::size_t k = 0;
    while (k < all.size() && name != all[k].name) ++k;
    rows.emplace_back(k, line);
  }
  std::stable_sort(rows.begin(), rows.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::ofstream out(path);
  out << header << '\n';
  for (const auto& row : rows) out << row.second << '\n';
  return static_cast<bool>(out);
}

}  // namespace

int main(int argc, char** argv) {
  const auto started = std::chrono::steady_clock::now();
  std::string names;
  for (const Case& c : allCases()) names += (names.empty() ? "" : ",") + std::string(c.name);
  auto usage = [&] {
    std::fprintf(stderr,
                 "usage: %s [--out DIR] [--fast] [--cases NAME[.RUN],...] [--list [--runs]] "
                 "[--combine]\n  cases: %s\n",
                 argv[0], names.c_str());
    return 2;
  };
  Options o;
  bool list = false, list_runs = false, combine = false;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--list") {
      list = true;
    } else if (a == "--runs") {
      list_runs = true;
    } else if (a == "--combine") {
      combine = true;
    } else if (a == "--fast") {
      o.fast = true;
    } else if (a == "--out" && i + 1 < argc) {
      o.out = argv[++i];
    } else if (a == "--cases" && i + 1 < argc) {
      std::string entries = argv[++i];
      for (std::size_t p = 0; p != std::string::npos;) {
        const std::size_t q = entries.find(',', p);
        only.push_back(entries.substr(p, q == std::string::npos ? q : q - p));
        p = q == std::string::npos ? q : q + 1;
      }
    } else {
      return usage();
    }
  }
  if (list_runs && !list) return usage();
  std::vector<Selected> selected;
  for (const std::string& entry : only) {
    std::string problem;
    selected.push_back(select(entry, o.fast, problem));
    if (!problem.empty()) {
      std::fprintf(stderr, "%s\n", problem.c_str());
      return usage();
    }
  }
  if (only.empty())
    for (const Case& c : allCases()) selected.push_back({&c, -1});
  if (list) {
    for (const Selected& s : selected) {
      const int n = list_runs && s.part < 0 ? s.c->runs(o.fast) : 1;
      for (int k = 0; k < n; ++k)
        std::printf("%s%s\n", s.c->name,
                    n > 1 ? ("." + std::to_string(k)).c_str()
                          : (s.part >= 0 ? "." + std::to_string(s.part) : "").c_str());
    }
    return 0;
  }
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  if (combine) {  // the split cases' fits, from their runs' tables gathered in --out
    Results results(o.out + "/results.csv", true);
    if (!results.ok()) {
      std::fprintf(stderr, "cannot append to %s/results.csv\n", o.out.c_str());
      return 1;
    }
    for (const Selected& s : selected) {
      if (!s.c->combine) continue;
      std::printf("%s: combining its runs (%s)\n", s.c->name,
                  o.fast ? "fast" : "report resolution");
      try {
        s.c->combine(o, results);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s: %s\n", s.c->name, e.what());
        return 1;
      }
    }
    const int status = results.nonFinite() > 0 ? 3 : 0;
    results.close();
    if (!orderByCase(o.out + "/results.csv")) {
      std::fprintf(stderr, "cannot rewrite %s/results.csv\n", o.out.c_str());
      return 1;
    }
    return status;
  }
  std::filesystem::remove(o.out + "/summary.csv", ec);  // a run is done only once it says so
  Results results(o.out + "/results.csv");
  if (!results.ok()) {
    std::fprintf(stderr, "cannot write %s/results.csv\n", o.out.c_str());
    return 1;
  }
  for (const Selected& s : selected) {
    Options run = o;
    run.part = s.part;
    if (s.part >= 0)
      std::printf("%s, run %d of %d (%s)\n", s.c->name, s.part + 1, s.c->runs(o.fast),
                  o.fast ? "fast" : "report resolution");
    else
      std::printf("%s (%s)\n", s.c->name, o.fast ? "fast" : "report resolution");
    std::fflush(stdout);
    try {
      s.c->run(run, results);
      if (s.part < 0 && s.c->combine) s.c->combine(run, results);
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: %s\n", s.c->name, e.what());
      return 1;
    }
  }
  const int status = results.nonFinite() > 0 ? 3 : 0;
  if (status != 0)
    std::fprintf(stderr, "%d quantities are not finite numbers (an unstable run)\n",
                 results.nonFinite());
  std::ofstream(o.out + "/summary.csv")
      << "status,cases,wall_s\n"
      << status << ',' << selected.size() << ','
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() << '\n';
  return status;
}
