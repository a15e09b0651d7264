// Partitioned MPM-DEM coupling (seed 003, Algorithm 1), weak Gauss-Seidel with one exchange per
// step: (1) the blocks meet a wall of segments through massless boundary particles and get
// their contact forces; (2) the forces at the wall's nodes become point loads on the boundary
// particles (the nodes coincide with them, so the mapping is a copy); (3) the MPM step runs with
// the loads on the grid (eq. 13-14) and moves the boundary particles with the material; (4)
// their new positions and velocities are the wall's for the next step.
//
// As in seed 003's wooden-block case, the boundary particles start on the outline of each body
// of material, `boundary_inset` inside it (the loads then act on the main body of material, not
// on lone outer points), and move with the material like massless material points (with the
// affine velocity field of the nearest point). A segment
// stretched past one cell by the flow is split at its middle, so the wall stays closed as the
// material's surface grows.
#pragma once

#include <array>
#include <vector>

#include "mpm_sdem/core/coupling/coupling.hpp"
#include "mpm_sdem/core/mpm/shapes.hpp"

namespace mpm_sdem {

class PartitionedCoupling final : public Coupling {
 public:
  PartitionedCoupling(const CouplingDef& def, Real cell_size, const std::vector<BodyDef>& bodies);

  void beforeStep(CouplingStep& s) override;
  void addGridForces(CouplingStep& s) override;
  void afterMaterialStep(CouplingStep& s) override;
  CouplingHooks hooks() const override { return {true, true, false, true}; }
  std::string settings() const override;
  void saveState(cereal::BinaryOutputArchive& ar) override;
  void loadState(cereal::BinaryInputArchive& ar) override;

  // The wall: boundary particle positions (m), loads of the last step (N/m, on the material),
  // and segments between them, each with the material on its left.
  const std::vector<Vec2>& boundaryPositions() const { return x_; }
  const std::vector<Vec2>& boundaryLoads() const { return load_; }
  const std::vector<std::array<int, 2>>& segments() const { return segments_; }
  // Sum of the loads the last DEM solve put on the boundary particles (N/m); forceOnMaterial()
  // is the part that reached the grid.
  Vec2 loadSum() const { return load_sum_; }

 private:
  // The boundary particles and their wall (the segment buckets are rebuilt every step).
  template <class Archive>
  void stateIo(Archive& ar) {
    ar(x_, v_, load_, couple_, body_, host_, offset_, segments_, stamp_, longest_, half_size_,
       wall_mass_, load_sum_);
  }
  void contact(ContactBodies& B, int b, const Vec2& n, Real overlap, const Vec2& point,
               const Vec2& wall_velocity, int e0, int e1, Real t);
  void bucketSegments(const Grid& G);
  void attach(const Particles& P);
  // The nearest point of body to x among those binned near it this step, or -1.
  int nearestPoint(const CouplingStep& s, const Vec2& x, int body) const;
  // x relative to point host, zero without a host (-1): a boundary particle's offset.
  static Vec2 offsetFrom(const Particles& P, const Vec2& x, int host);
  // Boundary particle e's host anew (the nearest point) once its offset exceeds a cell.
  void rehost(const CouplingStep& s, std::size_t e);

  Real h_;
  std::vector<Vec2> x_, v_, load_;
  std::vector<Real> couple_;  // each load's moment about its node (N m/m), from the contact point
  std::vector<int> body_;     // the body each boundary particle was placed on
  std::vector<int> host_;     // its nearest point of that body (moves it), or -1
  std::vector<Vec2> offset_;  // from the host (m)
  std::vector<std::array<int, 2>> segments_;
  // Segments by the cell of their middle (counting sort, buffers kept between steps).
  std::vector<int> cell_start_, cell_segments_, segment_cell_, fill_, stamp_;
  int cells_x_ = 0, cells_y_ = 0;
  Real longest_ = 0;       // longest segment (m), for the search
  Real half_size_ = 0.25;  // of the points (cells), for GIMP weights
  Real wall_mass_ = 0;     // mean point mass (kg/m), the wall side of the contact damping
  Vec2 load_sum_{0, 0};
};

}  // namespace mpm_sdem
