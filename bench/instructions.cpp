// Instructions per particle-step without timing noise: the column scene's steps under valgrind's
// callgrind, which counts only inside measuredSteps (bench/instructions.sh passes
// --toggle-collect for it). Usage: mpm_sdem_bench_instructions elastic|drucker_prager PARTICLES
// STEPS [usf|usl]; prints the particle count, for the script's division.
#include <omp.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "bench_scenes.hpp"
#include "mpm_sdem/core/stepper.hpp"

using namespace mpm_sdem;

// Not inlined, so that callgrind can switch its counting on and off at its boundaries.
__attribute__((noinline)) void measuredSteps(World& world, int steps) {
  for (int s = 0; s < steps; ++s) stepStable(world);
}

int main(int argc, char** argv) {
  if (argc != 4 && argc != 5) {
    std::fprintf(stderr, "usage: %s elastic|drucker_prager PARTICLES STEPS [usf|usl]\n", argv[0]);
    return 2;
  }
  const std::string update = argc == 5 ? argv[4] : "usf";
  if (update != "usf" && update != "usl") {
    std::fprintf(stderr, "stress update must be usf or usl, got '%s'\n", argv[4]);
    return 2;
  }
  const std::string model = argv[1];
  if (model != "elastic" && model != "drucker_prager") {
    std::fprintf(stderr, "model must be elastic or drucker_prager, got '%s'\n", argv[1]);
    return 2;
  }
  omp_set_num_threads(1);
  WorldDef def =
      bench::columnWorld(std::atol(argv[2]), model == "elastic" ? MaterialModel::kLinearElastic
                                                                : MaterialModel::kDruckerPrager);
  def.solver.stress_update = update == "usf" ? StressUpdate::kUsf : StressUpdate::kUsl;
  World world(def);
  for (int s = 0; s < 10; ++s) stepStable(world);  // warm-up, as throughput
  measuredSteps(world, std::atoi(argv[3]));
  std::printf("particles %zu\n", world.particles().size());
  return 0;
}
