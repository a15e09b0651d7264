// Scene files: YAML in, core definitions out. Parsing is strict (unknown keys, missing keys,
// wrong types and non-physical values are errors naming the key, the line and a valid value);
// see docs/scene_reference.md. No YAML type appears in this header.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/render/view.hpp"

namespace mpm_sdem {

struct OutputDef {
  Real interval = 0;              // s between time-series rows; 0 means end / 100
  bool particles = true;          // write the final particle states
  std::vector<MassGauge> gauges;  // a <name>_mass column of the time series each
};

struct LimitsDef {
  // Stop when the total energy exceeds its initial value by this fraction of it.
  Real energy_growth = 0.5;
  // Stop when the stable step falls below this fraction of the run's first step (StepGuard).
  Real step_collapse = 1e-3;
};

struct Scene {
  std::string name;
  std::string description;
  std::string source;  // file the scene was read from
  WorldDef world;
  Real end_time = 0;  // s
  OutputDef output;
  LimitsDef limits;
  // The quantity and colour scale of the node's pictures and videos (the section `view`); the
  // node's ~image parameters win over it (render::chooseScale).
  render::ViewRequest view;
  // The settings that shape the simulated state, as canonical YAML: the tree after the
  // overrides without name, description, time.end, output, limits and view (a resumed run may
  // go further, or write other outputs). A checkpoint records it; a resume compares it.
  std::string state_text;
};

// One message, already formatted as "file:line:column: key: problem; fix".
class SceneError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// overrides: "dotted.key=value" strings applied to the YAML tree before validation; a sequence
// element is addressed by index or by its name, e.g. "materials.sand.density=1500".
Scene loadScene(const std::string& path, const std::vector<std::string>& overrides = {});
Scene parseScene(const std::string& yaml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides = {});

// Where two state texts (Scene::state_text) differ, one line per setting: "key: value in the
// checkpoint, value here", keys dotted with names for named list items (materials.sand.density).
// At most max lines, then how many more; empty when they are equal.
std::vector<std::string> sceneDifferences(const std::string& checkpoint, const std::string& here,
                                          std::size_t max = 8);
// A run of this scene continued from a checkpoint (its bytes; from: where they came from, for
// messages): restored into world, built from the scene, when the checkpoint was written by
// this build for these settings. Throws CheckpointError otherwise, "cannot continue from
// <from>: " and what differs, the build (buildDifference) or the scene's settings
// (sceneDifferences), and what to do; or restoreCheckpoint's error.
void resumeWorld(World& world, const Scene& scene, const std::string& bytes,
                 const std::string& from);

}  // namespace mpm_sdem
