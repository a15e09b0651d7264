// Seed 000 sec. 5.4 (Fig. 17-18), extended to every coupling scheme: the rod collision of
// validation/cases.hpp (400-point elastic rod at 2 cm/s into a free rigid rod of equal mass,
// Table 1's hard material and cgs-read stiffnesses) at grid sizes d_g = 0.1 to 1.0 cm; the run
// ends 60 ms after the free approach would close the gap, when the rods have separated.
//
// Reported per scheme and grid size:
//   energy error = |E(end) - E(0)| / E(0), E the kinetic energy of both rods plus the rod's
//                  strain energy (what the contact dissipates or creates);
//   v2 error     = |sum m v^2 (end) - sum m v^2 (0)| / sum m v^2 (0) (the seed's measure; it
//                  also counts the rod's vibration as a loss);
//   block speed  = the rigid rod's speed after the collision (2 cm/s for a perfect exchange);
//   us per step  = wall time per step, and the steps taken (the step is set by CFL and, for
//                  spring schemes, the contact term).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "cases.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

struct Result {
  Real energy_error, v2_error, block_speed, us_per_step;
  long steps;
};

Result run(CouplingScheme scheme, Real h) {
  Real approach = 0;
  const WorldDef def = cases::rodCollision(scheme, h, approach);
  World w(def);
  const Diagnostics d0 = measure(w);
  const Real e0 = d0.kinetic + d0.elastic;  // kinetic includes the blocks
  const Real end = approach + 0.06;
  const auto t0 = std::chrono::steady_clock::now();
  runUntil(w, end);
  const double sec = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Diagnostics d = measure(w);
  const Real e = d.kinetic + d.elastic;
  return {std::abs(e - e0) / e0, std::abs(d.kinetic - d0.kinetic) / d0.kinetic,
          w.blocks()->state(0).velocity.norm(), 1e6 * sec / w.stepCount(), w.stepCount()};
}

}  // namespace

int main(int argc, char** argv) {
  const char* csv = nullptr;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--csv") == 0) {
      csv = argv[i + 1];
    } else {
      std::fprintf(stderr, "usage: %s [--csv FILE]\n", argv[0]);
      return 2;
    }
  }
  if (argc % 2 == 0) {
    std::fprintf(stderr, "usage: %s [--csv FILE]\n", argv[0]);
    return 2;
  }
  FILE* out = csv ? std::fopen(csv, "w") : nullptr;
  if (csv && !out) {
    std::fprintf(stderr, "cannot write %s\n", csv);
    return 1;
  }
  if (out)
    std::fprintf(out,
                 "scheme,cell_size_m,energy_error,v2_error,block_speed_m_s,us_per_step,steps\n");
  std::printf("%-17s %7s %13s %10s %12s %12s %8s\n", "scheme", "d_g cm", "energy error", "v2 error",
              "block cm/s", "us per step", "steps");
  for (CouplingScheme scheme :
       {CouplingScheme::kImp, CouplingScheme::kImpGrid, CouplingScheme::kMultiVelocity,
        CouplingScheme::kParticleSurface, CouplingScheme::kPartitioned}) {
    for (int k = 1; k <= 10; ++k) {
      const Real h = 0.001 * k;
      const Result r = run(scheme, h);
      std::printf("%-17s %7.1f %13.3e %10.3e %12.4f %12.2f %8ld\n", couplingSchemeName(scheme),
                  100 * h, r.energy_error, r.v2_error, 100 * r.block_speed, r.us_per_step, r.steps);
      std::fflush(stdout);
      if (out)
        std::fprintf(out, "%s,%g,%.6g,%.6g,%.6g,%.4g,%ld\n", couplingSchemeName(scheme), h,
                     r.energy_error, r.v2_error, r.block_speed, r.us_per_step, r.steps);
    }
  }
  if (out) std::fclose(out);
  return 0;
}
