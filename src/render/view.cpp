#include "mpm_sdem/render/view.hpp"

#include <cmath>
#include <cstdio>

namespace mpm_sdem::render {

namespace {

// Up to the next 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten: round tick labels, and a
// default at most 1.5 times the value it was derived from.
Real roundUp(Real v) {
  const Real decade = std::pow(10.0, std::floor(std::log10(v)));
  for (const Real m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0}) {
    if (m * decade >= v * (1 - 1e-12)) return m * decade;
  }
  return 10 * decade;
}

std::string describe(const char* what, Real v, ColorBy c) {
  char text[96];
  std::snprintf(text, sizeof(text), "%s %g %s", what, v, colorByUnit(c));
  return text;
}

}  // namespace

Real defaultMaxValue(const WorldDef& world, ColorBy c) {
  if (c == ColorBy::kKind) return 1;
  const Vec2 g = world.solver.gravity;
  const Vec2 span = world.domain.max - world.domain.min;
  // g H: the largest drop of potential per unit mass between two corners of the domain, whatever
  // the direction of g (g times the height under vertical gravity).
  const Real gh = std::abs(span.x() * g.x()) + std::abs(span.y() * g.y());
  Real initial = 0;
  for (const BodyDef& b : world.bodies) initial = std::max(initial, b.velocity.norm());
  for (const BlockDef& b : world.blocks) initial = std::max(initial, b.velocity.norm());
  Real speed = std::max(std::sqrt(2 * gh), initial);
  if (!(speed > 0)) speed = 1;
  if (c == ColorBy::kSpeed) return roundUp(speed);
  Real rho = 0;
  for (const MaterialDef& m : world.materials) rho = std::max(rho, m.density);
  if (!(rho > 0)) rho = 1000;  // a world without material: nothing will be coloured anyway
  return roundUp(gh > 0 ? rho * gh : rho * speed * speed);
}

ColorScale chooseScale(const ViewRequest& parameter, const ViewRequest& scene,
                       const WorldDef& world) {
  ColorScale s;
  s.color_by = parameter.color_by.value_or(scene.color_by.value_or(ColorBy::kSpeed));
  if (s.color_by == ColorBy::kKind) {
    s.max_value = 1;
    s.origin = "material points and SPH particles";
  } else if (parameter.max_value) {
    s.max_value = *parameter.max_value;
    s.origin = describe("parameter ~image/max_value", s.max_value, s.color_by);
  } else if (scene.max_value && scene.color_by == s.color_by) {
    s.max_value = *scene.max_value;
    s.origin = describe("scene view.max_value", s.max_value, s.color_by);
  } else {
    s.max_value = defaultMaxValue(world, s.color_by);
    s.origin = describe("the scene's default,", s.max_value, s.color_by);
  }
  return s;
}

}  // namespace mpm_sdem::render
