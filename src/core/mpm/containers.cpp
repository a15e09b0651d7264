#include <random>

#include "mpm_sdem/core/mpm/grid.hpp"
#include "mpm_sdem/core/mpm/particles.hpp"

namespace mpm_sdem {

void Particles::resize(std::size_t n) {
  const std::size_t old = size();
  forEachColumn([n](auto& column) { column.resize(n, 0); });
  for (std::size_t p = old; p < n; ++p) J[p] = 1;  // a new point is undeformed
}

namespace {

template <class T>
void gather(std::vector<T>& column, const std::vector<int>& order) {
  std::vector<T> scratch(column.size());
  for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = column[order[k]];
  column.swap(scratch);
}

}  // namespace

void Particles::permute(const std::vector<int>& order) {
  forEachColumn([&](auto& column) { gather(column, order); });
}

void perturbPositions(Particles& P, Real amplitude, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(-amplitude, amplitude);
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.x[p] += u(rng);
    P.y[p] += u(rng);
  }
}

void Grid::init(const Vec2& domain_min, int domain_cells_x, int domain_cells_y, Real cell_size) {
  h = cell_size;
  inv_h = 1 / cell_size;
  cells_x = domain_cells_x;
  cells_y = domain_cells_y;
  nx = domain_cells_x + 1 + 2 * kPad;
  ny = domain_cells_y + 1 + 2 * kPad;
  origin = domain_min - Vec2(kPad * h, kPad * h);
  forEachField([this](std::vector<Real>& a) { a.assign(nodeCount(), Real(0)); });
}

void Grid::foldPeriodicX(std::vector<Real>& a) const {
  const int pairs = nx - cells_x;
  for (int j = 0; j < ny; ++j) {
    Real* row = a.data() + static_cast<std::size_t>(j) * nx;
    for (int i = 0; i < pairs; ++i) row[i] = row[i + cells_x] = row[i] + row[i + cells_x];
  }
}

}  // namespace mpm_sdem
