// Obstacles at scale (issue 39): the default scene with 0, 10, 100 and 1,000 static disks of
// 2 mm radius added as the node's ~spawn_obstacle adds them (placement check, add, time step),
// in a lattice of 6 mm in the scene's empty upper right. For each count: how many spawns a second
// the core takes (the last tenth of them), and the step's cost over the first SIM_TIME s of
// simulated time, one thread: wall time per step, real-time factor and the block and contact
// stages per step. Medians of REPEATS runs.
// usage: mpm_sdem_bench_obstacles [--counts 0,10,100,1000] [--sim-time 0.1] [--repeats 3]
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;
using Clock = std::chrono::steady_clock;

namespace {

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

double seconds(Clock::time_point since) {
  return std::chrono::duration<double>(Clock::now() - since).count();
}

// The k-th disk: a lattice of 6 mm from (0.36, 0.07) m, 39 to a row.
BlockDef disk(int k) {
  BlockDef d;
  d.name = "disk" + std::to_string(k);
  d.core = {Vec2(0, 0)};
  d.rounding = 0.002;
  d.position = Vec2(0.36 + 0.006 * (k % 39), 0.07 + 0.006 * (k / 39));
  d.type = BodyType::kStatic;
  return d;
}

struct Result {
  double spawn_rate = 0, step_ms = 0, rtf = 0, blocks_ms = 0, contact_ms = 0;
  long steps = 0;
};

Result run(const Scene& scene, int count, double sim_time) {
  World world(scene.world);
  Result r;
  const int timed = std::max(1, count / 10);
  Clock::time_point spawn_start = Clock::now();
  for (int k = 0; k < count; ++k) {
    if (k == count - timed) spawn_start = Clock::now();
    const BlockDef d = disk(k);
    if (const Problem p = world.placementProblem(d, false); !p.empty()) {
      std::fprintf(stderr, "disk %d: %s\n", k, p.text().c_str());
      std::exit(1);
    }
    world.addBlock(d);
    if (!(world.chooseTimeStep().dt >= limits::kMinTimeStep)) std::exit(1);
  }
  if (count > 0) r.spawn_rate = timed / seconds(spawn_start);
  const Profile before = world.profile();
  const Clock::time_point start = Clock::now();
  while (world.time() < sim_time) {
    stepStable(world);
    ++r.steps;
  }
  const double wall = seconds(start);
  const Profile& p = world.profile();
  r.step_ms = 1e3 * wall / r.steps;
  r.rtf = world.time() / wall;
  const Profile run = p.since(before);
  r.blocks_ms = 1e3 * run.ownerSeconds(StageOwner::kBodies) / r.steps;
  r.contact_ms = 1e3 * run.ownerSeconds(StageOwner::kCoupling) / r.steps;
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::vector<int> counts{0, 10, 100, 1000};
  double sim_time = 0.1;
  int repeats = 3;
  for (int i = 1; i < argc; i += 2) {
    const std::string a = argv[i];
    if (i + 1 >= argc) {  // --help, or an option without its value
      std::fprintf(a == "--help" ? stdout : stderr,
                   "usage: %s [--counts 0,10,100,1000] [--sim-time 0.1] [--repeats 3]\n", argv[0]);
      return a == "--help" ? 0 : 2;
    }
    if (a == "--counts") {
      counts.clear();
      std::stringstream in(argv[i + 1]);
      for (std::string c; std::getline(in, c, ',');) counts.push_back(std::atoi(c.c_str()));
    } else if (a == "--sim-time") {
      sim_time = std::atof(argv[i + 1]);
    } else if (a == "--repeats") {
      repeats = std::atoi(argv[i + 1]);
    } else {
      std::fprintf(stderr, "unknown option %s\n", a.c_str());
      return 2;
    }
  }
  omp_set_num_threads(1);
  const Scene scene =
      loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/debris_impact.yaml");
  std::printf("%8s %12s %10s %10s %12s %12s %8s\n", "disks", "spawns/s", "ms/step", "x real",
              "bodies ms", "contact ms", "steps");
  for (int count : counts) {
    std::vector<double> rate, step, rtf, blocks, contact;
    long steps = 0;
    for (int k = 0; k < repeats; ++k) {
      const Result r = run(scene, count, sim_time);
      rate.push_back(r.spawn_rate);
      step.push_back(r.step_ms);
      rtf.push_back(r.rtf);
      blocks.push_back(r.blocks_ms);
      contact.push_back(r.contact_ms);
      steps = r.steps;
    }
    std::printf("%8d %12.0f %10.4f %10.3f %12.4f %12.4f %8ld\n", count, median(rate), median(step),
                median(rtf), median(blocks), median(contact), steps);
    std::fflush(stdout);
  }
  return 0;
}
