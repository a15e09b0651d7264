// Meshes for FEM bodies: a polygon filled with triangles by CGAL's 2D constrained Delaunay
// mesher (Delaunay refinement with Ruppert's and Shewchuk's criteria). Kept out of the physics
// core: the scene layer meshes, the core receives an FemMesh.
#pragma once

#include <vector>

#include "mpm_sdem/core/fem/fem_mesh.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

// Triangles of edges at most element_size (m) filling the simple polygon outline (m, either
// orientation), with no angle below about 20.7 degrees (CGAL's bound B = sqrt(2), the mesher's
// guarantee for inputs without small angles). Every outline vertex is a node; the outline's
// edges are split to the size. Throws std::invalid_argument on an outline of fewer than three
// vertices, zero area, crossing edges or an element size that is not positive, or when the mesh
// would exceed max_triangles.
FemMesh meshPolygon(const std::vector<Vec2>& outline, Real element_size,
                    std::size_t max_triangles = 200000);

}  // namespace mpm_sdem
