/// \file
/// Checkpoints: a world's whole state as bytes, restored bit for bit into a world built from the
/// same scene by the same build, so that a run continued from a checkpoint computes exactly what
/// the uninterrupted run computes.
///
/// What is kept: every member that outlives a step (each class lists them in its stateIo), the
/// blocks added and removed while running, the material points, the SPH and FEM state, the
/// coupling's contact histories and pair lists, the last binning. What is not: scratch that every
/// step rebuilds (the grid, search buckets). The bytes are
///   "MPMSDEMC", format version (uint32), body length (uint64), CRC-32 of the body (uint32), body
/// with the body a cereal binary archive: the header fields below, then the state.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

/// A checkpoint that cannot be used, with the reason: damaged (length, checksum, format), written
/// by another build, or not fitting this world.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// What a checkpoint says about itself, read without restoring it.
struct CheckpointHeader {
  std::string build;       ///< buildId() of the program that wrote it
  std::string scene_hash;  ///< sceneHash(scene)
  std::string scene;       ///< the text the writer gave for its scene (saveCheckpoint)
  Real time = 0;           ///< s
  long steps = 0;          ///< steps taken when it was written
  std::size_t bytes = 0;   ///< of the whole checkpoint
};

/// This build: "physics sources <hash>; compiler <id version>; flags <...>; isa <...>", the hash
/// over the core, scene and mesh sources. Equal ids compute equal bits.
const std::string& buildId();
/// The parts in which two build ids differ, e.g. "physics sources (3f2a... there, 91c0... here)";
/// empty when they are equal.
std::string buildDifference(const std::string& theirs, const std::string& ours);
/// Hex CRC-32 of a scene's text: what the header records and a resume compares first.
std::string sceneHash(const std::string& scene);

/// The world's state now. scene: the text the caller builds the world from (the scene layer's
/// canonical text), kept so that a resume can compare and name what differs.
/// With Box2D's own block contacts (BlockContactModel::kBox2D), the blocks' Box2D world is then
/// rebuilt from the saved state, as a restore builds it: Box2D keeps contact caches (warm-start
/// impulses, contact order) that its API cannot set, so both runs drop them at the checkpoint.
/// A run writing checkpoints then differs from one that does not, by one cold start of Box2D's
/// contact solver per checkpoint; the penalty model's blocks are restored exactly and untouched.
std::string saveCheckpoint(World& world, const std::string& scene);
/// Checks the container (magic, format, length, checksum) and reads the header. Throws
/// CheckpointError naming what is wrong.
CheckpointHeader readCheckpointHeader(const std::string& bytes);
/// Puts the saved state into world, which must have been built from the definitions the
/// checkpoint was written from (the caller compares the scene text). Throws CheckpointError for a
/// damaged checkpoint, another build, or state that does not fit the world; the world must then
/// not be used.
void restoreCheckpoint(World& world, const std::string& bytes);

}  // namespace mpm_sdem
