// Partitioned MPM-DEM coupling (seed 003, Algorithm 1), weak Gauss-Seidel with one exchange per
// step: (1) the blocks meet a wall of segments through massless boundary particles and get
// their contact forces; (2) the forces at the wall's nodes become point loads on the boundary
// particles (the nodes coincide with them, so the mapping is a copy); (3) the MPM step runs with
// the loads on the grid (eq. 13-14) and moves the boundary particles with the material; (4)
// their new positions and velocities are the wall's for the next step.
//
// The boundary particles sit on the material's outline, slightly inside it (seed 003: the
// loads then act on the main body of material, not on lone outer points): the contour of the
// nodal volume fraction at 1/2 + S(0) inset / h (S(0) the kernel's weight at a node, so the
// level is `inset` inside a flat surface), by marching squares. Every boundary_interval steps
// the boundary is rebuilt from the outline, so it follows the flow as it deforms; in between
// the particles move with it.
#pragma once

#include <array>
#include <vector>

#include "mpm_sdem/core/coupling.hpp"

namespace mpm_sdem {

class PartitionedCoupling final : public Coupling {
 public:
  PartitionedCoupling(const CouplingDef& def, Real cell_size);

  void beforeStep(CouplingStep& s) override;
  void addGridForces(CouplingStep& s) override;
  void afterMaterialStep(CouplingStep& s) override;
  bool hasSprings() const override { return true; }

  // The wall: boundary particle positions (m), velocities (m/s), loads of the last step (N/m,
  // on the material), and segments between them.
  const std::vector<Vec2>& boundaryPositions() const { return x_; }
  const std::vector<Vec2>& boundaryLoads() const { return load_; }
  const std::vector<std::array<int, 2>>& segments() const { return segments_; }
  // Sum of the loads the last DEM solve put on the boundary particles (N/m); forceOnMaterial()
  // is the part that reached the grid.
  Vec2 loadSum() const { return load_sum_; }

 private:
  void rebuild(const CouplingStep& s);
  void contact(Blocks& B, int b, const Vec2& n, Real overlap, const Vec2& point,
               const Vec2& wall_velocity, int e0, int e1, Real t);

  Real h_;
  std::vector<Vec2> x_, v_, load_;
  std::vector<std::array<int, 2>> segments_;
  std::vector<int> cell_start_, stamp_;  // segments by the cell they were built in
  int cells_x_ = 0, cells_y_ = 0;
  std::vector<Real> volume_, mass_, mom_x_, mom_y_;  // nodal sums for the outline
  std::vector<int> edge_point_;                      // grid edge -> boundary particle
  std::vector<Vec2> x_built_;
  Real drift_ = 0;         // farthest a boundary particle moved since the rebuild (m)
  Real half_size_ = 0.25;  // of the points (cells), for GIMP weights
  Real wall_mass_ = 0;     // mean point mass (kg/m), the wall side of the contact damping
  int since_rebuild_ = -1;
  Vec2 load_sum_{0, 0};
};

}  // namespace mpm_sdem
