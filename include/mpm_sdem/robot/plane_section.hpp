/// @file
/// A robot link's collision solids cut by the simulation plane: the plane-strain slice of a 3D
/// body is its section by that plane (not its projection, which would widen a link that
/// crosses the plane obliquely by all of its depth). No ROS and no URDF types: the robot layer
/// (urdf_obstacles.hpp) turns a description's geometry into these solids.
#pragma once

#include <Eigen/Geometry>
#include <vector>

#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem::robot {

/// One convex collision solid in its own frame (URDF's conventions: a box centred on the
/// origin, a cylinder along z centred on the origin, a sphere at the origin; a mesh's convex
/// hull by its corners), SI.
struct Solid {
  enum class Kind { kBox, kCylinder, kSphere, kConvex };
  Kind kind = Kind::kBox;
  Eigen::Vector3d size{0, 0, 0};         ///< box: full edge lengths (m)
  double radius = 0;                     ///< cylinder and sphere (m)
  double length = 0;                     ///< cylinder, along its z (m)
  std::vector<Eigen::Vector3d> corners;  ///< convex: the hull's corners (m; mesh_hull.hpp)
};

/// The section of a solid by the plane z = 0: a convex polygon (counter-clockwise, in the
/// plane's x, y), or a disc when the solid is a sphere or a cylinder whose axis is normal to the
/// plane. Empty (no polygon, radius 0) when the solid does not reach the plane; `gap` then
/// says how far it stays from it (m).
struct Section {
  std::vector<Vec2> polygon;
  Vec2 centre{0, 0};  ///< a disc's
  double radius = 0;  ///< a disc's; 0 for a polygon
  double gap = 0;
  bool empty() const { return polygon.empty() && radius <= 0; }
};

/// A cylinder's caps as polygons of this many vertices when the plane cuts it obliquely: the
/// section then lies inside the true one by at most r (1 - cos(pi / kCylinderFacets)), 0.12% of
/// the radius.
constexpr int kCylinderFacets = 64;

/// The section by the plane z = 0 of `solid` placed at `pose` (the solid's frame in the plane's
/// frame).
Section sectionByPlane(const Solid& solid, const Eigen::Isometry3d& pose);

/// A section as a block's outline in the frame at `origin` turned by `angle` (rad) in the plane:
/// a disc as a one-vertex core swept by its radius; a polygon shrunk by `rounding` (m; at most a
/// quarter of its smallest width, so thin sections keep a core) and swept by it, so that the
/// outline is the section with its corners rounded. Sets def.core and def.rounding.
void outlineInFrame(const Section& section, const Vec2& origin, double angle, double rounding,
                    BlockDef& def);

}  // namespace mpm_sdem::robot
