// libFuzzer target: arbitrary text as a scene file. The parser must refuse it with a SceneError
// or accept it; an accepted scene small enough to build quickly becomes a World (which may
// refuse it with std::invalid_argument, e.g. a first step below 1e-9 s) and takes a few steps.
// Anything else (another exception, a crash, a sanitizer report) is a finding.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

[[noreturn]] void finding(const std::string& what) {
  std::fprintf(stderr, "finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > 64 * 1024) return 0;  // scene files are a few kB
  const std::string text(reinterpret_cast<const char*>(data), size);
  Scene scene;
  try {
    scene = parseScene(text, "fuzz.yaml");
  } catch (const SceneError&) {
    return 0;  // refused: the expected answer to most inputs
  } catch (const std::exception& e) {
    finding(std::string("the parser threw something other than a SceneError: ") + e.what());
  }
  // Build and step only small worlds: the fuzzer needs thousands of inputs a second.
  const WorldDef& w = scene.world;
  const Vec2 cells = (w.domain.max - w.domain.min) / w.cell_size;
  if (cells.x() * cells.y() > 2e4) return 0;
  try {
    World world(w);
    if (world.particles().size() > 5000) return 0;
    for (int k = 0; k < 3; ++k) {
      const TimeStepChoice dt = world.chooseTimeStep();
      // World promises its first step; later ones may fall (the runner then stops, exit 3).
      if (!(dt.dt >= limits::kMinTimeStep)) {
        if (k == 0) finding("World accepted a scene whose first step is below 1e-9 s");
        break;
      }
      world.step(stepTowards(dt.dt, scene.end_time, world.time()));
      if (world.time() >= scene.end_time) break;
    }
  } catch (const std::invalid_argument&) {
    return 0;  // the world refused it, with a message
  }
  return 0;
}
