#include "mpm_sdem/mesh/mesher.hpp"

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Delaunay_mesh_face_base_2.h>
#include <CGAL/Delaunay_mesh_size_criteria_2.h>
#include <CGAL/Delaunay_mesher_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2.h>

#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

namespace mpm_sdem {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_2<Kernel>;
using FaceBase = CGAL::Delaunay_mesh_face_base_2<Kernel>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;
using Criteria = CGAL::Delaunay_mesh_size_criteria_2<Cdt>;
using Point = Kernel::Point_2;

// sin^2 of the smallest angle the refinement leaves: CGAL's default bound, B = sqrt(2) for which
// Delaunay refinement terminates (about 20.7 degrees).
constexpr double kAspectBound = 0.125;

}  // namespace

FemMesh meshPolygon(const std::vector<Vec2>& outline, Real element_size,
                    std::size_t max_triangles) {
  if (outline.size() < 3)
    throw std::invalid_argument("an FEM outline needs at least 3 vertices, got " +
                                std::to_string(outline.size()));
  if (!(element_size > 0) || !std::isfinite(element_size))
    throw std::invalid_argument("element_size must be a positive length (m)");
  CGAL::Polygon_2<Kernel> polygon;
  for (const Vec2& v : outline) {
    if (!v.allFinite()) throw std::invalid_argument("an FEM outline vertex is not finite");
    polygon.push_back(Point(v.x(), v.y()));
  }
  if (!polygon.is_simple())
    throw std::invalid_argument(
        "the FEM outline is not a simple polygon (two edges cross or a vertex repeats)");
  const double area = std::abs(CGAL::to_double(polygon.area()));
  if (!(area > 0)) throw std::invalid_argument("the FEM outline has no area");
  // Equilateral triangles of side element_size cover sqrt(3)/4 h^2 each; refinement makes a few
  // smaller ones near corners: estimate twice the count before meshing.
  const double expected = 2 * area / (std::sqrt(3.0) / 4 * element_size * element_size);
  if (expected > static_cast<double>(max_triangles))
    throw std::invalid_argument("element_size " + std::to_string(element_size) +
                                " m would make about " + std::to_string(expected) +
                                " triangles, more than the limit " + std::to_string(max_triangles) +
                                "; use a larger element_size");

  Cdt cdt;
  std::vector<Cdt::Vertex_handle> corners;
  for (const Vec2& v : outline) corners.push_back(cdt.insert(Point(v.x(), v.y())));
  for (std::size_t i = 0; i < corners.size(); ++i)
    cdt.insert_constraint(corners[i], corners[(i + 1) % corners.size()]);
  // Without seeds the domain is what the constraints enclose.
  CGAL::refine_Delaunay_mesh_2(cdt, Criteria(kAspectBound, element_size));

  FemMesh mesh;
  std::map<Cdt::Vertex_handle, int> number;
  auto nodeOf = [&](Cdt::Vertex_handle v) {
    const auto [it, added] = number.emplace(v, static_cast<int>(mesh.nodes.size()));
    if (added) mesh.nodes.emplace_back(v->point().x(), v->point().y());
    return it->second;
  };
  for (const Cdt::Face_handle f : cdt.finite_face_handles()) {
    if (!f->is_in_domain()) continue;
    std::array<int, 3> t{nodeOf(f->vertex(0)), nodeOf(f->vertex(1)), nodeOf(f->vertex(2))};
    mesh.triangles.push_back(t);  // CGAL's faces are counter-clockwise
  }
  if (mesh.triangles.size() > max_triangles)
    throw std::invalid_argument("the mesh has " + std::to_string(mesh.triangles.size()) +
                                " triangles, more than the limit " + std::to_string(max_triangles) +
                                "; use a larger element_size");
  return mesh;
}

}  // namespace mpm_sdem
