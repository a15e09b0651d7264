#include "mpm_sdem/core/rigid/spheropolygon.hpp"

#include "mpm_sdem/core/mpm/shapes.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace mpm_sdem {

namespace {

// Area, first moment and polar second moment (about the frame origin) of a simple polygon.
struct Moments {
  Real area = 0;
  Vec2 first{0, 0};
  Real polar = 0;
  void addPolygon(const Vec2* v, int n) {
    for (int i = 0; i < n; ++i) {
      const Vec2& a = v[i];
      const Vec2& b = v[(i + 1) % n];
      const Real c = cross(a, b);
      area += c / 2;
      first += c * (a + b) / 6;
      polar += c * (a.squaredNorm() + a.dot(b) + b.squaredNorm()) / 12;
    }
  }
  // Circular sector of radius r centred at v, between polar angles t0 and t0 + dt.
  void addSector(const Vec2& v, Real r, Real t0, Real dt) {
    const Vec2 u_int(std::sin(t0 + dt) - std::sin(t0), std::cos(t0) - std::cos(t0 + dt));
    area += r * r * dt / 2;
    first += v * r * r * dt / 2 + u_int * r * r * r / 3;
    polar += v.squaredNorm() * r * r * dt / 2 + 2 * v.dot(u_int) * r * r * r / 3 +
             r * r * r * r * dt / 4;
  }
};

Vec2 outwardNormal(const Vec2& a, const Vec2& b) {
  const Vec2 e = b - a;
  return Vec2(e.y(), -e.x()).normalized();  // right of the edge: outward for CCW order
}

}  // namespace

MassProperties spheropolygonMass(const std::vector<Vec2>& core, Real a, Real density) {
  Moments m;
  const int n = static_cast<int>(core.size());
  if (n == 1) {
    m.addSector(core[0], a, 0, 2 * M_PI);
  } else {
    if (n >= 3) m.addPolygon(core.data(), n);
    for (int i = 0; i < n; ++i) {
      const Vec2& p = core[i];
      const Vec2& q = core[(i + 1) % n];
      const Vec2 nrm = outwardNormal(p, q);
      // Outward from p, along the edge, back in at q: counter-clockwise.
      const Vec2 quad[4] = {p, p + a * nrm, q + a * nrm, q};
      m.addPolygon(quad, 4);
      // Sector at q from this edge's normal to the next edge's normal (counter-clockwise).
      const Vec2 next = outwardNormal(q, core[(i + 2) % n]);
      const Real t0 = std::atan2(nrm.y(), nrm.x());
      Real dt = std::atan2(cross(nrm, next), nrm.dot(next));
      if (dt < 0) dt += 2 * M_PI;
      if (n == 2 && dt == 0) dt = M_PI;  // a capsule's end cap
      m.addSector(q, a, t0, dt);
    }
  }
  MassProperties out;
  out.area = m.area;
  out.mass = density * m.area;
  out.centroid = m.first / m.area;
  out.inertia = density * (m.polar - m.area * out.centroid.squaredNorm());
  return out;
}

void makeCounterClockwise(std::vector<Vec2>& core) {
  Real twice_area = 0;
  for (std::size_t i = 0; i < core.size(); ++i)
    twice_area += cross(core[i], core[(i + 1) % core.size()]);
  if (twice_area < 0) std::reverse(core.begin(), core.end());
}

Problem coreProblem(const std::vector<Vec2>& core) {
  const int n = static_cast<int>(core.size());
  if (n < 1) return "a block needs at least one core vertex (one vertex makes a disk)";
  if (n > kMaxBlockVertices) {
    return "a block core has at most " + std::to_string(kMaxBlockVertices) +
           " vertices (Box2D's limit), got " + std::to_string(n);
  }
  for (const Vec2& v : core) {
    if (!v.allFinite()) return "a core vertex is not a finite number";
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      if ((core[i] - core[j]).norm() <= 1e-12 * (1 + core[i].norm()))
        return "two core vertices coincide";
    }
  }
  if (n < 3) return "";
  if (selfIntersects(core)) {
    return "the core polygon's edges cross each other; list the vertices in order around it";
  }
  Real twice_area = 0;
  for (int i = 0; i < n; ++i) twice_area += cross(core[i], core[(i + 1) % n]);
  Real scale = 0;
  for (const Vec2& v : core) scale = std::fmax(scale, (v - core[0]).norm());
  if (std::abs(twice_area) <= 1e-12 * scale * scale) return "the core polygon has zero area";
  const Real sign = twice_area > 0 ? 1 : -1;
  for (int i = 0; i < n; ++i) {
    const Vec2 e1 = core[(i + 1) % n] - core[i];
    const Vec2 e2 = core[(i + 2) % n] - core[(i + 1) % n];
    // A vertex on the line through its neighbours is refused too: relative to the edge lengths,
    // so that the answer does not hang on the rounding of the cross product.
    if (sign * cross(e1, e2) <= 1e-12 * e1.norm() * e2.norm()) {
      return "the core polygon is not convex (or its vertices are not in order around it); "
             "split a concave outline into several blocks";
    }
  }
  return "";
}

CoreDistance closestOnCore(const Vec2* v, int n, const Vec2& q) {
  CoreDistance out;
  if (n == 1) {
    const Vec2 d = q - v[0];
    out.distance = d.norm();
    out.point = v[0];
    out.normal = out.distance > 0 ? Vec2(d / out.distance) : Vec2(0, 1);
    return out;
  }
  Real best = std::numeric_limits<Real>::infinity();
  bool inside = n >= 3;
  Real deepest =
      -std::numeric_limits<Real>::infinity();  // inside: max over edges of signed distance
  Vec2 deep_point{0, 0}, deep_normal{0, 1};
  const int edges = n == 2 ? 1 : n;
  for (int i = 0; i < edges; ++i) {
    const Vec2& a = v[i];
    const Vec2& b = v[(i + 1) % n];
    const Vec2 e = b - a;
    const Real len2 = e.squaredNorm();
    // The edge's parameter clamped to [0, 1] as fmin(fmax(r, 0), 1) would, NaN (a zero-length
    // edge) to 0, without their calls (this runs for every pair in every contact substep).
    const Real r = (q - a).dot(e) / len2;
    const Real t = r > 0 ? (r < 1 ? r : Real(1)) : Real(0);
    const Vec2 c = a + t * e;
    const Real d2 = (q - c).squaredNorm();
    if (d2 < best) {
      best = d2;
      out.point = c;
    }
    // The deepest edge matters only while the point may be inside: one edge it is outside of
    // settles that.
    if (inside) {
      const Real len = std::sqrt(len2);
      const Vec2 nrm(e.y() / len, -e.x() / len);
      const Real s = (q - a).dot(nrm);
      if (s > 0) inside = false;
      if (s > deepest) {
        deepest = s;
        deep_normal = nrm;
        deep_point = q - s * nrm;
      }
    }
  }
  if (inside) {
    out.distance = deepest;  // <= 0
    out.point = deep_point;
    out.normal = deep_normal;
    return out;
  }
  out.distance = std::sqrt(best);
  if (out.distance > 0) {
    out.normal = (q - out.point) / out.distance;
  } else if (n == 2) {
    const Vec2 e = v[1] - v[0];
    out.normal = Vec2(e.y(), -e.x()).normalized();
  }
  return out;
}

std::vector<Vec2> roundedOutline(const std::vector<Vec2>& core, Real a, int arc_points) {
  std::vector<Vec2> out;
  const int n = static_cast<int>(core.size());
  if (n == 1) {
    for (int k = 0; k <= 4 * arc_points; ++k) {
      const Real t = 2 * M_PI * k / (4 * arc_points);
      out.push_back(core[0] + a * Vec2(std::cos(t), std::sin(t)));
    }
    return out;
  }
  // Counter-clockwise core: at vertex i the arc runs from the normal of the edge before to
  // the normal of the edge after (for a capsule, n = 2, each arc is a half circle).
  for (int i = 0; i < n; ++i) {
    const Vec2 e_in = core[i] - core[(i + n - 1) % n], e_out = core[(i + 1) % n] - core[i];
    const Real t0 = std::atan2(-e_in.x(), e_in.y()), t1 = std::atan2(-e_out.x(), e_out.y());
    Real sweep = t1 - t0;
    while (sweep < 0) sweep += 2 * M_PI;
    if (n == 2) sweep = M_PI;
    for (int k = 0; k <= arc_points; ++k) {
      const Real t = t0 + sweep * k / arc_points;
      out.push_back(core[i] + a * Vec2(std::cos(t), std::sin(t)));
    }
  }
  out.push_back(out.front());
  return out;
}

}  // namespace mpm_sdem
