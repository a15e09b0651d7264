#include "mpm_sdem/sim/simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <utility>

#include "mpm_sdem/core/limits.hpp"

namespace mpm_sdem {

Simulation::Simulation(World& world, const RunDef& def)
    : world_(world),
      def_(def),
      stepper_(world, def.step_collapse),
      initial_(measure(world)),
      stable_(world.chooseTimeStep()),
      samples_(def.sample_interval > 0 ? 1 / def.sample_interval : 0) {
  if (def_.threads > 0)
    omp_set_num_threads(def_.threads);
  else
    // A world that steps on one thread anyway (World::sharesWork) gains nothing from trials.
    tuner_ = std::make_unique<ThreadTuner>(
        world.sharesWork() ? std::min(omp_get_max_threads(), limits::logicalCores()) : 1);
  world_.setCommandLog(
      [this](const WorldCommand& c) { tell([&](RunOutput& o) { o.command(c); }); });
}

Simulation::~Simulation() {
  world_.setCommandLog({});
}

void Simulation::attach(RunOutput& output) {
  outputs_.push_back(&output);
}

std::string Simulation::start(bool resumed) {
  stable_ = world_.chooseTimeStep();  // of the state the run starts from (a resumed one's)
  // A resumed run's schedule goes on from the checkpoint's time, which its writer sampled.
  if (resumed) samples_.due(world_.time(), true);
  tell([&](RunOutput& o) { o.start(world_, resumed); });
  // The first sample is the first state's, with the totals the guard measured.
  if (!resumed && samples_.due(world_.time()))
    tell([&](RunOutput& o) { o.sample(world_, initial_); });
  return std::exchange(dropped_, {});
}

bool Simulation::ended() const {
  return reachedEnd(world_.time(), def_.end_time);
}

int Simulation::threads() const {
  return tuner_ ? tuner_->threads() : def_.threads;
}

void Simulation::tell(const std::function<void(RunOutput&)>& f) {
  for (auto it = outputs_.begin(); it != outputs_.end();) {
    try {
      f(**it);
      ++it;
    } catch (const std::exception& e) {
      dropped_ += (dropped_.empty() ? "" : "; ") + std::string(e.what());
      it = outputs_.erase(it);
    }
  }
}

RunStep Simulation::advance(const std::function<void(Real)>& before_step) {
  RunStep out;
  const auto wall = std::chrono::steady_clock::now();
  if (tuner_) tuner_->beforeStep();
  const PlannedStep step = stepper_.plan(def_.end_time);
  stable_ = step.stable;
  if (!step.problem.empty()) {
    out.problem = step.problem;
    return out;
  }
  if (before_step) before_step(step.dt);
  out.info = stepper_.take(step, out.problem);
  out.dt = step.dt;
  if (tuner_)
    tuner_->afterStep(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall).count());
  if (!out.problem.empty()) return out;
  if (samples_.due(world_.time()) || ended()) sample(out);
  // After the sample: a checkpoint written by step() follows every output of its time.
  if (out.problem.empty()) tell([&](RunOutput& o) { o.step(world_); });
  out.output_problem = std::exchange(dropped_, {});  // this step's, and a command's since
  return out;
}

void Simulation::sample(RunStep& out) {
  out.sampled = true;
  const Diagnostics d = measure(world_);
  char text[320];
  if (!d.finite) {
    out.problem = "energy or momentum became non-finite (not written)";
    return;
  }
  if (d.total() > initial_.total() * (1 + def_.energy_growth) &&
      d.total() - initial_.total() > 1e-12) {
    std::snprintf(text, sizeof text,
                  "the total energy grew from %g to %g J/m, past +%g%% of the first state's "
                  "(limits.energy_growth): the step is likely unstable",
                  initial_.total(), d.total(), def_.energy_growth * 100);
    out.problem = text;  // the sample is written: it shows the growth
  } else if (const std::string w = machWarning(d, world_.time()); !w.empty() && !mach_warned_) {
    out.warning = w;
    mach_warned_ = true;
  }
  tell([&](RunOutput& o) { o.sample(world_, d); });
}

void Simulation::blocksChanged() {
  stable_ = world_.chooseTimeStep();
  tell([&](RunOutput& o) { o.blocksChanged(world_); });
}

std::string Simulation::finish(bool sound) {
  tell([&](RunOutput& o) { o.finish(world_, sound); });
  outputs_.clear();
  return std::exchange(dropped_, {});
}

}  // namespace mpm_sdem
