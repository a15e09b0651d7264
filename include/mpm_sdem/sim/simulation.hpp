/// \file
/// A run's step loop as the runner (mpm_sdem_run) and the node take it: the stable step chosen,
/// checked and landed on the end time (Stepper), the guards that stop a run gone wrong (the
/// step's collapse, a non-finite state, the energy's growth), samples at a fixed interval of
/// simulated time, and the run's outputs (time series, bags, videos, ParaView frames,
/// checkpoints) told of its start, each step, sample, command and block change, and its end.
/// A layer above the core with no ROS and no files of its own: the outputs are the callers'.
#pragma once

#include <chrono>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/thread_tuner.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

/// One of a run's outputs. Told, in this order: start, then after each step step() (and
/// sample() first when a sample is due), command() for every command applied to the world and
/// blocksChanged() when the caller says so, and finish() once. Each may throw std::exception
/// when it cannot write: the driver then drops it and says why (RunStep::output_problem); the
/// caller decides whether the run goes on. The world is not const only because saving a
/// checkpoint may rebuild Box2D's bodies (saveCheckpoint); outputs do not change it.
class RunOutput {
 public:
  virtual ~RunOutput() = default;
  /// The run's first state, or (resumed) the state a resumed run continues from, which the
  /// output's files already hold when it continues them.
  virtual void start(World& /*world*/, bool /*resumed*/) {}
  /// After every sound step, and after that step's sample (so that a checkpoint written here
  /// follows every output of its time).
  virtual void step(World& /*world*/) {}
  /// At every multiple of RunDef::sample_interval and at the end time, with the state's totals.
  virtual void sample(const World& /*world*/, const Diagnostics& /*totals*/) {}
  /// A command applied to the world (a request, a held load, a replayed command).
  virtual void command(const WorldCommand& /*command*/) {}
  /// The blocks were spawned, removed or moved by a command.
  virtual void blocksChanged(const World& /*world*/) {}
  /// The run ends. sound: its state is finite and passed the guards (worth a checkpoint and a
  /// last frame).
  virtual void finish(World& /*world*/, bool /*sound*/) {}
};

/// How a run steps (the scene's time and limits sections give the values).
struct RunDef {
  /// s; the steps land on it exactly (infinite: no end, the stable step as chosen).
  Time end_time = std::numeric_limits<Time>::infinity();
  /// s of simulated time between samples (0: none but the end time's).
  Real sample_interval = 0;
  /// limits.step_collapse: a stable step below this fraction of the reference step stops.
  Real step_collapse = 1e-3;
  /// limits.energy_growth: a total energy above (1 + this) times the first state's stops the
  /// run (checked at samples). Infinite: not checked (the node: commanded obstacles do work).
  Real energy_growth = std::numeric_limits<Real>::infinity();
  /// OpenMP threads; 0: a ThreadTuner picks them from the steps' wall time.
  int threads = 0;
};

/// What one step of the loop did.
struct RunStep {
  /// Why the run must stop (one clause, no full stop): the step collapsed, the state became
  /// non-finite or the energy grew past its limit. Empty: the step was taken and checked.
  std::string problem;
  /// The errors of outputs that failed (and were dropped) in this step, or in a command or
  /// block change since the last. The run may go on without them.
  std::string output_problem;
  /// A warning said once per run (a fluid's Mach number); empty otherwise.
  std::string warning;
  Real dt = 0;           ///< s, the step taken (0 when the guard stopped it first)
  bool sampled = false;  ///< a sample was taken after the step
  StepInfo info;         ///< the world's account of the step (a block outside the domain...)
};

/// The step loop of one world (see the file's comment). The world outlives the driver and the
/// outputs outlive it or are detached by finish().
class Simulation {
 public:
  /// The first state's energy is the energy guard's reference: make the driver before resuming
  /// the world, so that a resumed run keeps the limit of the run it continues.
  Simulation(World& world, const RunDef& def);
  ~Simulation();
  Simulation(const Simulation&) = delete;
  Simulation& operator=(const Simulation&) = delete;

  /// Adds an output (not owned, alive until finish()), before start().
  void attach(RunOutput& output);
  /// Starts the outputs and the sample schedule. resumed: the world continues a checkpoint,
  /// whose time was sampled by the run that wrote it. Returns the errors of outputs that failed
  /// (and were dropped); empty when none did.
  std::string start(bool resumed);

  /// One step: the stable step, checked and landed on the end time; before_step(dt) acts on the
  /// world with its length (the node's obstacle drivers); the outputs; the sample when due.
  RunStep advance(const std::function<void(Real)>& before_step = {});
  /// Whether the end time has been reached (never with an infinite one).
  bool ended() const;
  /// A new end time (the node runs on past the scene's end: infinity).
  void setEndTime(Time end_time) { def_.end_time = end_time; }

  /// After a command changed the blocks: the step is chosen again and the outputs told.
  void blocksChanged();
  /// The stable step as last chosen (before the first step: the world's at the start).
  const TimeStepChoice& stableStep() const { return stable_; }
  /// The totals of the first state (the energy guard's reference).
  const Diagnostics& initial() const { return initial_; }
  /// Threads the steps run on (the tuner's current choice with threads: 0).
  int threads() const;

  /// Ends the run: each attached output's finish(sound), then all are detached (called again, it
  /// does nothing). Returns the errors of outputs that failed; empty when none did. The
  /// destructor does not finish: a caller that stops on an exception decides what is sound.
  std::string finish(bool sound);

 private:
  /// Tells every output f; an output that throws is dropped and its error added to dropped_.
  void tell(const std::function<void(RunOutput&)>& f);
  /// Measures the state and applies the non-finite and energy guards; tells the outputs.
  void sample(RunStep& out);

  World& world_;
  RunDef def_;
  Stepper stepper_;
  Diagnostics initial_;
  TimeStepChoice stable_;
  SampleClock samples_;
  std::unique_ptr<ThreadTuner> tuner_;
  std::vector<RunOutput*> outputs_;
  std::string dropped_;  ///< errors of outputs dropped since they were last reported
  bool mach_warned_ = false;
};

}  // namespace mpm_sdem
