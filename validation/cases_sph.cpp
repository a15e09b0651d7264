// Worlds of seed 001's cases: the copper strip and plate, the reversal, Kirsch's hole, the
// biaxial plate, the SPH throughput.
#include "cases.hpp"
#include "mpm_sdem/core/stepper.hpp"

#include "mpm_sdem/mesh/mesher.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "cases_common.hpp"

namespace mpm_sdem::cases {

namespace {

// A strip of copper along x (seed 001 Table 1) with nu = 0: a one-dimensional bar.
WorldDef copperStrip(const Vec2& lo, const Vec2& hi, const Vec2& domain, Real h, int ppc) {
  WorldDef def;
  def.domain.max = domain;
  def.cell_size = h;
  def.solver.gravity = Vec2(0, 0);
  MaterialDef m;
  m.name = "copper";
  m.density = 8790;
  m.bulk_modulus = 128e9 / 3;  // E = 128 GPa, nu = 0: K = E / 3, G = E / 2
  m.shear_modulus = 128e9 / 2;
  def.materials.push_back(m);
  BodyDef bar;
  bar.name = "bar";
  bar.shape.type = ShapeType::kRectangle;
  bar.shape.min = lo;
  bar.shape.max = hi;
  bar.points_per_cell = ppc;
  def.bodies.push_back(bar);
  return def;
}

const Real kCopperWaveSpeed = std::sqrt(128e9 / 8790);  // m/s, sqrt(E / rho)

}  // namespace

SphDef sphBox(const Vec2& lo, const Vec2& hi, SphKernel kernel, Real alpha) {
  SphDef sph;
  ShapeDef box;
  box.type = ShapeType::kRectangle;
  box.min = lo;
  box.max = hi;
  sph.regions.push_back(box);
  sph.kernel = kernel;
  sph.viscosity_alpha = alpha;
  return sph;
}

Reversal reversal(TransferScheme transfer, StressUpdate update, const SphDef& sph) {
  const Real h = 0.01;
  WorldDef def = copperStrip(Vec2(0, 0), Vec2(1, 0.02), Vec2(1, 0.02), h, 2);
  def.sph = sph;
  def.domain.left.type = def.domain.right.type = WallType::kSticky;
  def.solver.transfer = transfer;
  def.solver.pic_fraction = 0;
  def.solver.stress_update = update;
  const Real c = kCopperWaveSpeed, dt = 0.1 * h / c;
  World w(def);
  Particles& P = w.particles();
  std::vector<Real> v0(P.size());
  const Real amp = 0.01 * c;
  for (std::size_t p = 0; p < P.size(); ++p) v0[p] = P.vx[p] = amp * std::sin(10 * M_PI * P.x[p]);
  const Real e0 = measure(w).total();
  for (int n = 0; n < 500; ++n) w.step(dt);
  w.reverseVelocities();
  for (int n = 0; n < 500; ++n) w.step(dt);
  Real worst = 0;
  for (std::size_t p = 0; p < P.size(); ++p) worst = std::fmax(worst, std::abs(P.vx[p] + v0[p]));
  return {worst / amp, measure(w).total() / e0};
}

BarStrain stressBar(Real h, int ppc, Real sigma, Real ramp_transits, Real hold_transits,
                    const SphDef& sph) {
  const Real L = 1, width = h;  // one cell wide, as in the seed's 1D bar
  WorldDef def = copperStrip(Vec2(4 * h, 2 * h), Vec2(4 * h + L, 2 * h + width),
                             Vec2(L + 8 * h, width + 4 * h), h, ppc);
  def.sph = sph;
  def.time_step.cfl = 0.1;  // seed 001 Table 1's Courant factor
  World w(def);
  const Particles& P = w.particles();
  // The traction on each end is shared by the points of the end column (spacing h / ppc).
  const Real spacing = h / ppc, share = sigma * spacing;
  std::vector<int> left, right;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.x[p] < 4 * h + spacing) left.push_back(static_cast<int>(p));
    if (P.x[p] > 4 * h + L - spacing) right.push_back(static_cast<int>(p));
  }
  const Real transit = L / kCopperWaveSpeed;
  const Real ramp = ramp_transits * transit, end = ramp + hold_transits * transit;
  // Gauge length between the end columns' centres, as an extensometer would read it.
  auto gauge = [&P, &left, &right] {
    Real l = 0, r = 0;
    for (int p : left) l += P.x[p];
    for (int p : right) r += P.x[p];
    return r / right.size() - l / left.size();
  };
  const Real gauge0 = gauge();
  auto meanStrain = [&] { return gauge() / gauge0 - 1; };
  BarStrain out;
  Real lo = std::numeric_limits<Real>::infinity(), hi = -lo, sum = 0, weight = 0;
  while (w.time() < end) {
    const Real load = share * std::min<Real>(1, w.time() / ramp);  // compressive: inwards
    for (int p : left) w.setPointLoad(p, Vec2(load, 0), Vec2(-spacing / 2, 0));
    for (int p : right) w.setPointLoad(p, Vec2(-load, 0), Vec2(spacing / 2, 0));
    const Real dt = stepTowards(w.chooseTimeStep().dt, end, w.time());
    w.step(dt);
    if (w.time() > ramp) {
      const Real e = meanStrain();
      sum += e * dt;
      weight += dt;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
    }
  }
  out.mean_strain = sum / weight;
  out.swing = hi - lo;
  out.steps = w.stepCount();
  out.points = P.size();
  return out;
}

namespace {

// A copper plate lo-hi (seed 001 Table 1, nu = 0.3) as one or more bodies in a domain with a
// margin of 4 cells, no gravity, local damping 0.1 (settling to a static state).
WorldDef copperPlate(const Vec2& size, Real h, std::vector<BodyDef> bodies, const SphDef& sph) {
  WorldDef def;
  def.domain.max = size + Vec2(8 * h, 8 * h);
  def.cell_size = h;
  def.solver.gravity = Vec2(0, 0);
  def.solver.damping = 0.1;
  MaterialDef m;
  m.name = "copper";
  m.density = 8790;
  m.bulk_modulus = 128e9 / (3 * (1 - 2 * 0.3));
  m.shear_modulus = 128e9 / (2 * 1.3);
  def.materials.push_back(m);
  def.bodies = std::move(bodies);
  def.sph = sph;
  return def;
}

// Steps w for `transits` P-wave transits of length L with the traction t (Pa, per face: x on
// the left and right faces, y on the bottom and top, positive pulling outwards) ramped over the
// first half on the outer points of the box lo-hi; each face's traction is shared by its outer
// layer of points (spacing s) and acts on the face (World::setPointLoad).
void loadFaces(World& w, const Vec2& lo, const Vec2& hi, Real s, const Vec2& t, Real L,
               Real transits) {
  const Particles& P = w.particles();
  const MaterialParams& m = w.materialParams()[0];
  const Real end = transits * L / std::sqrt(m.modulus_over_density), ramp = 0.5 * end;
  while (w.time() < end) {
    const Real f = s * std::min<Real>(1, w.time() / ramp);
    for (std::size_t p = 0; p < P.size(); ++p) {
      Vec2 force(0, 0), offset(0, 0);
      if (P.x[p] < lo.x() + s) force.x() -= f * t.x(), offset.x() = -s / 2;
      if (P.x[p] > hi.x() - s) force.x() += f * t.x(), offset.x() = s / 2;
      if (P.y[p] < lo.y() + s) force.y() -= f * t.y(), offset.y() = -s / 2;
      if (P.y[p] > hi.y() - s) force.y() += f * t.y(), offset.y() = s / 2;
      if (!force.isZero()) w.setPointLoad(static_cast<int>(p), force, offset);
    }
    stepStable(w, end);
  }
}

}  // namespace

Kirsch kirsch(Real a, Real S, const Vec2& d) {
  // Load S along y, theta from the x axis: the textbook solution for a load along x with
  // cos 2 theta and sin 2 theta negated (the angle measured from the load turns by 90 deg).
  const Real r2 = d.squaredNorm(), q = a * a / r2, q2 = q * q;
  const Real th = std::atan2(d.y(), d.x()), c2 = std::cos(2 * th), s2 = std::sin(2 * th);
  const Real rr = S / 2 * (1 - q) - S / 2 * (1 - 4 * q + 3 * q2) * c2;
  const Real tt = S / 2 * (1 + q) + S / 2 * (1 + 3 * q2) * c2;
  const Real rt = S / 2 * (1 + 2 * q - 3 * q2) * s2;
  const Real c = std::cos(th), s = std::sin(th);
  return {rr * c * c + tt * s * s - 2 * rt * s * c, rr * s * s + tt * c * c + 2 * rt * s * c,
          (rr - tt) * s * c + rt * (c * c - s * s)};
}

PlateHole plateWithHole(Real h, int hole_cells, Real width_over_d, const SphDef& sph,
                        Real transits) {
  const Real a = hole_cells * h, W = std::round(2 * a * width_over_d / h) * h;
  const Vec2 lo(4 * h, 4 * h), hi = lo + Vec2(W, W), c = 0.5 * (lo + hi);
  // Two bodies, the halves above and below the mid line, each notched by half the hole (a
  // 128-gon): the body shapes have no holes, and no lattice point lies on the mid line.
  std::vector<BodyDef> halves(2);
  for (int k = 0; k < 2; ++k) {
    BodyDef& b = halves[k];
    b.name = k == 0 ? "lower" : "upper";
    b.shape.type = ShapeType::kPolygon;
    const Real sgn = k == 0 ? -1 : 1, yedge = k == 0 ? lo.y() : hi.y();
    std::vector<Vec2>& v = b.shape.vertices;
    v.push_back(Vec2(hi.x(), c.y()));
    v.push_back(Vec2(hi.x(), yedge));
    v.push_back(Vec2(lo.x(), yedge));
    v.push_back(Vec2(lo.x(), c.y()));
    for (int i = 0; i <= 64; ++i) {  // the half circle from (xc - a, yc) to (xc + a, yc)
      const Real th = M_PI - M_PI * i / 64;
      v.push_back(c + a * Vec2(std::cos(th), sgn * std::sin(th)));
    }
  }
  World w(copperPlate(Vec2(W, W), h, halves, sph));
  // Kirsch's own traction sigma n on every outer face, so that his solution is the finite
  // plate's exact one (no finite-width correction): each face point carries its share, at the
  // face (World::setPointLoad), ramped over the first half of the run.
  const Real S = 1e6, s = h / 2;  // Pa; point spacing (m)
  const Particles& P = w.particles();
  struct Load {
    int p;
    Vec2 force, offset;
  };
  std::vector<Load> loads;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec2 x(P.x[p], P.y[p]);
    for (const Vec2& n : {Vec2(-1, 0), Vec2(1, 0), Vec2(0, -1), Vec2(0, 1)}) {
      const Real gap = n.x() < 0   ? x.x() - lo.x()
                       : n.x() > 0 ? hi.x() - x.x()
                       : n.y() < 0 ? x.y() - lo.y()
                                   : hi.y() - x.y();
      if (gap > s) continue;
      const Vec2 face = x + n * (s / 2);
      const Kirsch k = kirsch(a, S, face - c);
      loads.push_back({static_cast<int>(p),
                       s * Vec2(k.xx * n.x() + k.xy * n.y(), k.xy * n.x() + k.yy * n.y()),
                       n * (s / 2)});
    }
  }
  const MaterialParams& m = w.materialParams()[0];
  const Real end = transits * W / std::sqrt(m.modulus_over_density), ramp = 0.5 * end;
  std::vector<Vec2> total(P.size(), Vec2::Zero()), offset(P.size(), Vec2::Zero());
  for (const Load& l : loads) {
    total[l.p] += l.force;
    offset[l.p] += l.offset;  // a corner point's load acts at the corner
  }
  while (w.time() < end) {
    const Real f = std::min<Real>(1, w.time() / ramp);
    for (const Load& l : loads) w.setPointLoad(l.p, f * total[l.p], offset[l.p]);
    stepStable(w, end);
  }
  // sigma_yy along the mid line out to 3a against Kirsch at each point; and Kirsch's form
  // 1 + c1 q + c2 q^2 (q = a^2 / r^2) fitted by least squares to the points whose stencil lies
  // inside the material (r > a + 1.5 h), whose value at the edge, 1 + c1 + c2, is the stress
  // concentration they give (Kirsch: 3).
  PlateHole out;
  Real edge_r = std::numeric_limits<Real>::infinity();
  Real s11 = 0, s12 = 0, s22 = 0, b1 = 0, b2 = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec2 d(P.x[p] - c.x(), P.y[p] - c.y());
    if (std::abs(d.y()) > 0.5 * h || std::abs(d.x()) > 3 * a) continue;
    const Real expected = kirsch(a, S, d).yy / S, got = P.syy[p] / S;
    const Real rr = d.norm(), err = std::abs(got / expected - 1);
    out.worst = std::fmax(out.worst, err);
    ++out.points;
    if (P.kind[p] == kSphParticle) ++out.sph_points;
    if (d.x() > 0 && d.y() > 0)
      out.line.push_back({rr / a, got, expected, P.kind[p] == kSphParticle});
    const Real q = a * a / (rr * rr), q2 = q * q, complete = rr > a + 1.5 * h ? 1 : 0;
    s11 += complete * q * q;
    s12 += complete * q * q2;
    s22 += complete * q2 * q2;
    b1 += complete * q * (got - 1);
    b2 += complete * q2 * (got - 1);
    if (rr < edge_r - 1e-9 * a) {
      edge_r = rr;
      out.edge_error = err;
      out.edge = got;
      out.edge_expected = expected;
    } else if (std::abs(rr - edge_r) <= 1e-9 * a) {
      out.edge_error = std::fmax(out.edge_error, err);
    }
  }
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Vec2 d(P.x[p] - c.x(), P.y[p] - c.y());
    if (std::abs(d.y()) > 0.5 * h || std::abs(d.x()) > 3 * a || d.norm() <= a + 1.5 * h) continue;
    out.worst_inside = std::fmax(out.worst_inside, std::abs(P.syy[p] / kirsch(a, S, d).yy - 1));
  }
  std::sort(out.line.begin(), out.line.end(),
            [](const PlateHole::Sample& x, const PlateHole::Sample& y) { return x.r < y.r; });
  const Real det = s11 * s22 - s12 * s12;
  out.fitted_concentration = 1 + (b1 * s22 - b2 * s12) / det + (s11 * b2 - s12 * b1) / det;
  out.steps = w.stepCount();
  out.particles = static_cast<long>(P.size());
  return out;
}

Biaxial biaxial(Real h, const SphDef& sph, Real transits) {
  // A 1 m plate, the traction compressive on all four faces.
  const Real W = 1, sigma = 1e6;
  const Vec2 lo(4 * h, 4 * h), hi = lo + Vec2(W, W), mid = 0.5 * (lo + hi);
  BodyDef b;
  b.name = "plate";
  b.shape.min = lo;
  b.shape.max = hi;
  World w(copperPlate(Vec2(W, W), h, {b}, sph));
  loadFaces(w, lo, hi, h / 2, Vec2(-sigma, -sigma), W, transits);
  // sigma_xx along the horizontal centre line and sigma_yy along the vertical one: the points
  // within half a spacing of each line.
  const Particles& P = w.particles();
  const Real spacing = h / 2;
  Biaxial out;
  Real sum = 0, n = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const bool on_h = std::abs(P.y[p] - mid.y()) < spacing;
    const bool on_v = std::abs(P.x[p] - mid.x()) < spacing;
    for (int axis = 0; axis < 2; ++axis) {
      if (!(axis == 0 ? on_h : on_v)) continue;
      const Real s = -(axis == 0 ? P.sxx[p] : P.syy[p]) / sigma;
      out.worst = std::fmax(out.worst, std::abs(s - 1));
      sum += s;
      n += 1;
      if (P.kind[p] == kSphParticle) ++out.sph_points;
    }
  }
  out.mean = sum / n;
  out.line_points = static_cast<long>(n);
  out.steps = w.stepCount();
  return out;
}

SphDef holeFrame(Real h, int hole_cells, Real width_over_d, Real inner, Real outer) {
  const Real a = hole_cells * h, W = std::round(2 * a * width_over_d / h) * h;
  const Vec2 c = Vec2(4 * h, 4 * h) + 0.5 * Vec2(W, W);
  const Real in = inner * a, out = outer * a;
  SphDef sph = sphBox(c + Vec2(-out, -out), c + Vec2(out, -in), SphKernel::kCubicSpline, 0.5);
  for (const auto& [lo, hi] :
       {std::pair{Vec2(-out, in), Vec2(out, out)}, std::pair{Vec2(-out, -in), Vec2(-in, in)},
        std::pair{Vec2(in, -in), Vec2(out, in)}}) {
    sph.regions.push_back(sph.regions[0]);
    sph.regions.back().min = c + lo;
    sph.regions.back().max = c + hi;
  }
  return sph;
}

Throughput throughput(Real h, bool sph, int steps) {
  BodyDef b;
  b.name = "plate";
  b.shape.min = Vec2(4 * h, 4 * h);
  b.shape.max = b.shape.min + Vec2(1, 1);
  SphDef d;
  if (sph) d.bodies = {0};
  World w(copperPlate(Vec2(1, 1), h, {b}, d));
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) P.vx[p] = 0.1 * std::sin(3 * P.y[p]);  // m/s
  stepStable(w);  // warm-up: binning, first lists
  w.resetProfile();
  const auto t0 = std::chrono::steady_clock::now();
  for (int n = 0; n < steps; ++n) stepStable(w);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  Throughput out;
  out.particles = static_cast<long>(P.size());
  out.particle_steps_per_second = static_cast<double>(P.size()) * steps / wall;
  out.sph_share = w.profile().ownerSeconds(StageOwner::kSph) / w.profile().total();
  out.dt = w.chooseTimeStep().dt;
  return out;
}

}  // namespace mpm_sdem::cases
