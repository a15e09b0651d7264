// Scenes shared by the kernel benchmarks and the throughput command: a column of material
// collapsing under gravity in a box, sized for a target particle count.
#pragma once

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::bench {

// APIC, quadratic B-spline, USF, 2x2 points per cell, cell 1 cm; the column is twice as tall as
// it is wide and the domain leaves room for it to spread.
WorldDef columnWorld(long target_particles, MaterialModel model);
const char* modelName(MaterialModel model);

}  // namespace mpm_sdem::bench
