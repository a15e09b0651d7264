// Whether a checkpoint can continue a run of a scene (the runner's and the node's --resume): the
// same build, and the same settings that shape the simulated state, or the differences named
// key by key.
#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/scene/scene.hpp"

namespace mpm_sdem {

namespace {

// A node as one line of YAML, for messages.
std::string flow(const YAML::Node& n) {
  if (!n.IsDefined() || n.IsNull()) return "(absent)";
  YAML::Emitter out;
  out << YAML::Flow << n;
  return out.c_str();
}

// List items are named by their name key when they have one (materials.sand).
std::string itemKey(const YAML::Node& item, std::size_t i) {
  if (item.IsMap() && item["name"] && item["name"].IsScalar()) return item["name"].Scalar();
  return std::to_string(i);
}

void differences(const YAML::Node& a, const YAML::Node& b, const std::string& key,
                 std::vector<std::string>& out) {
  const std::string prefix = key.empty() ? "" : key + ".";
  if (a.IsMap() && b.IsMap()) {
    std::vector<std::string> keys;
    for (const auto& kv : a) keys.push_back(kv.first.Scalar());
    for (const auto& kv : b)
      if (!a[kv.first.Scalar()]) keys.push_back(kv.first.Scalar());
    for (const std::string& k : keys) differences(a[k], b[k], prefix + k, out);
  } else if (a.IsSequence() && b.IsSequence() && a.size() == b.size()) {
    for (std::size_t i = 0; i < a.size(); ++i)
      differences(a[i], b[i], prefix + itemKey(b[i], i), out);
  } else if (flow(a) != flow(b)) {
    out.push_back((key.empty() ? "the scene" : key) + ": " + flow(a) + " in the checkpoint, " +
                  flow(b) + " here");
  }
}

}  // namespace

std::vector<std::string> sceneDifferences(const std::string& checkpoint, const std::string& here,
                                          std::size_t max) {
  if (checkpoint == here) return {};
  std::vector<std::string> out;
  try {
    differences(YAML::Load(checkpoint), YAML::Load(here), "", out);
  } catch (const YAML::Exception&) {
    out = {"the scene: the checkpoint's text is not a scene"};
  }
  if (out.empty()) out.push_back("the scene: the same settings, written differently");
  if (out.size() > max) {
    const std::size_t more = out.size() - max;
    out.resize(max);
    out.push_back("and " + std::to_string(more) + " more");
  }
  return out;
}

namespace {

// Why a checkpoint cannot continue a run of this scene: empty, or the message.
Problem resumeProblem(const Scene& scene, const CheckpointHeader& h) {
  if (h.build != buildId())
    return "it was written by another build of mpm_sdem: " + buildDifference(h.build, buildId()) +
           ". Continue it with the build that wrote it, or start the run again";
  if (h.scene_hash == sceneHash(scene.state_text) && h.scene == scene.state_text) return {};
  std::string why = "it was written for other scene settings (hash " + h.scene_hash + ", here " +
                    sceneHash(scene.state_text) + "):";
  for (const std::string& d : sceneDifferences(h.scene, scene.state_text)) why += "\n  " + d;
  return why +
         "\nResume with the scene file and --set values it was written with (time.end, output, "
         "limits and view may change)";
}

}  // namespace

void resumeWorld(World& world, const Scene& scene, const std::string& bytes,
                 const std::string& from) {
  if (const Problem p = resumeProblem(scene, readCheckpointHeader(bytes)); !p.empty())
    throw CheckpointError("cannot continue from " + from + ": " + p.message);
  restoreCheckpoint(world, bytes);
}

}  // namespace mpm_sdem
