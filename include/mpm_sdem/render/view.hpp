// What a picture shows and on what colour scale. Two sources ask (the node's ~image parameters,
// the scene's `view` section) and chooseScale decides: a parameter given wins over the scene,
// and what neither gives comes from the scene's size and gravity. The scale is fixed for the
// whole run, so that a colour means the same speed in every frame. Plain types, no OpenCV: the
// scene parser fills a ViewRequest.
#pragma once

#include <optional>
#include <string>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::render {

// kKind: material points blue, SPH particles (seed 001) red.
enum class ColorBy { kSpeed, kPressure, kKind };

// What one source asks for; an empty field is left to the next source. max_value is in the unit
// of the quantity chosen (m/s or Pa). The scene's parser fills in color_by (speed) when a scene
// gives max_value alone, so that a scene's top meant for speeds never colours pressures that a
// parameter asked for.
struct ViewRequest {
  std::optional<ColorBy> color_by;
  std::optional<Real> max_value;
};

struct ColorScale {
  ColorBy color_by = ColorBy::kSpeed;
  Real max_value = 1;  // m/s or Pa at the top of the colour map; 0 and below at the bottom
  std::string origin;  // where max_value came from, for the log
};

inline const char* colorByName(ColorBy c) {
  return c == ColorBy::kSpeed ? "speed" : c == ColorBy::kPressure ? "pressure" : "kind";
}
inline const char* colorByUnit(ColorBy c) {
  return c == ColorBy::kSpeed ? "m/s" : c == ColorBy::kPressure ? "Pa" : "";
}

// "" or why v cannot top a scale of c (limits::kScaleSpeed, kScalePressure; none for kind).
inline Problem maxValueProblem(ColorBy c, Real v) {
  if (c == ColorBy::kKind) return "applies only to color_by speed or pressure";
  return limits::rangeProblem(v,
                              c == ColorBy::kSpeed ? limits::kScaleSpeed : limits::kScalePressure);
}

// The top of the scale when no source gives one, rounded up to 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8
// times a power of ten so that the colour bar's ticks are round. H is the domain's extent along
// gravity g (its height under vertical gravity):
//   speed:    sqrt(2 g H), the speed of a fall through the whole domain, or the fastest initial
//             speed of a body or block if higher; 1 m/s in a scene with neither;
//   pressure: rho g H of the densest material, the weight of a column filling the domain
//             height; rho v^2 with v the speed default above when there is no gravity.
Real defaultMaxValue(const WorldDef& world, ColorBy c);

// color_by: the parameter's, else the scene's, else speed. max_value: the parameter's, else the
// scene's if the scene's color_by is the one chosen, else defaultMaxValue. Does not check the
// value (maxValueProblem).
ColorScale chooseScale(const ViewRequest& parameter, const ViewRequest& scene,
                       const WorldDef& world);

}  // namespace mpm_sdem::render
