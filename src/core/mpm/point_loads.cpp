#include "mpm_sdem/core/mpm/point_loads.hpp"

#include <algorithm>
#include <stdexcept>

#include "transfer.hpp"

namespace mpm_sdem {

void PointLoads::set(int particle, std::size_t count, const Vec2& force, const Vec2& offset) {
  if (particle < 0 || static_cast<std::size_t>(particle) >= count || !force.allFinite() ||
      !offset.allFinite())
    throw std::invalid_argument("setPointLoad: no such point, or a non-finite force or offset");
  auto it = std::find_if(loads_.begin(), loads_.end(),
                         [particle](const Load& l) { return l.particle == particle; });
  if (it == loads_.end()) {
    if (force.isZero()) return;
    loads_.push_back({particle, force, offset});
  } else if (force.isZero()) {
    loads_.erase(it);
  } else {
    *it = {particle, force, offset};
  }
}

void PointLoads::spread(KernelType kernel, const Particles& P, Grid& grid, Real* sph_ax,
                        Real* sph_ay) const {
  detail::withKernel(kernel, [&](auto k) {
    for (const Load& l : loads_) {
      if (P.kind[l.particle] == kSphParticle) {  // moved by its own acceleration, not the grid
        sph_ax[l.particle] += l.force.x() / P.mass[l.particle];
        sph_ay[l.particle] += l.force.y() / P.mass[l.particle];
        continue;
      }
      const Vec2 at = Vec2(P.x[l.particle], P.y[l.particle]) + l.offset;
      detail::spreadPointLoad<decltype(k)>(grid, at, P.half_size[l.particle], l.force);
    }
  });
}

}  // namespace mpm_sdem
