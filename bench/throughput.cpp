// Scene-level throughput: particle-steps per second of the full step for column scenes of given
// sizes, materials and thread counts; medians over repeats. Prints a table and, with --csv FILE,
// writes it as CSV.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "bench_scenes.hpp"

using namespace mpm_sdem;

namespace {

std::vector<long> parseList(const char* s) {
  std::vector<long> out;
  std::stringstream in(s);
  for (std::string item; std::getline(in, item, ',');) out.push_back(std::atol(item.c_str()));
  return out;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<long> sizes{10000, 100000}, threads{1, 2};
  int steps = 200, repeats = 5;
  const char* csv = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string a = argv[i];
    if (a == "--particles")
      sizes = parseList(argv[i + 1]);
    else if (a == "--threads")
      threads = parseList(argv[i + 1]);
    else if (a == "--steps")
      steps = std::atoi(argv[i + 1]);
    else if (a == "--repeats")
      repeats = std::atoi(argv[i + 1]);
    else if (a == "--csv")
      csv = argv[i + 1];
    else {
      std::fprintf(stderr,
                   "usage: %s [--particles 10000,100000] [--threads 1,2] [--steps 200] "
                   "[--repeats 5] [--csv FILE]\n",
                   argv[0]);
      return 2;
    }
  }
  FILE* out = csv ? std::fopen(csv, "w") : nullptr;
  if (out) std::fprintf(out, "model,particles,threads,steps,median_particle_steps_per_s,min,max\n");
  std::printf("%-15s %10s %8s %22s %10s %10s\n", "model", "particles", "threads",
              "median Mpart-steps/s", "min", "max");
  for (MaterialModel model : {MaterialModel::kLinearElastic, MaterialModel::kDruckerPrager}) {
    for (long n : sizes) {
      for (long t : threads) {
        omp_set_num_threads(static_cast<int>(t));
        std::vector<double> rates;
        long count = 0;
        Profile profile;
        for (int r = 0; r < repeats; ++r) {
          World world(bench::columnWorld(n, model));
          count = static_cast<long>(world.particles().size());
          for (int s = 0; s < 10; ++s) world.step(world.chooseTimeStep().dt);  // warm-up
          world.resetProfile();
          const auto t0 = std::chrono::steady_clock::now();
          for (int s = 0; s < steps; ++s) world.step(world.chooseTimeStep().dt);
          const double sec =
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          rates.push_back(static_cast<double>(count) * steps / sec);
          if (r == 0) profile = world.profile();
        }
        const double med = median(rates);
        const auto [lo, hi] = std::minmax_element(rates.begin(), rates.end());
        std::printf("%-15s %10ld %8ld %22.3f %10.3f %10.3f\n", bench::modelName(model), count, t,
                    med * 1e-6, *lo * 1e-6, *hi * 1e-6);
        std::printf("  us per step:");
        for (int k = 0; k < static_cast<int>(Stage::kCount); ++k) {
          std::printf(" %s %.1f", stageName(static_cast<Stage>(k)),
                      1e6 * profile.seconds[k] / std::max(1L, profile.steps));
        }
        std::printf("\n");
        std::fflush(stdout);
        if (out) {
          std::fprintf(out, "%s,%ld,%ld,%d,%.6g,%.6g,%.6g\n", bench::modelName(model), count, t,
                       steps, med, *lo, *hi);
        }
      }
    }
  }
  if (out) std::fclose(out);
  return 0;
}
