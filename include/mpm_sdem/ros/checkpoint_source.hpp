// Where a run continues from (mpm_sdem_run --resume, the node's ~resume): a checkpoint file, a
// folder of them, or a bag that recorded checkpoints.
#pragma once

#include <string>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

struct CheckpointSource {
  std::string bytes;        // the checkpoint (core/checkpoint.hpp)
  std::string description;  // for messages: "the checkpoint at t = 0.5 s in run.bag"
  std::string bag;          // the bag it came from, or "" for a file
  Real time = 0;            // s, its time
  Real asked = -1;          // s, the TIME of BAG@TIME; -1 when none was asked for
  Real spacing = 0;         // s between the bag's checkpoints around it; 0 when it holds one
};

// spec: a checkpoint file; a folder (the latest t*.ckpt in it, or in its checkpoints/); or
// BAG[@TIME], a .bag: its last checkpoint at or before TIME s, or its last without @TIME. Throws
// std::runtime_error saying what is missing (the file, any checkpoint, one before TIME: then the
// times the bag holds).
CheckpointSource loadCheckpointSource(const std::string& spec);

// "" when the run resumes within a step dt (s) of the time BAG@TIME asked for (or none was
// asked); else a warning saying how far before it, how far apart the bag's checkpoints are, and
// the checkpoint rate to record with to resume nearer.
std::string resumeGapWarning(const CheckpointSource& from, Real dt);

// The name of a checkpoint file of time t in a folder: t<seconds, 6 decimals>.ckpt, which sorts
// by time.
std::string checkpointFileName(Real t);

}  // namespace mpm_sdem
