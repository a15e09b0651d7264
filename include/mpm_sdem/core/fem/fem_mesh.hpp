/// \file
/// A plane-strain finite-element mesh of linear triangles (seed 002 sec. 2.3 in 2D): nodes in the
/// world frame (m) and counter-clockwise triangles. Made by the mesher (mpm_sdem/mesh/mesher.hpp)
/// or given directly; the core checks it and finds its boundary.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// Linear triangles: node positions (m) and each triangle's three node indices, counter-clockwise.
struct FemMesh {
  std::vector<Vec2> nodes;                    ///< m
  std::vector<std::array<int, 3>> triangles;  ///< node numbers, counter-clockwise
};

/// "" when the mesh can be simulated, else why not: no triangles, a node number out of range, a
/// triangle that is clockwise or degenerate (area below 1e-12 of its longest edge squared), a
/// node no triangle uses, an edge shared by more than two triangles.
Problem meshProblem(const FemMesh& mesh);

/// The edges that belong to one triangle only, each oriented as its triangle runs
/// (counter-clockwise: the body on the left, the outward normal on the right), with the node
/// opposite to it in that triangle.
struct BoundaryEdge {
  ///@{
  /// nodes
  int a = 0, b = 0;
  ///@}
  int opposite = 0;  ///< the third node of the edge's triangle
};
/// The mesh's boundary: the edges that belong to one triangle only.
std::vector<BoundaryEdge> boundaryEdges(const FemMesh& mesh);

}  // namespace mpm_sdem
