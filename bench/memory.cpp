// Memory of a long run: bytes per particle and per active grid node, and the resident set size
// every 1e5 steps, so that growth over a 1e6-step run shows. Runs the scene past its end time.
//   mpm_sdem_bench_memory [SCENE] [--steps 1000000]
#include <unistd.h>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

double residentMiB() {
  std::ifstream statm("/proc/self/statm");
  long total = 0, resident = 0;
  statm >> total >> resident;
  return static_cast<double>(resident) * sysconf(_SC_PAGESIZE) / (1024.0 * 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  std::string scene = std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/debris_impact.yaml";
  long steps = 1000000;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--steps" && i + 1 < argc)
      steps = std::atol(argv[++i]);
    else if (a[0] != '-')
      scene = a;
    else {
      std::fprintf(stderr, "usage: %s [SCENE] [--steps 1000000]\n", argv[0]);
      return 2;
    }
  }
  World w(loadScene(scene).world);
  std::printf("%s: %zu points, %ld steps\n%10s %10s %12s %14s %12s %12s\n", scene.c_str(),
              w.particles().size(), steps, "step", "time_s", "rss_MiB", "particle_B", "grid_B",
              "active_nodes");
  double rss_first = 0, rss_last = 0;
  for (long s = 1; s <= steps; ++s) {
    const StepInfo info = stepStable(w);
    if (!info.finite) {
      std::fprintf(stderr, "non-finite state at step %ld\n", s);
      return 1;
    }
    if (s % 100000 == 0 || s == steps) {
      const World::Memory m = w.memory();
      rss_last = residentMiB();
      if (rss_first == 0) rss_first = rss_last;
      std::printf("%10ld %10.2f %12.2f %14zu %12zu %12zu\n", s, w.time(), rss_last,
                  m.particle_bytes, m.grid_bytes, m.active_nodes);
      std::fflush(stdout);
    }
  }
  const World::Memory m = w.memory();
  std::printf(
      "bytes per particle %.1f; grid %zu nodes, %.1f bytes per node, %.1f grid bytes per "
      "active node (%zu active); resident set growth after the first 1e5 steps %.2f MiB\n",
      static_cast<double>(m.particle_bytes) / w.particles().size(), m.grid_nodes,
      static_cast<double>(m.grid_bytes) / m.grid_nodes,
      static_cast<double>(m.grid_bytes) / m.active_nodes, m.active_nodes, rss_last - rss_first);
  return 0;
}
