/// @file
/// A collision mesh as the convex solid its vertices span: a link's mesh becomes a block through
/// the section of its convex hull by the simulation plane (a block's outline is convex anyway).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace mpm_sdem::robot {

/// The file formats meshHullCorners reads (CGAL's polygon-soup readers), by extension.
constexpr const char* kMeshFormats = "STL, OFF, OBJ or PLY";

/// The corners of the convex hull of the vertices of the mesh file at `path`, each scaled by
/// `scale` per axis (URDF's mesh scale), in the mesh's frame (m). Throws std::runtime_error
/// naming the file when it cannot be read, is in another format (COLLADA .dae, for one) or its
/// vertices span no volume.
std::vector<Eigen::Vector3d> meshHullCorners(const std::string& path, const Eigen::Vector3d& scale);

}  // namespace mpm_sdem::robot
