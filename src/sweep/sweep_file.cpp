#include "sweep_file.hpp"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "mpm_sdem/scene/scene.hpp"
#include "scene/yaml_reader.hpp"

namespace mpm_sdem::sweep {

namespace fs = std::filesystem;
using scene::Context;
using scene::MapReader;

namespace {

// A value as --set takes it: YAML on one line.
std::string flow(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e << YAML::Flow << n;
  return e.c_str();
}

// Named measurements of the validation cases, as a file and a column.
struct Named {
  const char* name;
  const char* file;
  const char* column;
  const char* reduce;
  bool needs_block;
};
constexpr Named kNamed[] = {
    {"block_left_face", "blocks.csv", "min_x", "", true},  // the wooden blocks' measure
    {"block_right_face", "blocks.csv", "max_x", "", true},
    {"block_bottom", "blocks.csv", "min_y", "", true},
    {"block_top", "blocks.csv", "max_y", "", true},
    {"block_angle", "blocks.csv", "angle", "", true},
    {"flow_front", "particles.csv", "x", "max", false},  // the furthest point
    {"kinetic_energy", "timeseries.csv", "kinetic_energy", "", false},
    {"steps", "summary.csv", "steps", "", false},
    {"wall_s", "summary.csv", "wall_s", "", false},
};

Output readOutput(const Context& ctx, const std::string& name, const YAML::Node& node) {
  const std::string path = "outputs." + name;
  MapReader r(ctx, node, path,
              {"measure", "file", "column", "block", "at", "reduce", "rate_between", "reference"});
  Output o;
  o.name = name;
  if (r.has("measure")) {
    r.require(!r.has("file") && !r.has("column") && !r.has("reduce"), "measure",
              "give either measure or file and column, not both");
    const std::string m = r.text("measure");
    const Named* found = nullptr;
    std::string valid;
    for (const Named& n : kNamed) {
      if (m == n.name) found = &n;
      valid += std::string(valid.empty() ? "" : " | ") + n.name;
    }
    r.require(found != nullptr, "measure",
              "'" + m + "' is not a measurement; use one of: " + valid);
    o.file = found->file;
    o.column = found->column;
    o.reduce = found->reduce;
    r.require(!found->needs_block || r.has("block"), "measure",
              "'" + m + "' needs block: the block's name");
  } else {
    o.file = r.choice<std::string>("file",
                                   {{"timeseries.csv", "timeseries.csv"},
                                    {"blocks.csv", "blocks.csv"},
                                    {"particles.csv", "particles.csv"},
                                    {"summary.csv", "summary.csv"}},
                                   "");
    r.require(!o.file.empty(), "file", "missing: which output file (or give measure)");
    o.column = r.text("column");
    if (r.has("reduce"))
      o.reduce = r.choice<std::string>(
          "reduce", {{"max", "max"}, {"min", "min"}, {"mean", "mean"}, {"sum", "sum"}}, "");
  }
  o.block = r.text("block", "");
  r.require(o.block.empty() || o.file == "blocks.csv", "block", "only blocks.csv has blocks");
  r.require(!o.block.empty() || o.file != "blocks.csv", "column",
            "blocks.csv has a row per block: give block, the block's name");
  r.require(o.reduce.empty() == (o.file != "particles.csv"), "column",
            o.file == "particles.csv" ? "particles.csv has a row per point: give reduce "
                                        "(max | min | mean | sum)"
                                      : "reduce applies to particles.csv only");
  if (r.has("at")) {
    const YAML::Node at = r.node("at");
    if (at.IsScalar() && at.Scalar() == "end") {
      o.at = -1;
    } else {
      o.at = r.number("at", "s");
      r.require(o.at >= 0, "at", "a time >= 0 s, or end");
      r.require(o.file == "timeseries.csv" || o.file == "blocks.csv", "at",
                "only timeseries.csv and blocks.csv have rows in time");
    }
  }
  if (r.has("rate_between")) {
    r.require(o.file == "timeseries.csv" && !r.has("at"), "rate_between",
              "a slope over timeseries.csv rows; not with at");
    const YAML::Node b = r.node("rate_between");
    if (!b.IsSequence() || b.size() != 2)
      ctx.fail(b, path + ".rate_between", "expected [low, high]: the values between which");
    const double lo = MapReader::toNumber(ctx, b[0], path + ".rate_between", "(the column's)");
    const double hi = MapReader::toNumber(ctx, b[1], path + ".rate_between", "(the column's)");
    r.require(lo < hi, "rate_between", "low must be below high");
    o.rate_between = std::make_pair(lo, hi);
  }
  if (r.has("reference")) {
    const YAML::Node ref = r.node("reference");
    if (ref.IsSequence()) {
      for (const auto& v : ref)
        o.reference.push_back(MapReader::toNumber(ctx, v, path + ".reference", "(the output's)"));
    } else {
      o.reference.push_back(r.number("reference", "(the output's unit)"));
    }
    for (double v : o.reference)
      r.require(v != 0, "reference",
                "must not be 0 (the error is relative); compare with a small scale instead");
  }
  return o;
}

}  // namespace

SweepDef loadSweep(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw SweepError(path + ": no such sweep file");
  if (fs::file_size(path, ec) > (1u << 20))
    throw SweepError(path + ": more than 1 MiB; is this a sweep file?");
  SweepDef s;
  s.source = path;
  Context ctx(path);
  try {
    YAML::Node root;
    try {
      root = YAML::LoadFile(path);
    } catch (const YAML::ParserException& e) {
      throw SweepError(path + ":" + std::to_string(e.mark.line + 1) + ":" +
                       std::to_string(e.mark.column + 1) + ": not valid YAML: " + e.msg);
    }
    MapReader top(ctx, root, "",
                  {"name", "description", "scene", "set", "parameters", "combine", "ensemble",
                   "outputs", "validation"});
    s.name = top.name("name");
    if (top.has("validation")) {
      // The report's cases, one run each: nothing of a scene's sweep applies.
      for (const char* key : {"scene", "set", "parameters", "combine", "ensemble", "outputs"})
        top.require(!top.has(key), key,
                    "a validation sweep runs mpm_sdem_validate's cases; remove " +
                        std::string(key) + " (or validation, for a scene's sweep)");
      MapReader v(ctx, top.node("validation"), "validation", {"fast", "cases"});
      ValidationCases cases;
      cases.fast = v.boolean("fast", false);
      const YAML::Node list = v.node("cases");
      if (!list.IsSequence() || list.size() == 0)
        ctx.fail(list, "validation.cases",
                 "expected a list of case names (mpm_sdem_validate --list prints them)");
      for (const auto& c : list) {
        // A case, or one run of a case split into runs: name.N (mpm_sdem_validate --list --runs).
        const std::string name = c.Scalar();
        const std::size_t dot = name.find('.');
        const std::string base = name.substr(0, dot);
        if (base.empty() ||
            base.find_first_not_of("abcdefghijklmnopqrstuvwxyz0123456789_") != std::string::npos ||
            (dot != std::string::npos &&
             (dot + 1 == name.size() ||
              name.find_first_not_of("0123456789", dot + 1) != std::string::npos)))
          ctx.fail(c, "validation.cases",
                   "'" + name + "' is not a case name (a-z, 0-9, _) or one of its runs (name.N)");
        if (std::find(cases.cases.begin(), cases.cases.end(), name) != cases.cases.end())
          ctx.fail(c, "validation.cases", "'" + name + "' is listed twice");
        cases.cases.push_back(name);
      }
      s.validation = std::move(cases);
      return s;
    }
    // The scene relative to the sweep file, so that a sweep and its scene travel together.
    fs::path scene = top.text("scene");
    if (scene.is_relative()) scene = fs::absolute(fs::path(path).parent_path() / scene);
    s.scene = scene.lexically_normal().string();
    top.require(fs::is_regular_file(s.scene, ec), "scene",
                "no such scene file: " + s.scene + " (relative to the sweep file)");
    auto keyValues = [&](const char* section, auto&& f) {
      if (!top.has(section)) return;
      const YAML::Node n = top.node(section);
      if (!n.IsMap()) ctx.fail(n, section, "expected a map of scene keys (time.end: 0.5, ...)");
      for (const auto& kv : n) f(kv.first.Scalar(), kv.second);
    };
    keyValues("set", [&](const std::string& key, const YAML::Node& v) {
      s.fixed.push_back(key + "=" + flow(v));
    });
    auto values = [&](const std::string& key, const YAML::Node& v) {
      if (!v.IsSequence() || v.size() == 0)
        ctx.fail(v, "parameters." + key, "expected a list of values, e.g. [0.01, 0.005]");
      std::vector<std::string> out;
      for (const auto& value : v) out.push_back(flow(value));
      return out;
    };
    keyValues("parameters", [&](const std::string& key, const YAML::Node& v) {
      Parameter p;
      if (v.IsMap()) {  // a group: its keys' k-th values together
        for (const auto& kv : v) {
          const std::string inner = kv.first.Scalar();
          const std::vector<std::string> list = values(key + "." + inner, kv.second);
          if (!p.values.empty() && list.size() != p.values.size())
            ctx.fail(kv.second, "parameters." + key + "." + inner,
                     "a group's keys take their k-th values together: " +
                         std::to_string(list.size()) + " values here, " +
                         std::to_string(p.values.size()) + " for '" + p.keys.front() + "'");
          p.values.resize(list.size());
          for (std::size_t k = 0; k < list.size(); ++k) p.values[k].push_back(list[k]);
          p.keys.push_back(inner);
        }
      } else {
        p.keys.push_back(key);
        for (const std::string& value : values(key, v)) p.values.push_back({value});
      }
      s.parameters.push_back(std::move(p));
    });
    s.zip = top.choice<bool>("combine", {{"grid", false}, {"zip", true}}, false);
    if (s.zip) {
      for (const Parameter& p : s.parameters)
        top.require(p.values.size() == s.parameters.front().values.size(), "combine",
                    "zip takes the k-th value of each parameter: '" + p.keys.front() + "' has " +
                        std::to_string(p.values.size()) + " values, '" +
                        s.parameters.front().keys.front() + "' " +
                        std::to_string(s.parameters.front().values.size()));
    }
    if (top.has("ensemble")) {
      MapReader e(ctx, top.node("ensemble"), "ensemble",
                  {"members", "perturbation", "perturbation_cells", "seed"});
      s.ensemble.members = e.integer("members", 1);
      e.require(s.ensemble.members >= 1 && s.ensemble.members <= 10000, "members",
                "1 to 10000 runs per setting");
      e.require(!(e.has("perturbation") && e.has("perturbation_cells")), "perturbation",
                "give perturbation (m) or perturbation_cells (cells of each setting's grid)");
      s.ensemble.in_cells = e.has("perturbation_cells");
      const char* key = s.ensemble.in_cells ? "perturbation_cells" : "perturbation";
      s.ensemble.perturbation = e.number(key, s.ensemble.in_cells ? "cells" : "m", 0);
      e.require(s.ensemble.perturbation >= 0 && s.ensemble.perturbation <= 0.5, key,
                "in [0, 0.5] (points moved by up to this along x and y)");
      e.require(s.ensemble.members == 1 || s.ensemble.perturbation > 0, key,
                "members of an ensemble differ only by it: give a perturbation > 0");
      const int seed = e.integer("seed", 1);
      e.require(seed >= 0, "seed", "a whole number >= 0");
      s.ensemble.seed = static_cast<unsigned>(seed);
    }
    const YAML::Node outputs = top.node("outputs");
    if (!outputs.IsMap() || outputs.size() == 0)
      ctx.fail(outputs, "outputs", "expected a map of named outputs (block2_left: {...})");
    for (const auto& kv : outputs) {
      const std::string name = kv.first.Scalar();
      if (name.empty() || name.find_first_of(", \"'\n") != std::string::npos)
        ctx.fail(kv.first, "outputs." + name,
                 "an output's name is a column of results.csv: no comma, space or quote");
      s.outputs.push_back(readOutput(ctx, name, kv.second));
    }
  } catch (const SceneError& e) {
    throw SweepError(e.what());
  } catch (const YAML::Exception& e) {
    throw SweepError(path + ": " + e.what());
  }
  long settings = 1;
  for (const Parameter& p : s.parameters)
    settings =
        s.zip ? static_cast<long>(p.values.size()) : settings * static_cast<long>(p.values.size());
  for (const Output& o : s.outputs)
    if (o.reference.size() > 1 && static_cast<long>(o.reference.size()) != settings)
      throw SweepError(path + ": outputs." + o.name +
                       ".reference: " + std::to_string(o.reference.size()) + " values for " +
                       std::to_string(settings) + " settings; give one, or one per setting");
  if (settings * s.ensemble.members > 100000)
    throw SweepError(path + ": " + std::to_string(settings * s.ensemble.members) +
                     " runs; a sweep holds at most 100000");
  // Every setting's scene, now: a refused value is named with its setting.
  for (const Run& r : expandRuns(s)) {
    if (r.member != 0) continue;
    try {
      const Scene scene = loadScene(s.scene, r.overrides);
      if (s.ensemble.in_cells) s.cell_sizes.push_back(scene.world.cell_size);
    } catch (const SceneError& e) {
      throw SweepError(path + ": setting " + std::to_string(r.setting) + " (run " + r.id +
                       "): " + e.what());
    }
  }
  return s;
}

std::vector<std::string> parameterKeys(const SweepDef& s) {
  std::vector<std::string> keys;
  for (const Parameter& p : s.parameters) keys.insert(keys.end(), p.keys.begin(), p.keys.end());
  return keys;
}

std::vector<Run> expandRuns(const SweepDef& s) {
  if (s.validation) {
    std::vector<Run> runs;
    for (const std::string& name : s.validation->cases) {
      Run r;
      r.id = r.validation_case = name;
      r.setting = static_cast<int>(runs.size());
      runs.push_back(std::move(r));
    }
    return runs;
  }
  // settings[k]: the values of every parameter key at setting k, in the order of keys().
  std::vector<std::vector<std::string>> settings(1);
  auto append = [](std::vector<std::string>& to, const std::vector<std::string>& values) {
    to.insert(to.end(), values.begin(), values.end());
  };
  if (s.zip && !s.parameters.empty()) {
    settings.assign(s.parameters.front().values.size(), {});
    for (const Parameter& p : s.parameters)
      for (std::size_t k = 0; k < p.values.size(); ++k) append(settings[k], p.values[k]);
  } else {
    // Every combination, the last parameter varying fastest.
    for (const Parameter& p : s.parameters) {
      std::vector<std::vector<std::string>> next;
      for (const auto& partial : settings) {
        for (const std::vector<std::string>& v : p.values) {
          next.push_back(partial);
          append(next.back(), v);
        }
      }
      settings.swap(next);
    }
  }
  const std::vector<std::string> keys = parameterKeys(s);
  std::vector<Run> runs;
  for (std::size_t k = 0; k < settings.size(); ++k) {
    for (int m = 0; m < s.ensemble.members; ++m) {
      Run r;
      r.setting = static_cast<int>(k);
      r.member = m;
      r.seed = s.ensemble.seed + static_cast<unsigned>(m);
      char id[48];
      std::snprintf(id, sizeof id, "s%03zu_m%02d", k, m);
      r.id = id;
      r.values = settings[k];
      r.perturbation = s.ensemble.perturbation;
      if (s.ensemble.in_cells && k < s.cell_sizes.size()) r.perturbation *= s.cell_sizes[k];
      r.overrides = s.fixed;
      for (std::size_t i = 0; i < keys.size(); ++i)
        r.overrides.push_back(keys[i] + "=" + settings[k][i]);
      runs.push_back(std::move(r));
    }
  }
  return runs;
}

}  // namespace mpm_sdem::sweep
