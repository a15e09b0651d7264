// The builders every topic of cases.hpp shares (blocks, disks, the elastic disk's material, the
// fit of an acceleration).
#include "cases.hpp"
#include "mpm_sdem/core/stepper.hpp"

#include "mpm_sdem/mesh/mesher.hpp"
#include "mpm_sdem/scene/scene.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cases_common.hpp"

namespace mpm_sdem::cases {

BlockDef boxBlock(const std::string& name, const Vec2& center, Real w, Real h, Real a,
                  BodyType type, Real density) {
  BlockDef b;
  b.name = name;
  b.core = {Vec2(-w / 2 + a, -h / 2 + a), Vec2(w / 2 - a, -h / 2 + a), Vec2(w / 2 - a, h / 2 - a),
            Vec2(-w / 2 + a, h / 2 - a)};
  b.rounding = a;
  b.position = center;
  b.type = type;
  b.density = density;
  return b;
}

BlockDef discRow(const std::string& name, const Vec2& from, const Vec2& to, Real r, Real p,
                 BodyType type) {
  BlockDef b;
  b.name = name;
  const Real length = (to - from).norm();
  const int n = static_cast<int>(std::floor(length / p + 1e-9)) + 1;
  for (int k = 0; k < n; ++k) b.discs.push_back({Vec2(-length / 2 + k * length / (n - 1), 0), r});
  b.position = (from + to) / 2;
  b.angle = std::atan2(to.y() - from.y(), to.x() - from.x());
  b.type = type;
  return b;
}

BodyDef diskBody(const Vec2& center, Real radius, int ppc) {
  BodyDef b;
  b.name = "disk";
  b.shape.type = ShapeType::kDisk;
  b.shape.center = center;
  b.shape.radius = radius;
  b.points_per_cell = ppc;
  return b;
}

std::string exact(Real v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

std::string exact(const Vec2& v) {
  return "[" + exact(v.x()) + ", " + exact(v.y()) + "]";
}

std::string exact(const std::vector<Vec2>& points) {
  std::string out;
  for (const Vec2& v : points) out += (out.empty() ? "[" : ", ") + exact(v);
  return out + "]";
}

WorldDef shippedScene(const std::string& name, const std::vector<std::string>& set) {
  return loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/" + name + ".yaml", set)
      .world;
}

MaterialDef elasticDisk() {
  MaterialDef m;
  m.name = "disk";
  m.density = 1000;
  m.bulk_modulus = 1e7 / (3 * (1 - 2 * 0.3));
  m.shear_modulus = 1e7 / (2 * (1 + 0.3));
  return m;
}

Real fittedAcceleration(const std::vector<Real>& t, const std::vector<Real>& x, Real t0) {
  Eigen::Matrix3d M = Eigen::Matrix3d::Zero();
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < t.size(); ++i) {
    if (t[i] < t0) continue;
    const Eigen::Vector3d f(1, t[i], 0.5 * t[i] * t[i]);
    M += f * f.transpose();
    b += f * x[i];
  }
  return M.ldlt().solve(b)(2);
}

}  // namespace mpm_sdem::cases
