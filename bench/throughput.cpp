// Scene-level throughput: particle-steps per second of the full step (time step choice included)
// for the column scenes of given sizes and materials and for scene files (optionally refined to
// another cell size), on given thread counts; medians over repeats, with the per-stage profile
// of the first repeat. Prints a table and, with --csv FILE, writes it as CSV.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scenes.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

std::vector<std::string> split(const char* s) {
  std::vector<std::string> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(item);
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

struct Case {
  std::string name;
  WorldDef def;
};

}  // namespace

int main(int argc, char** argv) {
  std::vector<std::string> sizes{"10000", "100000"}, threads{"1", "2"}, scenes, updates{"usf"};
  int steps = 200, repeats = 5;
  const char* csv = nullptr;
  auto usage = [&](FILE* to) {
    std::fprintf(to,
                 "usage: %s [--particles 10000,100000] [--threads 1,2] "
                 "[--scenes FILE[@CELL_SIZE_M][#COUPLING_SCHEME],...] [--steps 200] "
                 "[--repeats 5] [--csv FILE] [--update usf,usl]\n"
                 "  --update: the columns' stress update (USF, seed 000 sec. 2.2, or USL); scenes "
                 "keep their own\n",
                 argv[0]);
    return to == stdout ? 0 : 2;
  };
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") return usage(stdout);
    if (i + 1 >= argc) return usage(stderr);  // an option without its value
    if (a == "--particles")
      sizes = split(argv[i + 1]);
    else if (a == "--threads")
      threads = split(argv[i + 1]);
    else if (a == "--scenes")  // FILE[@CELL_SIZE][#COUPLING_SCHEME],...
      scenes = split(argv[i + 1]);
    else if (a == "--steps")
      steps = std::atoi(argv[i + 1]);
    else if (a == "--repeats")
      repeats = std::atoi(argv[i + 1]);
    else if (a == "--csv")
      csv = argv[i + 1];
    else if (a == "--update")
      updates = split(argv[i + 1]);
    else
      return usage(stderr);
  }
  std::vector<Case> cases;
  for (const std::string& u : updates) {
    if (u != "usf" && u != "usl") return usage(stderr);
    for (MaterialModel model : {MaterialModel::kLinearElastic, MaterialModel::kDruckerPrager}) {
      for (const std::string& n : sizes) {
        Case c{std::string("column_") + bench::modelName(model) + (u == "usl" ? "_usl" : ""),
               bench::columnWorld(std::atol(n.c_str()), model)};
        if (u == "usl") c.def.solver.stress_update = StressUpdate::kUsl;
        cases.push_back(c);
      }
    }
  }
  for (const std::string& spec : scenes) {
    const std::size_t hash = spec.find('#');
    const std::string s = spec.substr(0, hash);
    const std::size_t at = s.find('@');
    Case c{s.substr(0, at), loadScene(s.substr(0, at)).world};
    c.name = c.name.substr(c.name.find_last_of('/') + 1);
    if (at != std::string::npos) {
      c.def.cell_size = std::atof(s.c_str() + at + 1);  // same points per cell: refined
      c.name += "@" + s.substr(at + 1);
    }
    if (hash != std::string::npos) {
      const std::string scheme = spec.substr(hash + 1);
      bool known = false;
      for (CouplingScheme k :
           {CouplingScheme::kImp, CouplingScheme::kImpGrid, CouplingScheme::kMultiVelocity,
            CouplingScheme::kParticleSurface, CouplingScheme::kPartitioned}) {
        if (scheme == couplingSchemeName(k)) {
          c.def.coupling.scheme = k;
          known = true;
        }
      }
      if (!known) {
        std::fprintf(stderr, "unknown coupling scheme '%s' in '%s'\n", scheme.c_str(),
                     spec.c_str());
        return 2;
      }
      c.name += "#" + scheme;
    }
    cases.push_back(c);
  }

  FILE* out = csv ? std::fopen(csv, "w") : nullptr;
  if (out) {
    std::fprintf(out, "case,particles,threads,steps,median_particle_steps_per_s,min,max");
    for (int k = 0; k < static_cast<int>(Stage::kCount); ++k)
      std::fprintf(out, ",us_%s", stageName(static_cast<Stage>(k)));
    std::fprintf(out, ",median_realtime_factor,mean_dt_s\n");
  }
  std::printf("%-36s %10s %8s %14s %10s %10s\n", "case", "particles", "threads", "median M/s",
              "min", "max");
  for (const Case& c : cases) {
    for (const std::string& t : threads) {
      omp_set_num_threads(std::atoi(t.c_str()));
      std::vector<double> rates, realtime;
      long count = 0;
      double mean_dt = 0;
      Profile profile;
      for (int r = 0; r < repeats; ++r) {
        World world(c.def);
        count = static_cast<long>(world.particles().size());
        for (int s = 0; s < 10; ++s) stepStable(world);  // warm-up
        world.resetProfile();
        const double sim0 = world.time();
        const auto t0 = std::chrono::steady_clock::now();
        for (int s = 0; s < steps; ++s) stepStable(world);
        const double sec =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        rates.push_back(static_cast<double>(count) * steps / sec);
        realtime.push_back((world.time() - sim0) / sec);
        mean_dt = (world.time() - sim0) / steps;
        if (r == 0) profile = world.profile();
      }
      const double med = median(rates);
      const auto [lo, hi] = std::minmax_element(rates.begin(), rates.end());
      std::printf("%-36s %10ld %8s %14.3f %10.3f %10.3f\n  us per step:", c.name.c_str(), count,
                  t.c_str(), med * 1e-6, *lo * 1e-6, *hi * 1e-6);
      if (out) {
        std::fprintf(out, "%s,%ld,%s,%d,%.6g,%.6g,%.6g", c.name.c_str(), count, t.c_str(), steps,
                     med, *lo, *hi);
      }
      for (int k = 0; k < static_cast<int>(Stage::kCount); ++k) {
        const double us = 1e6 * profile.seconds[k] / std::max(1L, profile.steps);
        if (profile.used[k]) std::printf(" %s %.1f", stageName(static_cast<Stage>(k)), us);
        if (out) std::fprintf(out, ",%.2f", us);
      }
      std::printf("\n  real-time factor %.3f, mean dt %.3g s\n", median(realtime), mean_dt);
      if (out) std::fprintf(out, ",%.4g,%.4g\n", median(realtime), mean_dt);
      std::fflush(stdout);
    }
  }
  if (out) std::fclose(out);
  return 0;
}
