/// \file
/// Domain walls, imposed on the grid velocity of the nodes on and beyond each domain side.
#pragma once

#include <cmath>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// kPeriodic: the left and right sides together (a point leaving one enters by the other; nodes
/// one domain width apart are one node), for a uniform flow in x such as a periodic chute.
enum class WallType { kSticky, kSlip, kFriction, kPeriodic };

/// One side of the domain: its kind of wall and, for a frictional one, its friction.
struct WallDef {
  WallType type = WallType::kSlip;  ///< sticky, slip, frictional or periodic
  Real friction = 0;                ///< Coulomb coefficient, kFriction only
};

/// The flume's side walls, parallel to the simulation plane, of a quasi-2D flow (Jop,
/// Forterre & Pouliquen 2005): a body force of 2 mu_w p / W per unit volume against the material's
/// velocity, p the points' pressure (none in tension). width 0: none (a plane-strain slice).
struct SidewallsDef {
  Real width = 0;     ///< W, the channel's width between the walls (m)
  Real friction = 0;  ///< mu_w, Coulomb coefficient of the material on the walls
};

/// The simulated box and what bounds it (scene section `domain`).
struct DomainDef {
  ///@{
  /// Corners (m); each extent an integer number of cells.
  Vec2 min{0, 0}, max{1, 1};
  ///@}
  ///@{
  /// The four sides' walls.
  WallDef left, right, bottom, top;
  ///@}
  SidewallsDef sidewalls;  ///< the flume's walls parallel to the plane; none by default
};

/// n is the unit normal pointing out of the domain (into the wall). Material moving away from the
/// wall is left alone (it may separate); moving into it, the normal velocity is removed and, for a
/// Coulomb wall, the tangential speed is reduced by friction * |normal velocity removed| without
/// reversing (the impulse form of Coulomb friction on a grid node).
inline void applyWall(const WallDef& wall, Real n_x, Real n_y, Real& v_x, Real& v_y) {
  if (wall.type == WallType::kPeriodic) return;
  if (wall.type == WallType::kSticky) {
    v_x = 0;
    v_y = 0;
    return;
  }
  const Real vn = v_x * n_x + v_y * n_y;
  if (vn <= 0) return;
  Real tx = v_x - vn * n_x, ty = v_y - vn * n_y;
  if (wall.type == WallType::kFriction) {
    const Real vt = std::sqrt(tx * tx + ty * ty);
    const Real scale = vt > wall.friction * vn ? 1 - wall.friction * vn / vt : Real(0);
    tx *= scale;
    ty *= scale;
  }
  v_x = tx;
  v_y = ty;
}

}  // namespace mpm_sdem
