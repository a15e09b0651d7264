#include "yaml_reader.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "mpm_sdem/scene/scene.hpp"

namespace mpm_sdem::scene {

namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] != b[j - 1])});
      diag = up;
    }
  }
  return row[b.size()];
}

// True when `at` is the value an override set or lies anywhere inside it (a key or a value of
// a map or list given on the command line, however deep).
bool isOverride(const YAML::Node& at, const YAML::Node& set) {
  if (at.is(set)) return true;
  if (set.IsMap()) {
    for (const auto& child : set) {
      if (at.is(child.first) || isOverride(at, child.second)) return true;
    }
  } else if (set.IsSequence()) {
    for (const auto& child : set) {
      if (isOverride(at, child)) return true;
    }
  }
  return false;
}

}  // namespace

std::string Context::where(const YAML::Node& at) const {
  for (const auto& o : overrides_) {
    if (at.IsDefined() && isOverride(at, o.first)) return file_ + " (--set " + o.second + ")";
  }
  if (!at.IsDefined()) return file_;
  const YAML::Mark m = at.Mark();
  if (m.line < 0) return file_;
  return file_ + ":" + std::to_string(m.line + 1) + ":" + std::to_string(m.column + 1);
}

void Context::fail(const YAML::Node& at, const std::string& key, const std::string& what) const {
  throw SceneError(where(at) + ": " + key + ": " + what);
}

MapReader::MapReader(const Context& ctx, const YAML::Node& node, std::string path,
                     const std::vector<const char*>& keys)
    : ctx_(ctx), node_(node), path_(std::move(path)) {
  if (!node_.IsMap()) {
    ctx_.fail(node_, path_.empty() ? "(top level)" : path_,
              "expected a map of keys, got '" + describe(node_) + "'");
  }
  for (const auto& kv : node_) {
    const std::string key = kv.first.Scalar();
    std::string best, valid;
    std::size_t best_d = 3;  // suggest only close spellings
    bool known = false;
    for (const char* k : keys) {
      known = known || key == k;
      const std::size_t d = editDistance(key, k);
      if (d < best_d) {
        best_d = d;
        best = k;
      }
      valid += (valid.empty() ? "" : ", ") + std::string(k);
    }
    if (known) continue;
    ctx_.fail(kv.first, this->path(describe(kv.first).c_str()),
              "unknown key" + (best.empty() ? std::string(".") : "; did you mean '" + best + "'?") +
                  " Valid keys here: " + valid);
  }
}

std::string MapReader::path(const char* key) const {
  return path_.empty() ? std::string(key) : path_ + "." + key;
}

bool MapReader::has(const char* key) const {
  const YAML::Node n = node_[key];
  return n.IsDefined() && !n.IsNull();
}

YAML::Node MapReader::node(const char* key) const {
  if (!has(key))
    ctx_.fail(node_, path_.empty() ? "(top level)" : path_,
              std::string("missing required key '") + key + "'");
  return node_[key];
}

std::string MapReader::describe(const YAML::Node& n) {
  // Cut: a message must not echo a 100 kB value back.
  if (n.IsScalar()) return n.Scalar().size() <= 80 ? n.Scalar() : n.Scalar().substr(0, 80) + "...";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a map";
  return "nothing";
}

Real MapReader::toNumber(const Context& ctx, const YAML::Node& n, const std::string& key_path,
                         const char* unit) {
  double v = 0;
  if (!n.IsScalar() || !YAML::convert<double>::decode(n, v) || !std::isfinite(v)) {
    ctx.fail(n, key_path,
             "expected a finite number in " + std::string(unit) + ", got '" + describe(n) + "'");
  }
  return v;
}

Vec2 MapReader::toVec2(const Context& ctx, const YAML::Node& n, const std::string& key_path,
                       const char* unit) {
  if (!n.IsSequence() || n.size() != 2) {
    ctx.fail(n, key_path,
             "expected a pair [x, y] in " + std::string(unit) + ", got '" + describe(n) + "'");
  }
  return Vec2(toNumber(ctx, n[0], key_path + "[0]", unit),
              toNumber(ctx, n[1], key_path + "[1]", unit));
}

Real MapReader::number(const char* key, const char* unit) const {
  return toNumber(ctx_, node(key), path(key), unit);
}
Real MapReader::number(const char* key, const char* unit, Real fallback) const {
  return has(key) ? number(key, unit) : fallback;
}

Real MapReader::number(const char* key, const limits::Range& range) const {
  const Real v = number(key, *range.unit ? range.unit : "(dimensionless)");
  require(key, limits::rangeProblem(v, range));
  return v;
}
Real MapReader::number(const char* key, const limits::Range& range, Real fallback) const {
  return has(key) ? number(key, range) : fallback;
}

std::string MapReader::name(const char* key) const {
  const std::string n = text(key);
  require(key, limits::nameProblem(n));
  return n;
}

int MapReader::integer(const char* key, int fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = node(key);
  int v = 0;
  if (!n.IsScalar() || !YAML::convert<int>::decode(n, v)) {
    ctx_.fail(n, path(key), "expected a whole number, got '" + describe(n) + "'");
  }
  return v;
}

bool MapReader::boolean(const char* key, bool fallback) const {
  if (!has(key)) return fallback;
  const YAML::Node n = node(key);
  bool v = false;
  if (!n.IsScalar() || !YAML::convert<bool>::decode(n, v)) {
    ctx_.fail(n, path(key), "expected true or false, got '" + describe(n) + "'");
  }
  return v;
}

std::string MapReader::text(const char* key) const {
  const YAML::Node n = node(key);
  if (!n.IsScalar()) ctx_.fail(n, path(key), "expected a text value, got '" + describe(n) + "'");
  return n.Scalar();
}
std::string MapReader::text(const char* key, const std::string& fallback) const {
  return has(key) ? text(key) : fallback;
}

Vec2 MapReader::vec2(const char* key, const char* unit) const {
  return toVec2(ctx_, node(key), path(key), unit);
}
Vec2 MapReader::vec2(const char* key, const char* unit, const Vec2& fallback) const {
  return has(key) ? vec2(key, unit) : fallback;
}

Vec2 MapReader::vec2(const char* key, const limits::Range& range) const {
  const Vec2 v = vec2(key, range.unit);
  for (int a = 0; a < 2; ++a) require(key, limits::rangeProblem(v[a], range));
  return v;
}

void MapReader::require(bool ok, const char* key, const std::string& what) const {
  if (!ok) ctx_.fail(has(key) ? node_[key] : node_, path(key), what);
}

void MapReader::require(const char* key, const Problem& p, const std::string& prefix) const {
  require(p.empty(), key, prefix + p.message);
}

}  // namespace mpm_sdem::scene
