#include "mpm_sdem/core/terrain.hpp"

#include <cmath>
#include <limits>

namespace mpm_sdem {

void heightProfile(const Particles& P, Real x0, Real dx, int columns, std::vector<Real>& height) {
  height.assign(columns, -std::numeric_limits<Real>::infinity());
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Real c = std::floor((P.x[p] - x0) / dx);
    if (!(c >= 0 && c < columns)) continue;  // also NaN positions
    Real& h = height[static_cast<int>(c)];
    h = std::fmax(h, P.y[p] + Real(0.5) * std::sqrt(P.volume0[p] * P.J[p]));
  }
  for (Real& h : height)
    if (std::isinf(h)) h = std::numeric_limits<Real>::quiet_NaN();
}

}  // namespace mpm_sdem
