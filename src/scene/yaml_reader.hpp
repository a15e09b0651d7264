// Strict, line-aware reading of YAML maps for the scene parser. Internal to the scene library.
#pragma once

#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include <yaml-cpp/yaml.h>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::scene {

// Where a value came from: the file (with line and column) or a --set override.
class Context {
 public:
  explicit Context(std::string file) : file_(std::move(file)) {}
  void addOverride(const YAML::Node& node, const std::string& spec) {
    overrides_.emplace_back(node, spec);
  }
  [[noreturn]] void fail(const YAML::Node& at, const std::string& key,
                         const std::string& what) const;

 private:
  std::string where(const YAML::Node& at) const;
  std::string file_;
  std::vector<std::pair<YAML::Node, std::string>> overrides_;
};

// Reads one YAML map whose keys must all be among `keys`; an unknown key (a typo, most often) is
// refused on construction, before any complaint about a missing one.
class MapReader {
 public:
  MapReader(const Context& ctx, const YAML::Node& node, std::string path,
            const std::vector<const char*>& keys);

  bool has(const char* key) const;
  YAML::Node node(const char* key) const;  // required
  const YAML::Node& self() const { return node_; }
  std::string path(const char* key) const;

  Real number(const char* key, const char* unit) const;
  Real number(const char* key, const char* unit, Real fallback) const;
  // A number that must lie in a range of limits.hpp (its unit too), refused at its line.
  Real number(const char* key, const limits::Range& range) const;
  Real number(const char* key, const limits::Range& range, Real fallback) const;
  // A name (limits::nameProblem).
  std::string name(const char* key) const;
  int integer(const char* key, int fallback) const;
  bool boolean(const char* key, bool fallback) const;
  std::string text(const char* key) const;
  std::string text(const char* key, const std::string& fallback) const;
  Vec2 vec2(const char* key, const char* unit) const;
  Vec2 vec2(const char* key, const char* unit, const Vec2& fallback) const;
  // A pair whose both components lie in the range.
  Vec2 vec2(const char* key, const limits::Range& range) const;

  // Interprets a scalar as one of the listed names.
  template <class E>
  E choice(const char* key, const std::vector<std::pair<const char*, E>>& options,
           E fallback) const {
    if (!has(key)) return fallback;
    return choiceOf(node(key), path(key), options);
  }
  template <class E>
  E choiceOf(const YAML::Node& n, const std::string& key_path,
             const std::vector<std::pair<const char*, E>>& options) const {
    std::string valid;
    if (n.IsScalar()) {
      for (const auto& o : options) {
        if (n.Scalar() == o.first) return o.second;
      }
    }
    for (const auto& o : options) valid += std::string(valid.empty() ? "" : " | ") + o.first;
    ctx_.fail(n, key_path, "'" + describe(n) + "' is not valid; use one of: " + valid);
  }

  // Fails on a value that is out of range, at that key's line.
  void require(bool ok, const char* key, const std::string& what) const;
  // Fails when p is not empty, at that key's line, with p's message after prefix.
  void require(const char* key, const Problem& p, const std::string& prefix = "") const;

  static std::string describe(const YAML::Node& n);
  static Real toNumber(const Context& ctx, const YAML::Node& n, const std::string& key_path,
                       const char* unit);
  static Vec2 toVec2(const Context& ctx, const YAML::Node& n, const std::string& key_path,
                     const char* unit);

 private:
  const Context& ctx_;
  YAML::Node node_;
  std::string path_;
};

}  // namespace mpm_sdem::scene
