#include "mpm_sdem/core/fem/fem_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace mpm_sdem {

namespace {

// Each undirected edge with the triangles that use it, as (triangle, local edge k: nodes k and
// k + 1).
std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> edgeUse(const FemMesh& m) {
  std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> use;
  for (int t = 0; t < static_cast<int>(m.triangles.size()); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int a = m.triangles[t][k], b = m.triangles[t][(k + 1) % 3];
      use[{std::min(a, b), std::max(a, b)}].push_back({t, k});
    }
  }
  return use;
}

}  // namespace

Problem meshProblem(const FemMesh& m) {
  if (m.triangles.empty()) return "the mesh has no triangles";
  const int n = static_cast<int>(m.nodes.size());
  std::vector<char> used(m.nodes.size(), 0);
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    const auto& tri = m.triangles[t];
    for (const int v : tri) {
      if (v < 0 || v >= n)
        return "triangle " + std::to_string(t) + " names node " + std::to_string(v) +
               ", not one of the " + std::to_string(n) + " nodes";
      if (!m.nodes[v].allFinite()) return "node " + std::to_string(v) + " is not finite";
      used[v] = 1;
    }
    const Vec2 e1 = m.nodes[tri[1]] - m.nodes[tri[0]], e2 = m.nodes[tri[2]] - m.nodes[tri[0]];
    const Real longest2 = std::max({e1.squaredNorm(), e2.squaredNorm(), (e2 - e1).squaredNorm()});
    if (!(cross(e1, e2) > 1e-12 * longest2))
      return "triangle " + std::to_string(t) + " is clockwise or degenerate";
  }
  for (int v = 0; v < n; ++v)
    if (!used[v]) return "node " + std::to_string(v) + " belongs to no triangle";
  for (const auto& [edge, users] : edgeUse(m))
    if (users.size() > 2)
      return "the edge between nodes " + std::to_string(edge.first) + " and " +
             std::to_string(edge.second) + " belongs to " + std::to_string(users.size()) +
             " triangles";
  return "";
}

std::vector<BoundaryEdge> boundaryEdges(const FemMesh& m) {
  std::vector<BoundaryEdge> edges;
  for (const auto& [edge, users] : edgeUse(m)) {
    if (users.size() != 1) continue;
    const auto& tri = m.triangles[users[0].first];
    const int k = users[0].second;
    edges.push_back({tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]});
  }
  return edges;
}

}  // namespace mpm_sdem
