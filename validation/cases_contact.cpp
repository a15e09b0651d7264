// Worlds of seed 000's contact cases (sec. 5.1-5.4) and their measures: disk collisions, the
// resting square, the incline, the thrown and dropped disks, the rock into a bed.
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
#include "mpm_sdem/scene/scene.hpp"

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

WorldDef restingSquare(Real h, Real friction, CouplingScheme scheme, Real disc_pitch) {
  const Real side = 0.1, rho = 2500, g = 1.0, a = 0.005;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(std::round(0.6 / h) * h, std::round(0.2 / h) * h);
  def.cell_size = h;
  def.solver.gravity = Vec2(0, -g);
  def.solver.kernel = KernelType::kGimp;
  def.solver.transfer = TransferScheme::kPic;
  MaterialDef m;
  m.name = "square";
  m.density = rho;
  m.bulk_modulus = 6e6;
  m.shear_modulus = 3.5e6;
  def.materials.push_back(m);
  // Top surface at y = 0.05.
  BlockDef floor = disc_pitch > 0
                       ? discRow("floor", Vec2(0.01 + a, 0.05 - a), Vec2(0.59 - a, 0.05 - a), a,
                                 disc_pitch, BodyType::kStatic)
                       : boxBlock("floor", Vec2(0.3, 0.025), 0.58, 0.05, a, BodyType::kStatic);
  floor.friction = friction;
  floor.restitution = 0.5;
  def.blocks.push_back(floor);
  def.coupling.scheme = scheme;
  // The seed's explicit springs: their many short steps are what settles the square (PIC loses a
  // share of the motion per transfer); at the material's own step it rings for longer than 3 s.
  def.coupling.normal_integration = ContactIntegration::kExplicit;
  def.coupling.normal_stiffness = 6e3;
  def.coupling.tangential_stiffness = 3e2;
  def.coupling.contact_radius = 0.001;
  def.coupling.verlet_distance = 0.002;
  // The lowest point row h/4 above the square's base, i.e. r_p + a - (half a point spacing)
  // above the core: just touching.
  const Real y0 = 0.05 + 0.001 - h / 4;
  BodyDef square;
  square.name = "square";
  square.shape.type = ShapeType::kRectangle;
  square.shape.min = Vec2(0.05, y0);
  square.shape.max = Vec2(0.05 + side, y0 + side);
  square.points_per_cell = 2;
  def.bodies.push_back(square);
  return def;
}

RestingForces restingSquareForces(World& w, Real slide_speed) {
  RestingForces out;
  out.weight = measure(w).mass * -w.def().solver.gravity.y();
  int quiet = 0;
  while (quiet < 25 && w.time() < 3.0) {
    const Real until = w.time() + 0.01;
    runUntil(w, until);
    quiet = measure(w).max_speed < 1e-4 ? quiet + 1 : 0;
  }
  out.settled = quiet == 25;
  out.settled_at = w.time();
  if (slide_speed > 0) {
    // Sliding is resisted by friction alone: no damping of the sliding motion.
    Particles& P = w.particles();
    for (std::size_t p = 0; p < P.size(); ++p) P.vx[p] += slide_speed;
  }
  Vec2 sum(0, 0);
  long samples = 0;
  const Real start = w.time() + (slide_speed > 0 ? 0.1 : 0);
  while (w.time() < start + 0.05) {
    stepStable(w);
    if (w.time() > start) {
      sum += w.blocks()->coupling()[0].force;
      ++samples;
    }
  }
  out.mean_force = sum / samples;
  return out;
}

Real inclineAnalytic(Real mu) {
  const Real th = M_PI / 4, g = 9.81;
  return std::tan(th) > 3 * mu ? g * (std::sin(th) - mu * std::cos(th)) : g * std::sin(th) * 2 / 3;
}

Real inclineAcceleration(Real mu, Real h, CouplingScheme scheme, Real segment, Real disc_pitch) {
  const Real th = M_PI / 4, R = 0.05, a = 0.005;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2::Constant(std::round(0.8 / h) * h);
  def.cell_size = h;
  def.solver.kernel = KernelType::kGimp;
  def.materials.push_back(elasticDisk());
  const Vec2 t(std::cos(th), -std::sin(th)), n(std::sin(th), std::cos(th));
  const Vec2 top0(0.05, 0.75);  // a point of the incline's surface
  BlockDef incline =
      boxBlock("incline", top0 + 0.5 * t - 0.025 * n, 1.2, 0.05, a, BodyType::kStatic);
  incline.angle = -th;
  incline.friction = mu;
  if (disc_pitch > 0) {
    // The same face as discs along the line a below the surface, 1.2 m long from 0.1 m above
    // top0 (as the segments).
    const Vec2 from = top0 - 0.1 * t - a * n;
    BlockDef row = discRow("incline", from, from + 1.2 * t, a, disc_pitch, BodyType::kStatic);
    row.friction = mu;
    def.blocks.push_back(row);
  } else if (segment <= 0) {
    def.blocks.push_back(incline);
  } else {
    // Segments swept by the same disk a, end to end along the line a below the surface: their
    // union is the same flat face, now with a joint every `segment`.
    const int count = static_cast<int>(std::round(1.2 / segment));
    for (int k = 0; k < count; ++k) {
      BlockDef piece = incline;
      piece.name = "incline" + std::to_string(k);
      piece.core = {Vec2(-segment / 2, 0), Vec2(segment / 2, 0)};
      piece.position = top0 + (-0.1 + (k + 0.5) * segment) * t - a * n;
      def.blocks.push_back(piece);
    }
  }
  def.coupling.scheme = scheme;
  def.coupling.normal_stiffness = 1e7;
  def.coupling.tangential_stiffness = 5e6;
  // Released half a millimetre above contact: the outermost points sit a quarter cell inside R.
  const Real rp = h / std::sqrt(2.0);
  def.bodies.push_back(diskBody(top0 + 0.15 * t + (R + rp - 0.25 * h + 0.0005) * n, R, 2));
  World w(def);
  std::vector<Real> ts, xs;
  const Real x0 = (measure(w).center_of_mass - top0).dot(t);
  while (w.time() < 0.3) {
    stepStable(w);
    ts.push_back(w.time());
    xs.push_back((measure(w).center_of_mass - top0).dot(t) - x0);
  }
  return fittedAcceleration(ts, xs, 0.05);
}

WorldDef thrownDisk(const ThrownDisk& c) {
  const Real h = c.cell_size, R = 0.05, a = 0.005;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  const Real length = 0.3 + c.v0 * c.t_end;
  def.domain.max = Vec2(std::round(length / h) * h, std::round(0.25 / h) * h);
  def.cell_size = h;
  def.solver.kernel = KernelType::kGimp;
  def.solver.transfer = c.transfer;
  def.materials.push_back(elasticDisk());
  const Real top = 0.05 + c.offset * h;
  BlockDef floor = boxBlock("floor", Vec2(0.5 * def.domain.max.x(), top - 0.025),
                            def.domain.max.x() - 2 * h, 0.05, a, BodyType::kStatic);
  floor.friction = c.mu;
  def.blocks.push_back(floor);
  def.coupling.scheme = c.scheme;
  def.coupling.normal_stiffness = 1e7;
  def.coupling.tangential_stiffness = 5e6;
  // Released 0.1 mm above the floor: it lands at 4 cm/s.
  BodyDef disk = diskBody(Vec2(0.15 + c.offset * h, top + R + 1e-4), R, 2);
  disk.velocity = Vec2(c.v0, 0);
  def.bodies.push_back(disk);
  return def;
}

Rolling rollDisk(World& w, const ThrownDisk& c) {
  if (c.spin) {
    // Rolling from the start: the rigid velocity field of omega = -v0 / R about the centre.
    Particles& P = w.particles();
    const Vec2 centre = measure(w).center_of_mass;
    const Real omega = -c.v0 / 0.05;
    for (std::size_t p = 0; p < P.size(); ++p) {
      P.vx[p] = c.v0 - omega * (P.y[p] - centre.y());
      P.vy[p] = omega * (P.x[p] - centre.x());
    }
  }
  const Particles& P = w.particles();
  std::vector<Real> ts, vs, ws;
  auto sample = [&] {
    Real M = 0;
    Vec2 x(0, 0), v(0, 0);
    for (std::size_t p = 0; p < P.size(); ++p) {
      M += P.mass[p];
      x += P.mass[p] * Vec2(P.x[p], P.y[p]);
      v += P.mass[p] * Vec2(P.vx[p], P.vy[p]);
    }
    x /= M;
    v /= M;
    Real L = 0, I = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Vec2 r = Vec2(P.x[p], P.y[p]) - x, u = Vec2(P.vx[p], P.vy[p]) - v;
      L += P.mass[p] * cross(r, u);
      I += P.mass[p] * r.squaredNorm();
    }
    ts.push_back(w.time());
    vs.push_back(v.x());
    ws.push_back(L / I);
  };
  const Real e0 = measure(w).total();
  Real next = 0;
  while (w.time() < c.t_end) {
    if (w.time() >= next) {
      sample();
      next += 1e-3;
    }
    stepStable(w);
  }
  sample();
  Rolling r;
  auto slope = [&](const std::vector<Real>& y) {  // least squares over the sliding window
    Real n = 0, st = 0, sy = 0, stt = 0, sty = 0;
    for (std::size_t i = 0; i < ts.size(); ++i) {
      if (ts[i] < 0.05 || ts[i] > 0.6) continue;
      n += 1;
      st += ts[i];
      sy += y[i];
      stt += ts[i] * ts[i];
      sty += ts[i] * y[i];
    }
    const Real b = (n * sty - st * sy) / (n * stt - st * st);
    return std::pair<Real, Real>((sy - b * st) / n, b);  // intercept, slope
  };
  Real v_sum = 0, w_sum = 0, n = 0;
  for (std::size_t i = 0; i < ts.size(); ++i) {
    if (ts[i] < c.t_end - 0.15) continue;
    v_sum += vs[i];
    w_sum += ws[i];
    n += 1;
  }
  r.roll_speed = v_sum / n;
  r.roll_ratio = -(w_sum / n) * 0.05 / r.roll_speed;
  if (!c.spin) {
    r.spin_up = -slope(ws).second;
    const auto [v_at_0, dv] = slope(vs);
    r.deceleration = -dv;
    r.roll_start = (v_at_0 - r.roll_speed) / r.deceleration;
  }
  r.energy_change = (measure(w).total() - e0) / e0;
  return r;
}

WorldDef dropDisk(CouplingScheme scheme) {
  const Real R = 0.02, drop = 0.03;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(0.1, 0.12);
  def.cell_size = 0.004;
  def.solver.kernel = KernelType::kGimp;
  MaterialDef m;
  m.name = "disk";
  m.density = 2000;
  m.bulk_modulus = 5e6;  // seed 000 Table 1, hard disk
  m.shear_modulus = 3.7e6;
  def.materials.push_back(m);
  BlockDef floor = boxBlock("floor", Vec2(0.05, 0.01), 0.1, 0.02, 0.02, BodyType::kStatic);
  floor.restitution = 1;
  def.blocks.push_back(floor);
  def.coupling.scheme = scheme;
  def.coupling.normal_stiffness = 6e3;
  def.coupling.tangential_stiffness = 3e2;
  def.coupling.contact_radius = 0.001;
  def.bodies.push_back(diskBody(Vec2(0.05, 0.02 + drop + R), R, 2));
  return def;
}

WorldDef rockIntoBed(CouplingScheme scheme, Real disc_radius) {
  // The shipped scene, under the case's scheme.
  WorldDef def =
      shippedScene("rock_into_bed", {std::string("coupling.scheme=") + couplingSchemeName(scheme)});
  BlockDef& rock = def.blocks.at(0);
  if (disc_radius > 0) {
    rock.discs = fillWithDiscs({rock.core, rock.rounding}, disc_radius, disc_radius);
    rock.core.clear();
  }
  return def;
}

Rebound dropRebound(World& w) {
  Rebound out;
  out.release = out.peak = measure(w).center_of_mass.y();
  Real peak_after = -std::numeric_limits<Real>::infinity(), prev_vy = 0;
  while (w.time() < 0.25) {
    stepStable(w);
    const Diagnostics d = measure(w);
    const Real vy = d.momentum.y() / d.mass;
    if (prev_vy < 0 && vy > 0) out.bounced = true;
    if (out.bounced) peak_after = std::max(peak_after, d.center_of_mass.y());
    prev_vy = vy;
  }
  out.peak = out.bounced ? peak_after : out.peak;
  return out;
}

}  // namespace mpm_sdem::cases
