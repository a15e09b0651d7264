#include "mpm_sdem/scene/scene.hpp"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

#include "mpm_sdem/core/exclusions.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "scene_sections.hpp"
#include "yaml_reader.hpp"

namespace mpm_sdem {

namespace {

using scene::Context;
using scene::MapReader;

// An override as messages show it: a long one (a pasted file, a 100 kB value) is cut.
std::string shown(const std::string& spec) {
  return spec.size() <= 120
             ? spec
             : spec.substr(0, 120) + "... (" + std::to_string(spec.size()) + " characters)";
}

void applyOverride(YAML::Node root, const std::string& spec, Context& ctx) {
  const auto eq = spec.find('=');
  if (eq == std::string::npos || eq == 0) {
    throw SceneError("--set " + shown(spec) + ": expected key=value, e.g. --set time.end=0.5");
  }
  std::vector<std::string> parts;
  std::stringstream keys(spec.substr(0, eq));
  for (std::string part; std::getline(keys, part, '.');) parts.push_back(part);
  YAML::Node cur;
  cur.reset(root);
  std::string walked;
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const std::string& key = parts[i];
    const bool last = i + 1 == parts.size();
    YAML::Node next;
    if (cur.IsSequence()) {
      // A list element by index or by its name field.
      bool found = false;
      for (std::size_t k = 0; k < cur.size() && !found; ++k) {
        const YAML::Node el = cur[k];
        if (key == std::to_string(k) || (el.IsMap() && el["name"] && el["name"].Scalar() == key)) {
          next.reset(el);
          found = true;
        }
      }
      if (!found || last) {
        throw SceneError("--set " + shown(spec) + ": '" + walked + "' has no element '" + key +
                         "' to set a key in (use an index or a name, then a key)");
      }
    } else if (cur.IsMap() || !cur.IsDefined() || cur.IsNull()) {
      if (last) {
        YAML::Node value = YAML::Load(spec.substr(eq + 1));
        cur[key] = value;
        for (const auto& kv : cur) {
          if (kv.first.Scalar() == key) {
            ctx.addOverride(kv.first, shown(spec));
            ctx.addOverride(kv.second, shown(spec));
          }
        }
        return;
      }
      const YAML::Node& const_cur = cur;
      if (!const_cur[key]) cur[key] = YAML::Node(YAML::NodeType::Map);
      next.reset(cur[key]);
    } else {
      throw SceneError("--set " + shown(spec) + ": '" + walked + "' is a value, not a section");
    }
    walked += (walked.empty() ? "" : ".") + key;
    cur.reset(next);
  }
}

// The node a dotted key names, or the deepest of its sections the file has: a key left at its
// default names no line, so its section's line (or the file's first) is given.
YAML::Node deepestNode(const YAML::Node& root, const std::string& key) {
  YAML::Node at;
  at.reset(root);
  std::size_t from = 0;
  while (from < key.size()) {
    const std::size_t dot = key.find('.', from);
    const std::string part = key.substr(from, dot == std::string::npos ? dot : dot - from);
    const YAML::Node& here = at;
    if (!here.IsMap() || !here[part]) break;
    at.reset(here[part]);
    if (dot == std::string::npos) break;
    from = dot + 1;
  }
  return at;
}

Scene parseTree(const YAML::Node& root, const Context& ctx, const std::string& source) {
  Scene s;
  s.source = source;
  MapReader top(
      ctx, root, "",
      {"name", "description", "domain", "grid", "solver", "time", "materials", "bodies", "output",
       "limits", "blocks", "block_contact", "coupling", "fem_bodies", "sph", "view"});
  s.name = top.has("name") ? top.name("name") : "";
  s.description = top.text("description", "");
  top.require(s.description.size() <= 4096, "description",
              "must be at most 4096 characters, got " + std::to_string(s.description.size()));
  parseDomain(ctx, top, s);
  parseGrid(ctx, top, s);
  parseSolver(ctx, top, s);
  parseTime(ctx, top, s);

  const std::map<std::string, int> materials = parseMaterials(ctx, top, s);
  parseBodies(ctx, top, s, materials);
  parseBlocks(ctx, top, s);
  parseFemBodies(ctx, top, s);
  parseSph(ctx, top, s);
  if (const Problem p = periodicProblem(s.world); !p.empty())
    ctx.fail(top.node("domain")["walls"], p.key, p.message);
  // What may not be combined: the core's one table, asked once every section is read.
  if (const Problem p = combinationProblem(s.world); !p.empty())
    ctx.fail(deepestNode(root, p.key), p.key, p.message);

  parseOutput(ctx, top, s);
  parseView(ctx, top, s);
  parseLimits(ctx, top, s);
  return s;
}

}  // namespace

namespace {

// Scene::state_text of a parsed tree.
std::string stateText(const YAML::Node& root) {
  YAML::Node state = YAML::Clone(root);
  for (const char* key : {"name", "description", "output", "limits", "view"}) state.remove(key);
  if (state["time"] && state["time"].IsMap()) state["time"].remove("end");
  YAML::Emitter out;
  out << state;
  return out.c_str();
}

}  // namespace

Scene parseScene(const std::string& yaml_text, const std::string& source_name,
                 const std::vector<std::string>& overrides) {
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw SceneError(source_name + ":" + std::to_string(e.mark.line + 1) + ":" +
                     std::to_string(e.mark.column + 1) + ": not valid YAML: " + e.msg);
  }
  Context ctx(source_name);
  if (!root.IsMap())
    throw SceneError(source_name + ": expected a map of sections (domain, grid, ...)");
  for (const std::string& o : overrides) {
    try {
      applyOverride(root, o, ctx);
    } catch (const YAML::Exception& e) {
      throw SceneError("--set " + shown(o) + ": the value is not valid YAML: " + e.msg);
    }
  }
  Scene s = parseTree(root, ctx, source_name);
  s.state_text = stateText(root);
  return s;
}

Scene loadScene(const std::string& path, const std::vector<std::string>& overrides) {
  // Only a regular file of bounded size: a FIFO would block for ever, /dev/zero never end.
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (error || !std::filesystem::exists(status)) throw SceneError(path + ": no such scene file");
  if (!std::filesystem::is_regular_file(status))
    throw SceneError(path + ": not a regular file (a scene is a YAML file)");
  const auto bytes = std::filesystem::file_size(path, error);
  if (error || bytes > limits::kMaxSceneBytes)
    throw SceneError(path + ": " + std::to_string(bytes) + " bytes, more than a scene file's " +
                     std::to_string(limits::kMaxSceneBytes) + "; is this the scene?");
  std::ifstream in(path);
  if (!in) throw SceneError(path + ": cannot open the scene file");
  std::stringstream text;
  text << in.rdbuf();
  return parseScene(text.str(), path, overrides);
}

}  // namespace mpm_sdem
