/// \file
/// Regions a body of material points is filled from.
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The kind of a ShapeDef.
enum class ShapeType { kRectangle, kPolygon, kDisk };

/// A region of the plane: a rectangle (min, max), a polygon (vertices) or a circle (center,
/// radius).
struct ShapeDef {
  ShapeType type = ShapeType::kRectangle;  ///< which of the fields below apply
  ///@{
  /// rectangle corners (m)
  Vec2 min{0, 0}, max{0, 0};
  ///@}
  std::vector<Vec2> vertices;  ///< polygon, convex or concave, either orientation (m)
  Vec2 center{0, 0};           ///< disk centre (m)
  Real radius = 0;             ///< disk radius (m)
};

/// A body of material: a region filled at points_per_cell^2 points per grid cell, all of one
/// material, moving with a uniform initial velocity.
struct BodyDef {
  std::string name;         ///< as outputs and sph.bodies name it
  ShapeDef shape;           ///< the region filled
  int material = 0;         ///< index into WorldDef::materials
  int points_per_cell = 2;  ///< per direction
  Vec2 velocity{0, 0};      ///< m/s
  /// Start from its own weight at rest (setLayerWeightAsStress) instead of unstressed: a bed
  /// in equilibrium from the first step. Not for fluids.
  bool geostatic = false;
};

/// Whether p lies inside the shape.
bool contains(const ShapeDef& shape, const Vec2& p);
/// The shape's bounding box (m).
void bounds(const ShapeDef& shape, Vec2& lo, Vec2& hi);
/// The polygon's area (m^2), positive when counter-clockwise.
Real signedArea(const std::vector<Vec2>& polygon);
/// True when two non-adjacent edges of the closed polygon cross or touch.
bool selfIntersects(const std::vector<Vec2>& polygon);

/// Distance from p to the outline of the shape (m), for p inside it.
Real outlineDistance(const ShapeDef& shape, const Vec2& p);

/// The points a body is filled with: the centres of the sub-cells of a lattice of spacing
/// cell_size / points_per_cell anchored at the domain corner, kept where they lie inside the shape.
std::vector<Vec2> fillPoints(const ShapeDef& shape, const Vec2& domain_min, Real cell_size,
                             int points_per_cell);

/// Area (m^2), centroid (m) and polar second moment of area about the centroid (m^4).
struct AreaMoments {
  Real area = 0;        ///< m^2
  Vec2 centroid{0, 0};  ///< m
  Real polar = 0;       ///< m^4, about the centroid
};
/// The shape's area moments.
AreaMoments areaMoments(const ShapeDef& shape);

/// The volume (m^2 per metre) each filled point stands for. A lattice samples a disk with a
/// staircase whose area, centroid and moment of inertia depend on where the disk sits on the
/// lattice (10 cells per radius: area within +-0.6%, centroid up to 0.16 mm off, so the disk's
/// spin under friction changed by 1.6% between lattice offsets). For a disk, the points of the
/// outermost layer (less than one spacing deep) get the least-squares change of volume that
/// gives the body the disk's area, centroid and polar moment (the points' own squares counted);
/// the others keep spacing^2. Where that would take a volume beyond half or 1.5 times spacing^2,
/// every point keeps spacing^2. Rectangles and polygons keep spacing^2 (see shapes.cpp).
std::vector<Real> pointVolumes(const ShapeDef& shape, const std::vector<Vec2>& points,
                               Real spacing);

}  // namespace mpm_sdem
