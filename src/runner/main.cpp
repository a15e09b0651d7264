// mpm_sdem_run: runs a scene without ROS and writes CSV outputs. See usage() for the interface;
// run.hpp for what a run holds, sim/simulation.hpp for its step loop.
#include <chrono>
#include <csignal>
#include <iostream>

#include "progress.hpp"
#include "run.hpp"

using namespace mpm_sdem;

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
void onSignal(int) {
  g_interrupted = 1;
}

}  // namespace

int main(int argc, char** argv) {
  const auto started = std::chrono::steady_clock::now();
  runner::Options opt;
  std::string error;
  bool help = false;
  if (!runner::parseOptions(argc, argv, opt, error, help)) {
    std::cerr << "mpm_sdem_run: " << error << "\n" << runner::usage();
    return 2;
  }
  if (help) {
    std::cout << runner::usage();
    return 0;
  }
  runner::Run run;
  if (!runner::prepare(opt, run)) return 1;
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);
  World& world = *run.world;
  runner::Progress progress(run.scene.end_time, !opt.quiet);
  int status = 0;
  bool outside_warned = false;
  while (!run.sim->ended() && !g_interrupted) {
    // Where the node applies them: between steps, before the next step is chosen.
    if (run.replay && run.replay->applyDue(world)) run.sim->blocksChanged();
    const RunStep step = run.sim->advance();
    if (!step.problem.empty()) {
      std::cerr << "\nerror: at step " << world.stepCount() << ", t = " << world.time() << " s, "
                << step.problem << ". Lower time.cfl or time.dt, or refine the grid.\n";
      status = 3;
      break;
    }
    if (!step.output_problem.empty()) {  // a file that cannot be written ends the run
      std::cerr << "\nerror: " << step.output_problem << "\n";
      status = 1;
      break;
    }
    if (!step.warning.empty()) std::cerr << "\nwarning: " << step.warning << "\n";
    // A block outside the domain leaves the material's grid: said once, the run goes on (the
    // node pauses instead, as it does for the requests that push blocks out).
    if (!step.info.block_problem.empty() && !outside_warned) {
      std::cerr << "\nwarning: at t = " << world.time() << " s, " << step.info.block_problem
                << "\n";
      outside_warned = true;
    }
    progress.update(world.stepCount(), world.time(), step.dt,
                    static_cast<long>(world.particles().size()));
  }
  progress.finish(world.stepCount(), world.time(), static_cast<long>(world.particles().size()));
  if (g_interrupted) {
    std::cerr << "interrupted at t = " << world.time() << " s; writing the state reached\n";
    status = 130;
  }
  return runner::finish(
      run, status,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count());
}
