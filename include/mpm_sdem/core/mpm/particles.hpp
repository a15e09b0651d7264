/// \file
/// Material points as structure-of-arrays. The step reads and writes whole columns, so each
/// quantity is one contiguous array; definitions (which body, which material) sit in small
/// integer columns next to them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The material points (and SPH particles) as structure of arrays, one column per quantity.
struct Particles {
  ///@{
  /// position (m)
  std::vector<Real> x, y;
  ///@}
  ///@{
  /// velocity (m/s), staggered half a step (leapfrog)
  std::vector<Real> vx, vy;
  ///@}
  ///@{
  /// APIC affine matrix B_p (m^2/s), seed 000 eq. 31
  std::vector<Real> bxx, bxy, byx, byy;
  ///@}
  ///@{
  /// Cauchy stress (Pa), plane strain
  std::vector<Real> sxx, syy, sxy, szz;
  ///@}
  ///@{
  /// velocity gradient of the last G2P (1/s)
  std::vector<Real> lxx, lxy, lyx, lyy;
  ///@}
  std::vector<Real> mass;       ///< kg per metre of thickness
  std::vector<Real> volume0;    ///< initial area (m^2 per metre of thickness)
  std::vector<Real> J;          ///< volume ratio V / V0
  std::vector<Real> half_size;  ///< GIMP half size l_p (grid units)
  /// Distance from the point to its body's outline when it was filled (m): how far the material
  /// it stands for reaches. It lets a contact see the body's true surface instead of the
  /// lattice's staircase (IMP reach, ImpCoupling).
  std::vector<Real> depth;
  std::vector<std::uint16_t> material;  ///< index into the world's materials
  std::vector<std::uint16_t> body;      ///< index of the body the point was filled from
  /// ParticleKind: updated from the grid (material point) or by the SPH sums (seed 001).
  std::vector<std::uint8_t> kind;
  /// 1 while the point sleeps (SleepDef): it skips the step, at rest, its grid share kept.
  std::vector<std::uint8_t> asleep;

  /// How many points.
  std::size_t size() const { return x.size(); }
  /// Every column to n points (new ones zero, undeformed: J = 1).
  void resize(std::size_t n);
  /// Reorder every column so that new point k is old point order[k] (order is a permutation).
  void permute(const std::vector<int>& order);
  /// Call f(column) for every column, the Real ones first; the one list that resizing,
  /// reordering and the memory report share.
  template <class F>
  void forEachColumn(F&& f) {
    for (auto* c : {&x,   &y,   &vx,  &vy,  &bxx, &bxy,  &byx,     &byy, &sxx,       &syy,  &sxy,
                    &szz, &lxx, &lxy, &lyx, &lyy, &mass, &volume0, &J,   &half_size, &depth})
      f(*c);
    f(material);
    f(body);
    f(kind);
    f(asleep);
  }
  /// The same, read only.
  template <class F>
  void forEachColumn(F&& f) const {
    const_cast<Particles*>(this)->forEachColumn([&f](const auto& c) { f(c); });
  }
};

/// A run of points [begin, end) in storage order (the awake ones while some sleep).
struct PointRun {
  ///@{
  /// Point indices of the run.
  long begin, end;
  ///@}
};

/// Moves every point by an independent uniform draw in [-amplitude, amplitude] (m) along x, then
/// along y, from std::mt19937(seed): the members of an ensemble (chaotic scenes: a converged
/// result is a converged distribution). The same seed gives the same positions on every machine.
void perturbPositions(Particles& P, Real amplitude, unsigned seed);

/// How far point p's material reaches beyond its centre towards a contact: its depth below its
/// body's outline, at most cap (r_p: IMP's eq. 44 and the particle-to-surface gap). The outermost
/// points then reach the body's true surface and no further, and points that reach the surface
/// later (a flow) reach cap.
inline Real materialReach(const Particles& P, std::size_t p, Real cap) {
  return P.depth[p] < cap ? P.depth[p] : cap;
}

}  // namespace mpm_sdem
