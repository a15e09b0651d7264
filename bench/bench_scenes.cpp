#include "bench_scenes.hpp"

#include <cmath>

namespace mpm_sdem::bench {

const char* modelName(MaterialModel model) {
  return model == MaterialModel::kLinearElastic ? "linear_elastic" : "drucker_prager";
}

WorldDef columnWorld(long target_particles, MaterialModel model) {
  const int ppc = 2;
  const Real h = 0.01;
  // Column of w x 2w cells holds 2 w^2 ppc^2 points.
  const int w =
      std::max(2, static_cast<int>(std::lround(std::sqrt(target_particles / (2.0 * ppc * ppc)))));
  WorldDef def;
  def.cell_size = h;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(4 * w * h, 2.5 * w * h);
  if (std::abs(std::round(2.5 * w) - 2.5 * w) > 1e-9) def.domain.max.y() = (2.5 * w + 0.5) * h;
  def.domain.bottom.type = WallType::kSticky;
  MaterialDef m;
  m.name = "bench";
  m.model = model;
  m.density = 1500;
  m.bulk_modulus = 1e6;
  m.shear_modulus = 0.5e6;
  m.friction_angle = 30 * M_PI / 180;
  if (model == MaterialModel::kGranular) {  // mu(I) with mu_s at the same 30 degrees
    m.mu_s = std::tan(m.friction_angle);
    m.mu_2 = std::tan(40 * M_PI / 180);
    m.inertial_i0 = 0.279;
    m.grain_diameter = 1e-3;
    m.solid_fraction = 0.6;
  }
  def.materials.push_back(m);
  BodyDef b;
  b.name = "column";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0, 0);
  b.shape.max = Vec2(w * h, 2 * w * h);
  b.points_per_cell = ppc;
  def.bodies.push_back(b);
  return def;
}

}  // namespace mpm_sdem::bench
