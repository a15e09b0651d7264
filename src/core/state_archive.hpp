// The archives a checkpoint writes and reads (cereal's binary ones) with what our types need
// to go through them: for checkpoint.cpp, and for the classes that write their own state
// (Coupling::saveState, loadState).
#pragma once

#include <cereal/archives/binary.hpp>
#include <cereal/types/array.hpp>
#include <cereal/types/common.hpp>
#include <cereal/types/string.hpp>
#include <cereal/types/utility.hpp>
#include <cereal/types/vector.hpp>

#include "mpm_sdem/core/types.hpp"

namespace cereal {
template <class Archive>
void serialize(Archive& ar, mpm_sdem::Vec2& v) {
  ar(v.x(), v.y());
}
}  // namespace cereal
