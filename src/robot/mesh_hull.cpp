#include "mpm_sdem/robot/mesh_hull.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/convex_hull_3.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cctype>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace mpm_sdem::robot {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
}  // namespace

std::vector<Eigen::Vector3d> meshHullCorners(const std::string& path,
                                             const Eigen::Vector3d& scale) {
  std::string ext = path.substr(std::min(path.size(), path.rfind('.') + 1));
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != "stl" && ext != "off" && ext != "obj" && ext != "ply")
    throw std::runtime_error("mesh '" + path + "' is not in a format read here (" +
                             std::string(kMeshFormats) +
                             "); export its collision mesh as STL, or give the link a box, "
                             "cylinder or sphere collision");
  if (!std::ifstream(path))
    throw std::runtime_error("mesh '" + path + "' cannot be opened (no such file?)");
  std::vector<Kernel::Point_3> points;
  std::vector<std::vector<std::size_t>> faces;
  if (!CGAL::IO::read_polygon_soup(path, points, faces, CGAL::parameters::verbose(false)) ||
      points.empty())
    throw std::runtime_error("mesh '" + path + "' cannot be read as " + ext);
  for (Kernel::Point_3& p : points)
    p = Kernel::Point_3(p.x() * scale.x(), p.y() * scale.y(), p.z() * scale.z());
  // Only the hull's corners matter to a section (plane_section.hpp), and they are few.
  std::vector<Kernel::Point_3> corners;
  CGAL::extreme_points_3(points, std::back_inserter(corners));
  std::vector<Eigen::Vector3d> out;
  for (const Kernel::Point_3& p : corners) out.emplace_back(p.x(), p.y(), p.z());
  // Flat (a single-sided plate, say): its spread normal to its plane is nil.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& c : out) mean += c / static_cast<double>(out.size());
  Eigen::Matrix3d spread = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& c : out) spread += (c - mean) * (c - mean).transpose();
  const Eigen::Vector3d s = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(spread).eigenvalues();
  if (out.size() < 4 || !(s(0) > 1e-12 * s(2)))
    throw std::runtime_error("mesh '" + path + "' spans no volume (its " +
                             std::to_string(points.size()) + " vertices lie in one plane)");
  return out;
}

}  // namespace mpm_sdem::robot
