#include "mpm_sdem/core/mpm/shapes.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm_sdem {

namespace {
bool segmentsTouch(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const Real d1 = cross(b - a, c - a), d2 = cross(b - a, d - a);
  const Real d3 = cross(d - c, a - c), d4 = cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
  auto onSegment = [](const Vec2& p, const Vec2& q, const Vec2& r, Real c) {
    return c == 0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return onSegment(a, b, c, d1) || onSegment(a, b, d, d2) || onSegment(c, d, a, d3) ||
         onSegment(c, d, b, d4);
}
}  // namespace

Real signedArea(const std::vector<Vec2>& polygon) {
  Real a = 0;
  for (std::size_t i = 0, n = polygon.size(); i < n; ++i)
    a += cross(polygon[i], polygon[(i + 1) % n]);
  return a / 2;
}

bool selfIntersects(const std::vector<Vec2>& polygon) {
  const std::size_t n = polygon.size();
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) continue;
      if (segmentsTouch(polygon[i], polygon[(i + 1) % n], polygon[j], polygon[(j + 1) % n])) {
        return true;
      }
    }
  }
  return false;
}

bool contains(const ShapeDef& shape, const Vec2& p) {
  switch (shape.type) {
    case ShapeType::kRectangle:
      return p.x() >= shape.min.x() && p.x() <= shape.max.x() && p.y() >= shape.min.y() &&
             p.y() <= shape.max.y();
    case ShapeType::kDisk:
      return (p - shape.center).squaredNorm() <= shape.radius * shape.radius;
    case ShapeType::kPolygon: {
      // Even-odd ray casting: works for concave polygons of either orientation.
      bool inside = false;
      const auto& v = shape.vertices;
      for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++) {
        if ((v[i].y() > p.y()) != (v[j].y() > p.y()) &&
            p.x() < (v[j].x() - v[i].x()) * (p.y() - v[i].y()) / (v[j].y() - v[i].y()) + v[i].x()) {
          inside = !inside;
        }
      }
      return inside;
    }
  }
  return false;
}

void bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi) {
  switch (shape.type) {
    case ShapeType::kRectangle:
      lo = shape.min;
      hi = shape.max;
      return;
    case ShapeType::kDisk:
      lo = shape.center.array() - shape.radius;
      hi = shape.center.array() + shape.radius;
      return;
    case ShapeType::kPolygon:
      lo = hi = shape.vertices.front();
      for (const Vec2& v : shape.vertices) {
        lo = lo.cwiseMin(v);
        hi = hi.cwiseMax(v);
      }
      return;
  }
}

Real outlineDistance(const ShapeDef& shape, const Vec2& p) {
  auto toSegment = [&p](const Vec2& a, const Vec2& b) {
    const Vec2 e = b - a;
    const Real t = std::clamp((p - a).dot(e) / e.squaredNorm(), Real(0), Real(1));
    return (a + t * e - p).norm();
  };
  switch (shape.type) {
    case ShapeType::kRectangle:
      return std::min({p.x() - shape.min.x(), shape.max.x() - p.x(), p.y() - shape.min.y(),
                       shape.max.y() - p.y()});
    case ShapeType::kDisk:
      return shape.radius - (p - shape.center).norm();
    case ShapeType::kPolygon: {
      Real d = std::numeric_limits<Real>::infinity();
      const auto& v = shape.vertices;
      for (std::size_t i = 0, j = v.size() - 1; i < v.size(); j = i++)
        d = std::min(d, toSegment(v[j], v[i]));
      return d;
    }
  }
  return 0;
}

std::vector<Vec2> fillPoints(const ShapeDef& shape, const Vec2& domain_min, Real cell_size,
                             int points_per_cell) {
  Vec2 lo, hi;
  bounds(shape, lo, hi);
  const Real s = cell_size / points_per_cell;
  const long i0 = static_cast<long>(std::floor((lo.x() - domain_min.x()) / s));
  const long i1 = static_cast<long>(std::ceil((hi.x() - domain_min.x()) / s));
  const long j0 = static_cast<long>(std::floor((lo.y() - domain_min.y()) / s));
  const long j1 = static_cast<long>(std::ceil((hi.y() - domain_min.y()) / s));
  std::vector<Vec2> points;
  for (long j = j0; j < j1; ++j) {
    for (long i = i0; i < i1; ++i) {
      const Vec2 p = domain_min + s * Vec2(i + Real(0.5), j + Real(0.5));
      if (contains(shape, p)) points.push_back(p);
    }
  }
  return points;
}

AreaMoments areaMoments(const ShapeDef& shape) {
  AreaMoments m;
  switch (shape.type) {
    case ShapeType::kRectangle: {
      const Vec2 size = shape.max - shape.min;
      m.area = size.x() * size.y();
      m.centroid = 0.5 * (shape.min + shape.max);
      m.polar = m.area * size.squaredNorm() / 12;
      return m;
    }
    case ShapeType::kDisk:
      m.area = M_PI * shape.radius * shape.radius;
      m.centroid = shape.center;
      m.polar = m.area * shape.radius * shape.radius / 2;
      return m;
    case ShapeType::kPolygon: {
      // Sums over the triangles (o, v_i, v_i+1) from a vertex o, which keeps round-off small;
      // signed, so either orientation gives the same result once divided by the area.
      const auto& v = shape.vertices;
      const Vec2 o = v.front();
      Real area2 = 0, polar12 = 0;  // twice the area; 12 times the polar moment about o
      Vec2 first6(0, 0);            // 6 times the first moment about o
      for (std::size_t i = 0, n = v.size(); i < n; ++i) {
        const Vec2 a = v[i] - o, b = v[(i + 1) % n] - o;
        const Real c = cross(a, b);
        area2 += c;
        first6 += c * (a + b);
        polar12 += c * (a.squaredNorm() + a.dot(b) + b.squaredNorm());
      }
      m.area = std::abs(area2) / 2;
      const Vec2 offset = first6 / (3 * area2);
      m.centroid = o + offset;
      m.polar = std::abs(polar12) / 12 - m.area * offset.squaredNorm();
      return m;
    }
  }
  return m;
}

std::vector<Real> pointVolumes(const ShapeDef& shape, const std::vector<Vec2>& points,
                               Real spacing) {
  const Real v0 = spacing * spacing;
  std::vector<Real> volumes(points.size(), v0);
  // Straight edges keep the lattice's volumes: their staircase error is a strip along one edge,
  // which a reweighting of the whole outer layer spreads over every edge and corner (the silo's
  // sand at 3.5 mm cells: 0.58-1.34 spacing^2 along its walls, and its flow rates moved by
  // 2-11%). A strip wants the points' own area fractions, which this does not compute.
  if (shape.type != ShapeType::kDisk) return volumes;
  const AreaMoments want = areaMoments(shape);
  if (points.empty() || !(want.area > 0)) return volumes;
  // Moments in units of the shape's size, so that the 4 x 4 system is well conditioned.
  const Real L = std::sqrt(want.area);
  auto basis = [&](const Vec2& x) {
    const Vec2 d = (x - want.centroid) / L;
    return Eigen::Vector4d(1, d.x(), d.y(), d.squaredNorm());
  };
  Eigen::Vector4d have = Eigen::Vector4d::Zero();
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  std::vector<std::size_t> ring;
  for (std::size_t p = 0; p < points.size(); ++p) {
    const Eigen::Vector4d b = basis(points[p]);
    have += v0 / want.area * b;
    if (outlineDistance(shape, points[p]) < spacing) {
      ring.push_back(p);
      normal += b * b.transpose();
    }
  }
  // The points stand for squares of side s whose own polar moment, s^4 / 6 each, is not in
  // sum V |d|^2: the target is the shape's less A s^2 / 6 (parallel axis theorem).
  const Real own = want.area * spacing * spacing / 6;
  const Eigen::Vector4d target(1, 0, 0, (want.polar - own) / (want.area * want.area));
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(normal);
  if (lu.rank() < 4) return volumes;  // too few outer points to carry four moments
  // Least-norm change over the outer layer: dV_p = A b_p . lambda, with
  // sum_p dV_p b_p = A (target - have).
  const Eigen::Vector4d lambda = lu.solve(target - have);
  for (std::size_t p : ring) {
    const Real v = v0 + want.area * basis(points[p]).dot(lambda);
    if (!(v >= 0.5 * v0 && v <= 1.5 * v0)) return std::vector<Real>(points.size(), v0);
    volumes[p] = v;
  }
  return volumes;
}

}  // namespace mpm_sdem
