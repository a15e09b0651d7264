// Worlds of the cross-solver cases (issue 91): Lagree's mu(I) cases in Basilisk, set up for our
// solver with the same geometry, rheology, grains, floor and walls (cases.hpp explains the
// scaling).
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include "cases.hpp"
#include "cases_common.hpp"
#include "mpm_sdem/core/stepper.hpp"

namespace mpm_sdem::cases {

namespace {
constexpr Real kGravity = 9.81;
}  // namespace

MaterialDef crossSolverGranular(const CrossSolverRheology& r) {
  // The chute's stiff dense continuum (1500 kg/m^3, K 1 MPa, G 0.6 MPa, phi 0.6) with
  // Basilisk's mu(I).
  MaterialDef m = chute(Chute{}).materials.at(0);
  m.name = "grains";
  m.mu_s = r.mu_s;
  m.mu_2 = r.mu_s + r.delta_mu;
  m.inertial_i0 = r.i0;
  // Ours is I = d' gamma_dot / sqrt(p phi / rho); with d' = d sqrt(phi) it is Basilisk's
  // d gamma_dot / sqrt(p / rho), whose rho is the continuum's.
  m.grain_diameter = r.grain * std::sqrt(m.solid_fraction);
  return m;
}

CrossSolverRheology crossChuteRheology(const CrossChute& c) {
  return {0.38, 0.26, 0.3, c.depth / 25};  // bagnold_periodic.c's mu(I) and d
}

WorldDef crossSolverChute(const CrossChute& c) {
  Chute layer;
  layer.theta = c.theta;
  layer.depth = c.depth;
  layer.cell_size = c.cell_size;
  WorldDef def = chute(layer);  // periodic, 10 cells long, sticky base, 2 x 2 points per cell
  def.materials.at(0) = crossSolverGranular(crossChuteRheology(c));
  def.solver.transfer = c.transfer;
  return def;
}

void startOnBagnold(World& w, const CrossChute& c) {
  const MaterialDef& m = w.def().materials.at(0);
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.vx[p] = bagnoldProfile(m, c.theta, c.depth, std::clamp(P.y[p], Real(0), c.depth));
    P.vy[p] = 0;
  }
}

LayerProfile layerProfile(const World& w, Real layer) {
  const Particles& P = w.particles();
  std::vector<Real> u, z, n;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto k = static_cast<std::size_t>(std::max<Real>(0, P.y[p] / layer));
    if (k >= n.size()) u.resize(k + 1, 0), z.resize(k + 1, 0), n.resize(k + 1, 0);
    u[k] += P.vx[p];
    z[k] += P.y[p];
    n[k] += 1;
  }
  LayerProfile out;
  for (std::size_t k = 0; k < n.size(); ++k) {
    if (n[k] == 0) continue;
    out.z.push_back(z[k] / n[k]);
    out.u.push_back(u[k] / n[k]);
  }
  return out;
}

GranularColumn crossColumnShape(const CrossColumn& c) {
  GranularColumn g;
  g.aspect = c.aspect;
  g.length = c.height / c.aspect;
  g.cell_size = c.cell_size;
  g.grain = c.height / c.grain_ratio;
  return g;
}

WorldDef crossSolverColumn(const CrossColumn& c) {
  const GranularColumn shape = crossColumnShape(c);
  WorldDef def = granularColumn(shape);  // sticky floor, smooth back wall, 2 x 2 points per cell
  def.materials.at(0) = crossSolverGranular({0.32, 0.28, 0.4, shape.grain});
  def.solver.transfer = c.transfer;
  return def;
}

Deposit depositThickness(const World& w, Real cell) {
  const Particles& P = w.particles();
  const auto columns = static_cast<std::size_t>(std::ceil(w.def().domain.max.x() / cell)) + 1;
  Deposit d;
  d.thickness.assign(columns, 0);
  for (std::size_t k = 0; k < columns; ++k) d.x.push_back((k + Real(0.5)) * cell);
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto k = static_cast<std::size_t>(std::max<Real>(0, P.x[p] / cell));
    // At most its packed volume: a separated point (J > 1) flies apart with no stress, and its
    // J grows without bound; Basilisk's fluid is incompressible.
    d.thickness[std::min(k, columns - 1)] += P.volume0[p] * std::min<Real>(P.J[p], 1) / cell;
  }
  return d;
}

Real depositFront(const Deposit& d, Real thin) {
  std::size_t k = 0;
  while (k < d.x.size() && d.thickness[k] >= thin) ++k;
  if (k == 0) return d.x.empty() ? 0 : d.x[0];
  if (k == d.x.size()) return d.x.back();
  const Real a = d.thickness[k - 1], b = d.thickness[k];  // a >= thin > b
  return d.x[k - 1] + (d.x[k] - d.x[k - 1]) * (a - thin) / (a - b);
}

Real crossSiloFloor(const CrossSilo& c) {
  return 5 * c.opening;
}

WorldDef crossSolverSilo(const CrossSilo& c) {
  const Real W = c.opening, h = c.cell_size, floor = crossSiloFloor(c);
  const Real thickness = W / 2, rounding = W / 20, width = 10 * W, fill = 4.5 * W;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(std::round(width / h) * h, std::ceil((floor + fill + W) / h) * h);
  def.domain.left.type = def.domain.right.type = WallType::kSticky;  // no-slip sides
  def.domain.bottom.type = WallType::kSlip;  // where the discharge lands, 5 W below the floor
  def.cell_size = h;
  def.solver.gravity = Vec2(0, -kGravity);
  def.solver.transfer = c.transfer;
  def.materials.push_back(crossSolverGranular({c.mu_s, 0.28, 0.4, W / 30}));
  // The floor: two static plates from beyond the walls to the opening's edges. A point meets a
  // block at the contact radius r_p from its surface (seed 000 eq. 45), so the plates stand
  // W + 2 r_p apart for the sand to pass through W (Basilisk's opening), with r_p a quarter cell
  // (as the robot tools').
  def.coupling.contact_radius = h / 4;
  const Real y = floor - thickness / 2, mid = width / 2, half = W / 2 + h / 4;
  for (const auto& [name, from, to] :
       {std::tuple<const char*, Real, Real>{"left_floor", -W, mid - half},
        std::tuple<const char*, Real, Real>{"right_floor", mid + half, width + W}}) {
    BlockDef b = boxBlock(name, Vec2((from + to) / 2, y), to - from, thickness, rounding,
                          BodyType::kStatic, 0);
    b.friction = 1;
    def.blocks.push_back(b);
  }
  BodyDef b;
  b.name = "fill";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0, floor);
  b.shape.max = Vec2(width, floor + fill);
  b.points_per_cell = 2;
  def.bodies.push_back(b);
  return def;
}

Real dischargeRate(World& w, const CrossSilo& c, Real t_from, Real t_to) {
  const MassGauge below{"discharged", MassGauge::Side::kBelow, crossSiloFloor(c) - c.opening / 2};
  LineFit fit;
  for (int k = 1; k <= 100; ++k) {
    runUntil(w, t_to * k / 100);
    if (w.time() >= t_from - 1e-12) fit.add(w.time(), gaugeMass(w.particles(), below));
  }
  return fit.slope() / w.def().materials.at(0).density;
}

}  // namespace mpm_sdem::cases
