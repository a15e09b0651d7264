// Builders for test scenes with blocks (SI units).
#pragma once

#include <cstdlib>
#include <string>

#include "cases.hpp"
#include "coupling/imp_coupling.hpp"
#include "helpers.hpp"

namespace mpm_sdem::test {

// Seed 000 Tables 1-3 list k_n = 6e6 and k_t = 3e5 "N/cm". The seed works in cgs (speeds in cm/s,
// g = 100 cm/s^2) and its dt = 1e-4 s is stable only for springs of this order, so these are
// dyn/cm: 6e3 and 3e2 N/m (see test_imp_collision.cpp for the stability argument).
constexpr Real kSeedNormalStiffness = 6e3;      // N/m per metre
constexpr Real kSeedTangentialStiffness = 3e2;  // N/m per metre

// MPM_SDEM_SEED_RESOLUTION=1 runs the seed-resolution versions of the verification tests (for
// the validation report; minutes instead of seconds). CI runs the coarse ones.
inline bool seedResolution() {
  const char* e = std::getenv("MPM_SDEM_SEED_RESOLUTION");
  return e != nullptr && std::string(e) == "1";
}

using cases::boxBlock;

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
