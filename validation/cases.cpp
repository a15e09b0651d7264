#include "cases.hpp"

#include <cmath>

namespace mpm_sdem::cases {

WorldDef diskCollision(const DiskCollision& c) {
  const Real R = 0.02, rho = 2000, h = c.cell_size;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(50 * h, 27 * h);
  def.cell_size = h;
  def.solver.gravity = Vec2(0, 0);
  def.solver.kernel = KernelType::kGimp;  // seed 000 uses GIMP for the elastic disks
  def.solver.transfer = TransferScheme::kApic;
  MaterialDef m;
  m.name = "disk";
  m.density = rho;
  m.bulk_modulus = c.bulk_modulus;
  m.shear_modulus = c.shear_modulus;
  def.materials.push_back(m);
  BodyDef disk;
  disk.name = "disk";
  disk.shape.type = ShapeType::kDisk;
  disk.shape.center = Vec2(0.05, 0.04);
  disk.shape.radius = R;
  disk.points_per_cell = c.points_per_cell;
  disk.velocity = Vec2(2, 0);
  def.bodies.push_back(disk);
  BlockDef block;
  block.name = "block";
  block.core = {Vec2(0, 0)};
  block.rounding = R;
  block.position = Vec2(0.05 + 2 * R + 0.004, 0.04);
  block.density = rho;
  block.restitution = 1;  // Table 1 has no contact damping
  block.friction = 0.1;
  def.blocks.push_back(block);
  def.coupling.scheme = c.scheme;
  def.coupling.normal_stiffness = c.normal_stiffness;
  def.coupling.tangential_stiffness = c.tangential_stiffness;
  def.coupling.contact_radius = 0.001;
  def.coupling.verlet_distance = 0.002;
  return def;
}

WorldDef rodCollision(CouplingScheme scheme, Real h, Real& end_of_approach) {
  const Real L1 = 0.04, s = L1 / 400, L2 = 0.01, a = 0.001, v = 0.02, rho = 2000;
  const Real gap = 0.002;
  WorldDef def;
  def.cell_size = h;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(std::ceil((L1 + gap + L2 + 0.04) / h) * h, std::ceil(0.02 / h) * h);
  def.solver.gravity = Vec2(0, 0);
  def.solver.kernel = KernelType::kQuadraticBSpline;
  MaterialDef m;
  m.name = "rod";
  m.density = rho;
  m.bulk_modulus = 5e6;
  m.shear_modulus = 3.7e6;
  def.materials.push_back(m);
  const Real x0 = std::round(0.01 / s) * s;
  const Real y0 = std::round(0.5 * def.domain.max.y() / s) * s;  // a lattice row at y0 + s/2
  BodyDef rod;
  rod.name = "rod";
  rod.shape.type = ShapeType::kRectangle;
  rod.shape.min = Vec2(x0, y0);
  rod.shape.max = Vec2(x0 + L1, y0 + s);
  rod.points_per_cell = static_cast<int>(std::lround(h / s));  // one row of 0.1 mm points
  rod.velocity = Vec2(v, 0);
  def.bodies.push_back(rod);
  // The rod's last points sit s/2 inside its end; the gap is counted from them.
  const Real tip = x0 + L1 - s / 2;
  BlockDef b;
  b.name = "rigid_rod";
  b.core = {Vec2(0, 0), Vec2(L2 - 2 * a, 0)};
  b.rounding = a;
  b.position = Vec2(tip + gap + a, y0 + s / 2);
  b.restitution = 1;
  b.friction = 0.1;
  b.density = rho * L1 * s / spheropolygonMass(b.core, a, 1).mass;  // equal masses
  def.blocks.push_back(b);
  def.coupling.scheme = scheme;
  def.coupling.normal_stiffness = 6e3;
  def.coupling.tangential_stiffness = 3e2;
  def.coupling.contact_radius = 0.001;
  def.coupling.verlet_distance = 0.002;
  end_of_approach = gap / v;
  return def;
}

}  // namespace mpm_sdem::cases
