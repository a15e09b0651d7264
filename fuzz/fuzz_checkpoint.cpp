// libFuzzer target: checkpoint bytes as they arrive from a damaged file or bag. The first input
// is a valid checkpoint of a small world with blocks (written here), which the fuzzer mutates.
// A finding is a crash, a sanitizer report or a hang; a refusal (CheckpointError) is the answer
// expected. What passes the CRC-32 is taken as written by mpm_sdem (docs/restart.md).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"
#include "small_world.hpp"

using namespace mpm_sdem;

namespace {

// The fuzz targets' bed with a box resting above it: blocks, IMP pairs and penalty history.
WorldDef worldWithABox() {
  WorldDef w = smallWorld(BlockContactModel::kPenalty);
  BlockDef box;
  box.name = "box";
  box.core = {Vec2(-0.01, -0.01), Vec2(0.01, -0.01), Vec2(0.01, 0.01), Vec2(-0.01, 0.01)};
  box.rounding = 0.002;
  box.position = Vec2(0.1, 0.06);
  w.blocks = {box};
  return w;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const WorldDef def = worldWithABox();
  static const std::string valid = [] {
    World w(def);
    for (int k = 0; k < 20; ++k) stepStable(w);
    return saveCheckpoint(w, "scene");
  }();
  // Half the inputs are the valid checkpoint with the input written over part of it, so that
  // the mutations reach past the magic; the others are the input as it is.
  std::string bytes(reinterpret_cast<const char*>(data), size);
  if (size > 0 && data[0] % 2 == 0) {
    bytes = valid;
    const std::size_t at = size > 1 ? (static_cast<std::size_t>(data[1]) * 997) % valid.size() : 0;
    for (std::size_t k = 2; k < size && at + k - 2 < bytes.size(); ++k)
      bytes[at + k - 2] = static_cast<char>(data[k]);
    if (size > 2 && data[0] % 4 == 0) bytes.resize(at);  // a truncated file
  }
  World w(def);
  try {
    readCheckpointHeader(bytes);
    restoreCheckpoint(w, bytes);
  } catch (const CheckpointError&) {
    return 0;
  }
  // Accepted: only the valid checkpoint itself (or an equal one) gets here; it must step.
  for (int k = 0; k < 5; ++k) stepStable(w);
  return 0;
}
