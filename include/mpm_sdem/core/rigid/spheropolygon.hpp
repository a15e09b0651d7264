/// \file
/// Spheropolygons (seed 000 sec. 3, eq. 37): a convex core polygon swept by a disk of radius a.
/// One core vertex makes a disk, two a capsule (a segment swept by the disk).
#pragma once

#include <string>
#include <vector>

#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

constexpr int kMaxBlockVertices = 8;  ///< Box2D 2.4's b2_maxPolygonVertices

/// A convex core (1 to kMaxBlockVertices vertices) swept by a disk of radius rounding (m).
struct Spheropolygon {
  std::vector<Vec2> core;  ///< counter-clockwise (m)
  Real rounding = 0;       ///< m
};

/// Mass, centroid and moment of inertia of a uniform outline per metre of thickness.
struct MassProperties {
  Real mass = 0;        ///< kg per metre of thickness
  Vec2 centroid{0, 0};  ///< in the frame the vertices are given in (m)
  Real inertia = 0;     ///< about the centroid (kg m^2 per metre)
  Real area = 0;        ///< m^2
};

/// Exact for the Minkowski sum: core polygon, one rectangle of width a on each edge and one
/// circular sector at each vertex (the sectors add up to a full disk).
MassProperties spheropolygonMass(const std::vector<Vec2>& core, Real rounding, Real density);

/// Empty when the core is acceptable for a block: 1 to 8 vertices, finite, a convex
/// counter-clockwise polygon with positive area when there are 3 or more, no repeated vertex.
/// Otherwise a sentence saying what is wrong.
Problem coreProblem(const std::vector<Vec2>& core);

/// Orders a convex polygon counter-clockwise (reverses a clockwise one).
void makeCounterClockwise(std::vector<Vec2>& core);

/// Closest point of the core (its edges, or its vertex) to q, all in one frame. distance is
/// signed: negative when q lies inside a core polygon of 3 or more vertices. normal is the unit
/// vector from the core towards q (the outward edge normal when q is inside).
struct CoreDistance {
  Real distance = 0;  ///< m, signed
  Vec2 point{0, 0};   ///< the closest point of the core (m)
  Vec2 normal{0, 1};  ///< unit, from the core towards q
};
/// The closest point of a core of count vertices to q.
CoreDistance closestOnCore(const Vec2* core, int count, const Vec2& q);

/// The rounded outline of a counter-clockwise core (in the core's frame) as a closed polyline,
/// with arcs of arc_points segments at the vertices; for drawing (rviz markers, images).
std::vector<Vec2> roundedOutline(const std::vector<Vec2>& core, Real rounding, int arc_points);

}  // namespace mpm_sdem
