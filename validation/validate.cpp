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
// --list prints the cases' names, one per line.
// Exit status 3 when a measured quantity is not a finite number (an unstable run).
// Each case lives in validation/report/<topic>.cpp (its world in cases.hpp); this file holds the
// list of cases and the command line.
#include <algorithm>
#include <chrono>
#include <cstdio>
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

int main(int argc, char** argv) {
  const auto started = std::chrono::steady_clock::now();
  const std::vector<std::pair<const char*, std::function<void(const Options&, Results&)>>> all{
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
      {"rolling", report::contact::rolling},
      {"chute", report::granular::chuteFlow},
      {"column_collapse", report::granular::columnCollapse},
      {"debris_granular", report::debris::debrisGranular},
      {"clusters", report::contact::clusters},
      {"fem_cantilever", report::fem::femCantilever},
      {"fem_incline", report::fem::femIncline},
      {"flexible_barrier", report::fem::flexibleBarrier},
      {"water_gate", report::fem::waterGate},
      {"bar", report::sph::bar},
      {"sph", report::sph::sph},
      {"silo", report::granular::siloDischarge},
      {"silo_convergence", report::granular::siloConvergence},
      {"silo_granular", report::granular::siloGranular},
      {"silo_granular_asflip", report::granular::siloGranularAsflip},
      {"compression", report::granular::compression},
      {"wheel", report::robots::wheel},
      {"wheel_granular", report::robots::wheelGranular},
      {"blade", report::robots::blade},
      {"blade_granular", report::robots::bladeGranular},
      {"stability", report::hard_cases::stability}};
  std::string names;
  for (const auto& entry : all) names += (names.empty() ? "" : ",") + std::string(entry.first);
  auto usage = [&] {
    std::fprintf(stderr, "usage: %s [--out DIR] [--fast] [--cases %s] [--list]\n", argv[0],
                 names.c_str());
    return 2;
  };
  Options o;
  std::vector<std::string> only;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--list") {
      for (const auto& entry : all) std::printf("%s\n", entry.first);
      return 0;
    } else if (a == "--fast") {
      o.fast = true;
    } else if (a == "--out" && i + 1 < argc) {
      o.out = argv[++i];
    } else if (a == "--cases" && i + 1 < argc) {
      std::string list = argv[++i];
      for (std::size_t p = 0; p != std::string::npos;) {
        const std::size_t q = list.find(',', p);
        only.push_back(list.substr(p, q == std::string::npos ? q : q - p));
        p = q == std::string::npos ? q : q + 1;
      }
    } else {
      return usage();
    }
  }
  for (const std::string& name : only) {
    if (std::none_of(all.begin(), all.end(), [&](const auto& e) { return name == e.first; })) {
      std::fprintf(stderr, "unknown case '%s'\n", name.c_str());
      return usage();
    }
  }
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  std::filesystem::remove(o.out + "/summary.csv", ec);  // a run is done only once it says so
  Results results(o.out + "/results.csv");
  if (!results.ok()) {
    std::fprintf(stderr, "cannot write %s/results.csv\n", o.out.c_str());
    return 1;
  }
  for (const auto& [name, run] : all) {
    if (!only.empty() && std::find(only.begin(), only.end(), name) == only.end()) continue;
    std::printf("%s (%s)\n", name, o.fast ? "fast" : "report resolution");
    std::fflush(stdout);
    run(o, results);
  }
  const int status = results.nonFinite() > 0 ? 3 : 0;
  if (status != 0)
    std::fprintf(stderr, "%d quantities are not finite numbers (an unstable run)\n",
                 results.nonFinite());
  std::ofstream(o.out + "/summary.csv")
      << "status,cases,wall_s\n"
      << status << ',' << (only.empty() ? all.size() : only.size()) << ','
      << std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() << '\n';
  return status;
}
