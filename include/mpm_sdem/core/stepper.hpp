/// \file
/// How a step is taken: the rule for landing on an end time (stepTowards), the plain loops of
/// tests, validation and benchmarks (stepStable, runUntil), one step of a run as the runner and
/// the node take it (Stepper), and the stop for a run whose stable step has collapsed (StepGuard).
///
/// StepGuard: the stop for a run whose stable step has collapsed. An unstable run does not always
/// raise its total energy past limits.energy_growth (gravity's part dominates a settling flow): the
/// partitioned blow-up of 2026-11-28 drove one point at 4,000 m/s^2 and cut the CFL step from
/// 31 us to 2 ns while the total stayed below the limit. No accepted input shortens a step by
/// anything near a thousand times in a sane run (the fastest command, 1e3 m/s, takes a sand's
/// CFL step down by 30-100 times), so a step far below the first one is a symptom of a blow-up.
/// The runner and the node ask it before every step (through Stepper).
#pragma once

#include <cstdint>
#include <limits>
#include <string>

#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

/// The one rule for landing on an end time, used by every loop (Stepper, stepStable, runUntil):
/// the step to take towards end_time given the stable step dt lands exactly on end_time and
/// merges a sliver of a last step into the one before it (half of the remainder each).
Real stepTowards(Real dt, Time end_time, Time time);
/// Whether a run landing its steps with stepTowards has reached end_time: within 1e-9 of it,
/// relative (the landed steps' sum may miss it by rounding, never by a step).
bool reachedEnd(Time time, Time end_time);

/// A step as tests, validation cases and benchmarks take it: the world's stable step, landed on
/// end_time (stepTowards); with no end time, the stable step as chosen. The runner and the node
/// add the guards through Stepper.
StepInfo stepStable(World& world, Time end_time = std::numeric_limits<Time>::infinity());
/// stepStable until end_time is reached (reachedEnd) or a step leaves the state non-finite; that
/// last step's info (a default StepInfo when already there).
StepInfo runUntil(World& world, Time end_time);

/// Stops a run whose stable step has collapsed (see the file's comment).
class StepGuard {
 public:
  /// collapse_fraction: the stop lies at this fraction of the reference step (scene key
  /// limits.step_collapse).
  explicit StepGuard(Real collapse_fraction) : fraction_(collapse_fraction) {}
  /// The next step checked becomes the reference: a run's start, its resumption, and in the
  /// node a request that changed the world (a spawned light obstacle may shorten the step).
  void rebase() { reference_ = 0; }
  /// Empty when the chosen step may be taken; otherwise what is wrong, one clause without a
  /// full stop, for the caller to place in its message. Below limits::kMinTimeStep always.
  std::string problem(const TimeStepChoice& dt);
  /// The reference step (s); 0 until the first step after a rebase.
  Real reference() const { return reference_; }

 private:
  Real fraction_;
  Real reference_ = 0;  ///< s; 0 until the first step after a rebase
};

/// A step as the runner and the node take it: the world's stable step, checked by the guard and
/// landed on the end time (stepTowards), then taken and its state checked. Between plan and take
/// the caller may act on the world with the step's length (the node's obstacle drivers). The
/// guard's reference is the run's first step, and the first after the blocks' layout changed (a
/// spawned light obstacle, also one replayed from a bag, may shorten the step for good).
struct PlannedStep {
  TimeStepChoice stable;  ///< the world's choice
  Real dt = 0;            ///< s, what take() steps: stable.dt landed on the end time
  std::string problem;    ///< not empty: the run must stop before this step (one clause)
};

/// A run's steps as the runner and the node take them (see PlannedStep).
class Stepper {
 public:
  /// collapse_fraction: StepGuard's (limits.step_collapse).
  Stepper(World& world, Real collapse_fraction) : world_(world), guard_(collapse_fraction) {}
  /// end_time: the time to land on exactly (infinite: none, the step is the stable one).
  PlannedStep plan(Time end_time = std::numeric_limits<Time>::infinity());
  /// Takes the planned step. problem: empty, or why the run must stop (the state became
  /// non-finite; one clause).
  StepInfo take(const PlannedStep& step, std::string& problem);
  /// The next planned step becomes the guard's reference (a reset in the node).
  void rebase() { guard_.rebase(); }

 private:
  World& world_;
  StepGuard guard_;
  std::uint64_t layout_ = 0;  ///< the blocks' layout version the guard's reference saw
};

}  // namespace mpm_sdem
