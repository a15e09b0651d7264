#include "rigid/box2d_shapes.hpp"

#include <stdexcept>
#include <string>

namespace mpm_sdem::detail {

namespace {

// The core with every edge pushed out by g (in by -g): Box2D cannot round a polygon, so its
// contact solver sees this polygon (exact along the edges, sharp instead of round at the
// corners). A segment becomes the rectangle g around it.
std::vector<Vec2> grownCore(const std::vector<Vec2>& core, Real g) {
  const int n = static_cast<int>(core.size());
  if (n == 2) {
    const Vec2 e = (core[1] - core[0]).normalized();
    const Vec2 nrm(e.y(), -e.x());
    const Vec2 p = core[0] - g * e, q = core[1] + g * e;
    return {p + g * nrm, q + g * nrm, q - g * nrm, p - g * nrm};
  }
  std::vector<Vec2> out(n);
  for (int i = 0; i < n; ++i) {
    const Vec2& p = core[(i + n - 1) % n];
    const Vec2& v = core[i];
    const Vec2& q = core[(i + 1) % n];
    const Vec2 e1 = (v - p).normalized(), e2 = (q - v).normalized();
    const Vec2 n1(e1.y(), -e1.x()), n2(e2.y(), -e2.x());
    out[i] = v + g * (n1 + n2) / (1 + n1.dot(n2));
  }
  return out;
}

}  // namespace

std::vector<b2Vec2> box2dPolygon(const Spheropolygon& d, const std::string& name, Real scale) {
  const Real g = d.rounding + box2dReach(scale) - b2_polygonRadius / scale;
  const std::vector<Vec2> grown = grownCore(d.core, g);
  const int n = static_cast<int>(grown.size());
  bool valid = d.core.size() > 2 || g > 0;
  for (int i = 0; i < n; ++i) {
    const Vec2 edge = grown[(i + 1) % n] - grown[i];
    valid = valid && edge.norm() * scale >= b2_linearSlop;
    if (d.core.size() > 2) valid = valid && edge.dot(d.core[(i + 1) % n] - d.core[i]) > 0;
  }
  if (!valid) {
    const std::string skin = std::to_string(b2_polygonRadius / scale - box2dReach(scale));
    throw std::invalid_argument("block '" + name + "': with block_contact box2d its rounding (" +
                                std::to_string(d.rounding) + " m) is below Box2D's skin (" + skin +
                                " m at this scene's length scale) by more than its core " +
                                "can shrink; give it a larger rounding or core, or use the " +
                                "penalty model");
  }
  std::vector<b2Vec2> pts;
  for (const Vec2& v : grown) pts.push_back(toB2(v, scale));
  return pts;
}

}  // namespace mpm_sdem::detail
