#include "mpm_sdem/robot/plane_section.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace mpm_sdem::robot {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

// The section by z = 0 of the convex hull of `corners` (the plane's frame): the hull of the
// corners on the plane and of the plane's crossings of the segments between corners on either
// side of it (every point of the section lies on such a segment).
Section polytopeSection(const std::vector<Eigen::Vector3d>& corners) {
  Section s;
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const Eigen::Vector3d& c : corners) {
    lo = std::min(lo, c.z());
    hi = std::max(hi, c.z());
  }
  if (lo > 0 || hi < 0) {
    s.gap = lo > 0 ? lo : -hi;
    return s;
  }
  std::vector<Kernel::Point_2> points;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Eigen::Vector3d& a = corners[i];
    if (a.z() == 0) points.emplace_back(a.x(), a.y());
    for (std::size_t j = i + 1; j < corners.size(); ++j) {
      const Eigen::Vector3d& b = corners[j];
      if ((a.z() < 0 && b.z() > 0) || (a.z() > 0 && b.z() < 0)) {
        const double t = a.z() / (a.z() - b.z());
        points.emplace_back(a.x() + t * (b.x() - a.x()), a.y() + t * (b.y() - a.y()));
      }
    }
  }
  std::vector<Kernel::Point_2> hull;
  CGAL::convex_hull_2(points.begin(), points.end(), std::back_inserter(hull));  // CCW
  // The crossings of a face's diagonals lie on the section's edges, and rounding puts some a
  // hair outside them: a corner that turns by less than 1e-9 rad is such a point, not a corner.
  const std::size_t n = hull.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 a(hull[(i + n - 1) % n].x(), hull[(i + n - 1) % n].y());
    const Vec2 b(hull[i].x(), hull[i].y()), c(hull[(i + 1) % n].x(), hull[(i + 1) % n].y());
    const Vec2 ab = b - a, bc = c - b;
    if (std::abs(ab.x() * bc.y() - ab.y() * bc.x()) > 1e-9 * ab.norm() * bc.norm())
      s.polygon.push_back(b);
  }
  if (s.polygon.size() < 3) s.polygon.clear();  // touches the plane along an edge or at a corner
  return s;
}

// The polygon's width: across its narrowest direction (for a convex polygon, normal to one of
// its edges).
double width(const std::vector<Vec2>& polygon) {
  double w = std::numeric_limits<double>::infinity();
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 e = polygon[(i + 1) % n] - polygon[i];
    const Vec2 normal = Vec2(e.y(), -e.x()).normalized();
    double far = 0;
    for (const Vec2& v : polygon) far = std::max(far, -normal.dot(v - polygon[i]));
    w = std::min(w, far);
  }
  return w;
}

// The convex polygon moved in by `by` on every edge: itself cut by each edge's line moved in
// (a half-plane clip, so an edge that vanishes leaves no stray vertex).
std::vector<Vec2> shrunk(const std::vector<Vec2>& polygon, double by) {
  std::vector<Vec2> out = polygon;
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n && out.size() >= 3; ++i) {
    const Vec2 e = polygon[(i + 1) % n] - polygon[i];
    const Vec2 normal = Vec2(e.y(), -e.x()).normalized();  // outward for counter-clockwise
    const double limit = normal.dot(polygon[i]) - by;
    std::vector<Vec2> kept;
    for (std::size_t k = 0; k < out.size(); ++k) {
      const Vec2 &a = out[k], &b = out[(k + 1) % out.size()];
      const double da = normal.dot(a) - limit, db = normal.dot(b) - limit;
      if (da <= 0) kept.push_back(a);
      if ((da < 0 && db > 0) || (da > 0 && db < 0)) kept.push_back(a + da / (da - db) * (b - a));
    }
    out.swap(kept);
  }
  return out;
}

}  // namespace

Section sectionByPlane(const Solid& solid, const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d centre = pose.translation();
  switch (solid.kind) {
    case Solid::Kind::kSphere: {
      Section s;
      const double d = std::abs(centre.z());
      if (d >= solid.radius) {
        s.gap = d - solid.radius;
      } else {
        s.centre = Vec2(centre.x(), centre.y());
        s.radius = std::sqrt(solid.radius * solid.radius - d * d);
      }
      return s;
    }
    case Solid::Kind::kCylinder: {
      const Eigen::Vector3d axis = pose.linear().col(2);
      if (std::abs(axis.z()) > 1 - 1e-12) {  // normal to the plane: a disc, exactly
        Section s;
        const double d = std::abs(centre.z()) - solid.length / 2;
        if (d >= 0) {
          s.gap = d;
        } else {
          s.centre = Vec2(centre.x(), centre.y());
          s.radius = solid.radius;
        }
        return s;
      }
      std::vector<Eigen::Vector3d> corners;
      for (int k = 0; k < kCylinderFacets; ++k) {
        const double a = 2 * M_PI * k / kCylinderFacets;
        for (const double z : {-solid.length / 2, solid.length / 2})
          corners.push_back(
              pose * Eigen::Vector3d(solid.radius * std::cos(a), solid.radius * std::sin(a), z));
      }
      return polytopeSection(corners);
    }
    case Solid::Kind::kConvex: {
      std::vector<Eigen::Vector3d> corners;
      for (const Eigen::Vector3d& c : solid.corners) corners.push_back(pose * c);
      return polytopeSection(corners);
    }
    case Solid::Kind::kBox:
    default: {
      std::vector<Eigen::Vector3d> corners;
      for (int k = 0; k < 8; ++k)
        corners.push_back(pose * Eigen::Vector3d((k & 1 ? 0.5 : -0.5) * solid.size.x(),
                                                 (k & 2 ? 0.5 : -0.5) * solid.size.y(),
                                                 (k & 4 ? 0.5 : -0.5) * solid.size.z()));
      return polytopeSection(corners);
    }
  }
}

void outlineInFrame(const Section& section, const Vec2& origin, double angle, double rounding,
                    BlockDef& def) {
  const Eigen::Rotation2D<double> to_frame(-angle);
  auto local = [&](const Vec2& p) -> Vec2 { return to_frame * (p - origin); };
  def.core.clear();
  def.discs.clear();
  if (section.radius > 0) {  // a disc: one core vertex swept by its radius
    def.core.push_back(local(section.centre));
    def.rounding = section.radius;
    return;
  }
  def.rounding = std::min(rounding, width(section.polygon) / 4);
  for (const Vec2& v : shrunk(section.polygon, def.rounding)) def.core.push_back(local(v));
}

}  // namespace mpm_sdem::robot
