// Builders for test scenes with blocks (SI units).
#pragma once

#include "helpers.hpp"

namespace mpm_sdem::test {

inline BlockDef boxBlock(const std::string& name, const Vec2& center, Real w, Real h, Real a,
                         BodyType type, Real density = 1000) {
  BlockDef b;
  b.name = name;
  b.core = {Vec2(-w / 2 + a, -h / 2 + a), Vec2(w / 2 - a, -h / 2 + a), Vec2(w / 2 - a, h / 2 - a),
            Vec2(-w / 2 + a, h / 2 - a)};  // outer size w x h including the rounding
  b.rounding = a;
  b.position = center;
  b.type = type;
  b.density = density;
  return b;
}

inline BlockDef diskBlock(const std::string& name, const Vec2& center, Real radius, BodyType type,
                          Real density) {
  BlockDef b;
  b.name = name;
  b.core = {Vec2(0, 0)};
  b.rounding = radius;
  b.position = center;
  b.type = type;
  b.density = density;
  return b;
}

// Total IMP force on block b in the last step (N/m).
inline Vec2 couplingForce(const World& w, int b) {
  return w.blocks()->coupling()[b].force;
}

}  // namespace mpm_sdem::test
