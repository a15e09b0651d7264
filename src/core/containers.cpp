#include "mpm_sdem/core/grid.hpp"
#include "mpm_sdem/core/particles.hpp"

namespace mpm_sdem {

void Particles::resize(std::size_t n) {
  for (auto* v : {&x, &y, &vx, &vy, &bxx, &bxy, &byx, &byy, &sxx, &syy, &sxy, &szz, &lxx, &lxy,
                  &lyx, &lyy, &mass, &volume0, &half_size}) {
    v->resize(n, Real(0));
  }
  J.resize(n, Real(1));  // a new point is undeformed
  material.resize(n, 0);
  body.resize(n, 0);
}

namespace {

template <class T>
void gather(std::vector<T>& column, const std::vector<int>& order, std::vector<T>& scratch) {
  scratch.resize(column.size());
  for (std::size_t k = 0; k < order.size(); ++k) scratch[k] = column[order[k]];
  column.swap(scratch);
}

}  // namespace

void Particles::permute(const std::vector<int>& order) {
  std::vector<Real> real_scratch;
  for (auto* v : {&x,   &y,   &vx,  &vy,  &bxx, &bxy, &byx,  &byy,     &sxx, &syy,
                  &sxy, &szz, &lxx, &lxy, &lyx, &lyy, &mass, &volume0, &J,   &half_size}) {
    gather(*v, order, real_scratch);
  }
  std::vector<std::uint16_t> int_scratch;
  gather(material, order, int_scratch);
  gather(body, order, int_scratch);
}

void Grid::init(const Vec2& domain_min, int domain_cells_x, int domain_cells_y, Real cell_size) {
  h = cell_size;
  inv_h = 1 / cell_size;
  cells_x = domain_cells_x;
  cells_y = domain_cells_y;
  nx = domain_cells_x + 1 + 2 * kPad;
  ny = domain_cells_y + 1 + 2 * kPad;
  origin = domain_min - Vec2(kPad * h, kPad * h);
  for (auto* v : {&mass, &mom_x, &mom_y, &force_x, &force_y, &vel_x, &vel_y, &vel0_x, &vel0_y}) {
    v->assign(nodeCount(), Real(0));
  }
}

}  // namespace mpm_sdem
