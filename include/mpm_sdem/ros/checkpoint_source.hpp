// Where a run continues from (mpm_sdem_run --resume, the node's ~resume): a checkpoint file, a
// folder of them, or a bag that recorded checkpoints.
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/types.hpp"
#include "mpm_sdem/core/world_command.hpp"
#include "mpm_sdem/sim/catch_up.hpp"

namespace mpm_sdem {

struct CheckpointSource {
  std::string bytes;        // the checkpoint (core/checkpoint.hpp)
  std::string description;  // for messages: "the checkpoint at t = 0.5 s in run.bag"
  std::string bag;          // the bag it came from, or "" for a file
  Real time = 0;            // s, its time
  Real asked = -1;          // s, the TIME of BAG@TIME; -1 when none was asked for
  // BAG@TIME: the bag's commands from the checkpoint's time to TIME, and where its recording
  // ends (s, its last message), for catchUpToAsked.
  std::vector<WorldCommand> commands;
  Real recorded_end = 0;
};

// spec: a checkpoint file; a folder (the latest t*.ckpt in it, or in its checkpoints/); or
// BAG[@TIME], a .bag: its last checkpoint at or before TIME s, or its last without @TIME. Throws
// std::runtime_error saying what is missing (the file, any checkpoint, one before TIME: then the
// times the bag holds).
CheckpointSource loadCheckpointSource(const std::string& spec);

// BAG@TIME: the world, restored from its checkpoint before TIME, stepped on to the last step at
// or before TIME (or the bag's end, if sooner) as the recorded run took them, under its commands
// (sim/catch_up.hpp); end_time and step_collapse: the run's (RunDef). Nothing to do for other
// sources. Throws std::runtime_error when a step fails on the way.
CatchUp catchUpToAsked(World& world, const CheckpointSource& from, Time end_time,
                       Real step_collapse);
// What the resume did, for the caller's log: "resumed from <checkpoint>", and for BAG@TIME how
// far it then stepped, with its cost.
std::string resumeDescription(const CheckpointSource& from, const CatchUp& caught_up, Time reached);
// "" when the run resumes within a step dt (s) of the time BAG@TIME asked for (or none was
// asked); else a warning that the bag's recording ends before it.
std::string resumeGapWarning(const CheckpointSource& from, Time reached, Real dt);

// The name of a checkpoint file of time t in a folder: t<seconds, 6 decimals>.ckpt, which sorts
// by time.
std::string checkpointFileName(Real t);

}  // namespace mpm_sdem
