/// \file
/// The background grid: a dense array of nodes covering the domain plus a margin of ghost nodes
/// wide enough for every kernel's stencil (2 nodes a side). Nodal fields are structure-of-arrays.
#pragma once

#include <cstddef>
#include <vector>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The background grid: node fields as structure of arrays over the domain padded by kPad nodes.
struct Grid {
  static constexpr int kPad = 2;  ///< ghost nodes beyond each domain side

  ///@{
  /// cell size (m) and its inverse
  Real h = 0, inv_h = 0;
  ///@}
  Vec2 origin{0, 0};  ///< position of node (0, 0) (m)
  ///@{
  /// node counts
  int nx = 0, ny = 0;
  ///@}
  ///@{
  /// cells inside the domain
  int cells_x = 0, cells_y = 0;
  ///@}

  std::vector<Real> mass;  ///< kg
  ///@{
  /// momentum (kg m/s)
  std::vector<Real> mom_x, mom_y;
  ///@}
  ///@{
  /// internal force (N)
  std::vector<Real> force_x, force_y;
  ///@}
  ///@{
  /// velocity after the kick (m/s)
  std::vector<Real> vel_x, vel_y;
  ///@}
  ///@{
  /// velocity before the kick (m/s)
  std::vector<Real> vel0_x, vel0_y;
  ///@}

  /// Sizes the arrays for the domain (cells, padded by kPad nodes each side), zeroed.
  void init(const Vec2& domain_min, int domain_cells_x, int domain_cells_y, Real cell_size);
  /// Call f(array) for every nodal array.
  template <class F>
  void forEachField(F&& f) {
    for (auto* a : {&mass, &mom_x, &mom_y, &force_x, &force_y, &vel_x, &vel_y, &vel0_x, &vel0_y})
      f(*a);
  }
  /// The same, read only.
  template <class F>
  void forEachField(F&& f) const {
    const_cast<Grid*>(this)->forEachField([&f](const auto& a) { f(a); });
  }
  ///@{
  /// Nodes in all, and node (i, j)'s index in the arrays.
  std::size_t nodeCount() const { return static_cast<std::size_t>(nx) * ny; }
  int index(int i, int j) const { return i + j * nx; }
  ///@}
  /// Periodic in x, nodes i and i + cells_x are one node: each gets the sum of both in a, an
  /// array over the nodes.
  void foldPeriodicX(std::vector<Real>& a) const;
};

}  // namespace mpm_sdem
