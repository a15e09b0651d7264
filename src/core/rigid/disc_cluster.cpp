#include "mpm_sdem/core/rigid/disc_cluster.hpp"

#include <algorithm>
#include <cmath>

namespace mpm_sdem {

namespace {

// The integrals of 1, x, y and x^2 + y^2 over a region, from its boundary.
struct ArcMoments {
  Real area = 0, x = 0, y = 0, polar = 0;
};

// Green's theorem on the arc theta in [a, b] of the circle (c, r), counter-clockwise:
// area from (x dy - y dx) / 2, x from x^2 dy / 2, y from -y^2 dx / 2, x^2 + y^2 from
// (x^3 dy - y^3 dx) / 3, with x = c_x + r cos t, y = c_y + r sin t; each a trigonometric
// polynomial of degree at most 4 in t, integrated in closed form (primitive at b minus at a).
ArcMoments arcMoments(const Vec2& c, Real r, Real a, Real b) {
  auto primitive = [&](Real t) {
    const Real C = std::cos(t), S = std::sin(t), s2 = std::sin(2 * t), s4 = std::sin(4 * t);
    const Real cc = t / 2 + s2 / 4, ss = t / 2 - s2 / 4;           // of cos^2, sin^2
    const Real ccc = S - S * S * S / 3, sss = -C + C * C * C / 3;  // of cos^3, sin^3
    const Real c4 = 3 * t / 8 + s2 / 4 + s4 / 32, s4i = 3 * t / 8 - s2 / 4 + s4 / 32;
    const Real cx = c.x(), cy = c.y();
    ArcMoments m;
    m.area = (r * r * t + r * cx * S - r * cy * C) / 2;
    m.x = r / 2 * (cx * cx * S + 2 * cx * r * cc + r * r * ccc);
    m.y = r / 2 * (-cy * cy * C + 2 * cy * r * ss + r * r * sss);
    m.polar = r / 3 *
              (cx * cx * cx * S + 3 * cx * cx * r * cc + 3 * cx * r * r * ccc + r * r * r * c4 -
               cy * cy * cy * C + 3 * cy * cy * r * ss + 3 * cy * r * r * sss + r * r * r * s4i);
    return m;
  };
  const ArcMoments pb = primitive(b), pa = primitive(a);
  return {pb.area - pa.area, pb.x - pa.x, pb.y - pa.y, pb.polar - pa.polar};
}

// The angles of circle i's boundary inside the other discs, as intervals in [0, 2 pi), merged;
// or the whole circle (covered = true) when i lies inside another disc.
bool coveredArcs(const std::vector<Disc>& discs, std::size_t i,
                 std::vector<std::pair<Real, Real>>& arcs) {
  constexpr Real kTwoPi = 2 * M_PI;
  arcs.clear();
  const Disc& a = discs[i];
  for (std::size_t j = 0; j < discs.size(); ++j) {
    if (j == i) continue;
    const Disc& b = discs[j];
    const Real d = (b.centre - a.centre).norm();
    if (d >= a.radius + b.radius) continue;  // apart or touching
    if (d <= b.radius - a.radius) {
      // Inside b. Two equal discs at one place: the first of them stands for both.
      if (d == 0 && a.radius == b.radius && j > i) continue;
      return true;
    }
    if (d <= a.radius - b.radius) continue;  // b inside a
    const Real phi = std::atan2(b.centre.y() - a.centre.y(), b.centre.x() - a.centre.x());
    const Real cosine = (a.radius * a.radius + d * d - b.radius * b.radius) / (2 * a.radius * d);
    const Real half = std::acos(std::clamp(cosine, Real(-1), Real(1)));
    Real lo = std::fmod(phi - half + 2 * kTwoPi, kTwoPi);
    const Real hi = lo + 2 * half;
    if (hi > kTwoPi) {
      arcs.emplace_back(lo, kTwoPi);
      arcs.emplace_back(0, hi - kTwoPi);
    } else {
      arcs.emplace_back(lo, hi);
    }
  }
  std::sort(arcs.begin(), arcs.end());
  std::size_t n = 0;
  for (const auto& arc : arcs) {
    if (n > 0 && arc.first <= arcs[n - 1].second)
      arcs[n - 1].second = std::fmax(arcs[n - 1].second, arc.second);
    else
      arcs[n++] = arc;
  }
  arcs.resize(n);
  return false;
}

}  // namespace

MassProperties discUnionMass(const std::vector<Disc>& discs, Real density) {
  ArcMoments sum;
  std::vector<std::pair<Real, Real>> covered;
  auto add = [&](const ArcMoments& m) {
    sum.area += m.area;
    sum.x += m.x;
    sum.y += m.y;
    sum.polar += m.polar;
  };
  for (std::size_t i = 0; i < discs.size(); ++i) {
    if (coveredArcs(discs, i, covered)) continue;
    const Vec2& c = discs[i].centre;
    const Real r = discs[i].radius;
    // The open arcs between the covered ones.
    Real from = 0;
    for (const auto& arc : covered) {
      if (arc.first > from) add(arcMoments(c, r, from, arc.first));
      from = std::fmax(from, arc.second);
    }
    if (from < 2 * M_PI) add(arcMoments(c, r, from, 2 * M_PI));
  }
  MassProperties m;
  m.area = sum.area;
  m.mass = density * sum.area;
  if (sum.area > 0) m.centroid = Vec2(sum.x, sum.y) / sum.area;
  m.inertia = density * (sum.polar - sum.area * m.centroid.squaredNorm());
  return m;
}

std::vector<Disc> fillWithDiscs(const Spheropolygon& outline, Real radius, Real pitch) {
  std::vector<Disc> discs;
  if (!(radius > 0) || !(pitch > 0) || outline.core.empty()) return discs;
  Vec2 lo = outline.core[0], hi = outline.core[0];
  for (const Vec2& v : outline.core) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const Vec2 size = (hi - lo).array() + 2 * outline.rounding;
  lo.array() -= outline.rounding;
  const Real slack = 1e-9 * radius;  // a disc exactly touching the outline counts as inside
  int n[2];
  Real start[2];
  for (int a = 0; a < 2; ++a) {
    if (size[a] + slack < 2 * radius) return discs;
    n[a] = static_cast<int>(std::floor((size[a] - 2 * radius + slack) / pitch)) + 1;
    start[a] = lo[a] + radius + (size[a] - 2 * radius - (n[a] - 1) * pitch) / 2;
  }
  const int count = static_cast<int>(outline.core.size());
  for (int j = 0; j < n[1]; ++j) {
    for (int i = 0; i < n[0]; ++i) {
      const Vec2 c(start[0] + i * pitch, start[1] + j * pitch);
      if (closestOnCore(outline.core.data(), count, c).distance <=
          outline.rounding - radius + slack)
        discs.push_back({c, radius});
    }
  }
  return discs;
}

Problem discsProblem(const std::vector<Disc>& discs) {
  if (discs.empty()) return "a cluster needs at least one disc";
  if (discs.size() > static_cast<std::size_t>(kMaxClusterDiscs))
    return "a cluster has at most " + std::to_string(kMaxClusterDiscs) + " discs, got " +
           std::to_string(discs.size());
  for (std::size_t i = 0; i < discs.size(); ++i) {
    if (!discs[i].centre.allFinite())
      return "disc " + std::to_string(i) + ": its centre must be finite numbers";
    if (!(discs[i].radius > 0) || !std::isfinite(discs[i].radius))
      return "disc " + std::to_string(i) + ": its radius must be positive and finite";
  }
  return "";
}

}  // namespace mpm_sdem
