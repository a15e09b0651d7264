// The fuzz targets' world: small enough to build for every input.
#pragma once

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

// A 0.2 m square domain with a bed of material 4 cm deep (80 points): cheap to build per input.
inline WorldDef smallWorld(BlockContactModel model) {
  WorldDef w;
  w.domain.min = Vec2(0, 0);
  w.domain.max = Vec2(0.2, 0.2);
  w.cell_size = 0.02;
  MaterialDef sand;
  sand.name = "sand";
  sand.model = MaterialModel::kDruckerPrager;
  sand.density = 1300;
  sand.bulk_modulus = 4e4;
  sand.shear_modulus = 2e4;
  sand.friction_angle = 0.5;
  w.materials = {sand};
  BodyDef bed;
  bed.name = "bed";
  bed.material = 0;
  bed.shape.type = ShapeType::kRectangle;
  bed.shape.min = Vec2(0, 0);
  bed.shape.max = Vec2(0.2, 0.04);
  w.bodies = {bed};
  w.block_contact.model = model;
  return w;
}

}  // namespace mpm_sdem
