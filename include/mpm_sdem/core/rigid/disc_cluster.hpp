/// \file
/// Rigid clusters of discs (seed 003 sec. 2.2 and 4.3: an obstacle of any shape as a rigid
/// arrangement of DEM discs, each disc meeting the others and the material as a disc does). The
/// cluster moves as one body whose mass and inertia are those of the union of its discs.
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// One disc of a cluster: its centre in the block's frame (m) and radius (m).
struct Disc {
  Vec2 centre{0, 0};  ///< m, in the cluster's frame
  Real radius = 0;    ///< m
  template <class Archive>
  void serialize(Archive& ar) {
    ar(centre, radius);
  }
};

/// Area, centroid and inertia about the centroid of the union of the discs at a density
/// (kg/m^3), exact: by Green's theorem, the area integrals of 1, x, y and x^2 + y^2 over the union
/// are line integrals over its boundary, the arcs of each circle that no other disc covers, each
/// integrated in closed form. Overlapping discs count once; touching discs add up.
MassProperties discUnionMass(const std::vector<Disc>& discs, Real density);

/// Discs of radius r on a square lattice of pitch p (p <= 2 r: touching or overlapping, seed
/// 003's "compacted" cluster) that fill a rounded outline: every disc lies inside it, the lattice
/// centred on the outline's bounding box. Empty when not even one disc fits.
std::vector<Disc> fillWithDiscs(const Spheropolygon& outline, Real radius, Real pitch);

/// The most discs a cluster may have.
constexpr int kMaxClusterDiscs = 4096;
/// Empty when the discs make an acceptable cluster: 1 to kMaxClusterDiscs, finite centres, radii
/// positive and finite. Otherwise a sentence saying what is wrong.
Problem discsProblem(const std::vector<Disc>& discs);

}  // namespace mpm_sdem
