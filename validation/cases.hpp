// The seeds' verification cases as world definitions, shared by the tests, the benchmarks and the
// validation report (one definition per case, so that they measure the same thing). Core types
// only.
#pragma once

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::cases {

// Seed 000 sec. 5.1.1 (Table 1): an elastic disk of radius 2 cm at 2 m/s towards an equal free
// rigid disk 4 mm away; no gravity; GIMP, APIC. Stiffnesses in N/m per metre (Table 1 read in
// cgs: 6e3 and 3e2), r_p = 1 mm, V_d = 2 mm, block restitution 1 and friction 0.1.
struct DiskCollision {
  Real bulk_modulus = 5e6;  // Pa (hard disk; the soft one is 5e5)
  Real shear_modulus = 3.7e6;
  Real normal_stiffness = 6e3;
  Real tangential_stiffness = 3e2;
  Real cell_size = 0.004;   // m; the seed's is 3 mm
  int points_per_cell = 2;  // per direction; 6 at the seed's resolution (5,024 points)
  CouplingScheme scheme = CouplingScheme::kImp;
};
WorldDef diskCollision(const DiskCollision& c);

// Seed 000 sec. 5.4 (Fig. 17): a one-dimensional elastic rod of 400 points (4 cm long, one
// 0.1 mm point thick, Table 1's hard material) at 2 cm/s towards a free rigid rod of equal mass
// (a 1 cm capsule of radius 1 mm) 2 mm away; no gravity; cell size h from 1 to 10 mm.
// Quadratic B-spline (with GIMP at these 10 to 100 points per cell the rod went non-finite before
// any contact at three of the sizes). Returns the time at which the free approach would close
// the gap in end_of_approach (s).
WorldDef rodCollision(CouplingScheme scheme, Real cell_size, Real& end_of_approach);

}  // namespace mpm_sdem::cases
