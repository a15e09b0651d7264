// Small builders for test worlds (SI units).
#pragma once

#include <cmath>
#include <string>

#include "cases.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::test {

inline MaterialDef elastic(Real density, Real E, Real nu) {
  MaterialDef m;
  m.name = "elastic";
  m.model = MaterialModel::kLinearElastic;
  m.density = density;
  m.bulk_modulus = E / (3 * (1 - 2 * nu));
  m.shear_modulus = E / (2 * (1 + nu));
  return m;
}

inline MaterialDef druckerPrager(Real density, Real E, Real nu, Real phi_deg, Real psi_deg) {
  MaterialDef m = elastic(density, E, nu);
  m.name = "granular";
  m.model = MaterialModel::kDruckerPrager;
  m.friction_angle = phi_deg * M_PI / 180;
  m.dilation_angle = psi_deg * M_PI / 180;
  return m;
}

// A weakly compressible fluid of sound speed c0 (m/s) and viscosity eta (Pa s), Tait gamma 7.
inline MaterialDef fluid(Real density, Real c0, Real eta = 0) {
  MaterialDef m;
  m.name = "fluid";
  m.model = MaterialModel::kFluid;
  m.density = density;
  m.bulk_modulus = density * c0 * c0;
  m.viscosity = eta;
  return m;
}

inline BodyDef rectangle(const Vec2& lo, const Vec2& hi, int ppc, int material = 0) {
  BodyDef b;
  b.name = "rect";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = lo;
  b.shape.max = hi;
  b.points_per_cell = ppc;
  b.material = material;
  return b;
}

inline BodyDef disk(const Vec2& c, Real r, int ppc, int material = 0) {
  BodyDef b = cases::diskBody(c, r, ppc);
  b.material = material;
  return b;
}

inline WorldDef box(const Vec2& lo, const Vec2& hi, Real h) {
  WorldDef d;
  d.domain.min = lo;
  d.domain.max = hi;
  d.cell_size = h;
  return d;
}

// A sand bed 0.4 m x 0.1 m (Drucker-Prager, 30 deg) at 2 cm cells in a 1 m x 0.6 m box: material
// alone, the solver's defaults (USF, IMP).
inline WorldDef smallBed() {
  WorldDef d = box(Vec2(0, 0), Vec2(1, 0.6), 0.02);
  d.materials.push_back(druckerPrager(1800, 1e6, 0.3, 30, 0));
  d.bodies.push_back(rectangle(Vec2(0.3, 0), Vec2(0.7, 0.1), 2));
  return d;
}

inline std::string sourcePath(const std::string& rel) {
  return std::string(MPM_SDEM_SOURCE_DIR) + "/" + rel;
}

}  // namespace mpm_sdem::test
