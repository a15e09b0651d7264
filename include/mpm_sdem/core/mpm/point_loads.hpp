/// \file
/// External forces carried by single material points: the f^ext term of seed 000 eq. 13, for a
/// traction on a surface (seed 001 sec. 5.2) entered as each surface point's share.
#pragma once

#include <vector>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"
#include "mpm_sdem/core/sph/sph.hpp"
#include "mpm_sdem/core/types.hpp"

namespace mpm_sdem {

/// The points' loads, held until set again. Few and rarely used: a list, not a column.
class PointLoads {
 public:
  /// One point's load.
  struct Load {
    int particle = 0;   ///< the point's index
    Vec2 force{0, 0};   ///< N/m
    Vec2 offset{0, 0};  ///< m, from the point to where the force acts
    /// cereal.
    template <class Archive>
    void serialize(Archive& ar) {
      ar(particle, force, offset);
    }
  };
  /// Sets point p's load; a zero force removes it. Throws std::invalid_argument on a point that
  /// is not one of count, or a force or offset not finite.
  void set(int particle, std::size_t count, const Vec2& force, const Vec2& offset);
  ///@{
  /// No load at all; the loads, in the order they were first set.
  bool empty() const { return loads_.empty(); }
  const std::vector<Load>& loads() const { return loads_; }
  ///@}
  /// Spreads each load onto the grid's force with the kernel's weights about the point's
  /// position plus offset; an SPH particle's goes to its acceleration (sph_ax, sph_ay), since the
  /// grid does not move it.
  void spread(KernelType kernel, const Particles& P, Grid& grid, Real* sph_ax, Real* sph_ay) const;
  /// cereal: the list.
  template <class Archive>
  void serialize(Archive& ar) {
    ar(loads_);
  }

 private:
  std::vector<Load> loads_;
};

}  // namespace mpm_sdem
