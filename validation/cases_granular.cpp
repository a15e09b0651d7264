// Worlds of the granular cases: the silo and Beverloo's law, the granular matrix under a plate
// (seed 000 sec. 7), the chute (Bagnold) and the column collapse (Lube et al.).
#include "cases.hpp"
#include "mpm_sdem/core/mpm/kernels.hpp"
#include "mpm_sdem/core/mpm/materials/drucker_prager.hpp"
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

constexpr Real kSiloPlateTop = 0.25, kSiloLeft = 0.1, kSiloWidth = 0.2;
constexpr Real kSandDensity = 1500, kSiloGravity = 10, kSiloContactRadius = 0.001;

// Seed 000 Table 3's dry sand (Drucker-Prager, no cohesion or tension).
MaterialDef tableThreeSand(const char* name) {
  MaterialDef m;
  m.name = name;
  m.model = MaterialModel::kDruckerPrager;
  m.density = kSandDensity;
  m.bulk_modulus = 5e5;
  m.shear_modulus = 3.2e5;
  m.friction_angle = 35 * M_PI / 180;
  m.dilation_angle = 25 * M_PI / 180;
  // Sand's loosest packing takes about (1 + e_max) / (1 + e_min) = 1.9 / 1.5 = 1.27 times the
  // volume of its densest: beyond that the grains (a falling jet, fines dropping into voids)
  // are apart.
  m.separation_volume_ratio = 1.27;
  return m;
}

}  // namespace

// The glass beads' rate dependence (Jop, Forterre & Pouliquen 2006) that issue 41's sands borrow.
constexpr Real kBeadsMuSpan = 0.261, kBeadsI0 = 0.279, kCriticalSolidFraction = 0.6;

MaterialDef matchedGranular(const MaterialDef& dp, Real grain_diameter) {
  MaterialDef g;
  g.name = dp.name;
  g.model = MaterialModel::kGranular;
  g.density = dp.density;
  g.bulk_modulus = dp.bulk_modulus;
  g.shear_modulus = dp.shear_modulus;
  g.mu_s = std::sin(flowingFrictionAngle(dp.friction_angle));
  g.mu_2 = g.mu_s + kBeadsMuSpan;
  g.inertial_i0 = kBeadsI0;
  g.grain_diameter = grain_diameter;
  g.solid_fraction = kCriticalSolidFraction;
  return g;
}

namespace {

// The shipped silo scene (config/scenes/silo.yaml) with overrides.
WorldDef siloScene(const std::vector<std::string>& set) {
  return shippedScene("silo", set);
}

}  // namespace

MaterialDef siloGranularSand(const char* name) {
  // Table 3's sand dilates, so it flows at no single angle to match (matchedGranular): its 35
  // deg is read as the Mohr-Coulomb angle, mu_s = sin 35 deg.
  MaterialDef sand = siloScene({}).materials.at(0);
  sand.name = name;
  MaterialDef m = matchedGranular(sand, 2 * kSiloContactRadius);
  m.mu_s = std::sin(35 * M_PI / 180);
  m.mu_2 = m.mu_s + kBeadsMuSpan;
  return m;
}

WorldDef silo(Real neck, Real h, int ppc, SiloSand material) {
  // The shipped scene with what the silo cases sweep: the neck, the cell (the domain a whole
  // number of cells) and the points per cell, and the sand.
  const Real a = 0.005, t = 0.02;  // the plates' rounding and thickness (m), as the scene's
  const Real mid = kSiloLeft + kSiloWidth / 2, right = kSiloLeft + kSiloWidth;
  // The plates from inside the walls (their rounded ends hidden in them) to the neck.
  auto plate = [](const std::string& name, const Vec2& lo, const Vec2& hi) {
    return std::vector<std::string>{"blocks." + name + ".position=" + exact(0.5 * (lo + hi)),
                                    "blocks." + name + ".size=" + exact(Vec2(hi - lo))};
  };
  std::vector<std::string> set = {
      "grid.cell_size=" + exact(h),
      "domain.max=" + exact(Vec2(std::round(0.4 / h) * h, std::round(0.5 / h) * h)),
      "bodies.sand.points_per_cell=" + std::to_string(ppc)};
  for (const auto& more : {plate("left_plate", Vec2(kSiloLeft - a, kSiloPlateTop - t),
                                 Vec2(mid - neck / 2, kSiloPlateTop)),
                           plate("right_plate", Vec2(mid + neck / 2, kSiloPlateTop - t),
                                 Vec2(right + a, kSiloPlateTop))})
    set.insert(set.end(), more.begin(), more.end());
  WorldDef def = siloScene(set);
  if (material == SiloSand::kGranular) def.materials.at(0) = siloGranularSand("sand");
  return def;
}

SiloFlow siloFlow(World& w, Real t_max) {
  SiloFlow out;
  const Particles& P = w.particles();
  Real total = 0;
  for (std::size_t p = 0; p < P.size(); ++p) total += P.mass[p];
  // Below the plates' underside (scene output.gauges does the same).
  const MassGauge outlet{"outlet", MassGauge::Side::kBelow, kSiloPlateTop - 0.02};
  auto discharged = [&] { return gaugeMass(P, outlet); };
  Real next = 0;
  while (w.time() < t_max) {
    stepStable(w);
    if (w.time() < next) continue;
    next += 0.01;
    const Real m = discharged();
    out.time.push_back(w.time());
    out.discharged.push_back(m);
    if (m > 0.3 * total) break;
  }
  // Least-squares line through the samples in the window.
  Real n = 0, st = 0, sm = 0, stt = 0, stm = 0;
  for (std::size_t i = 0; i < out.time.size(); ++i) {
    const Real f = out.discharged[i] / total;
    if (f < 0.1 || f > 0.3) continue;
    if (n == 0) out.window_start = out.time[i];
    out.window_end = out.time[i];
    n += 1;
    st += out.time[i];
    sm += out.discharged[i];
    stt += out.time[i] * out.time[i];
    stm += out.time[i] * out.discharged[i];
  }
  if (n >= 5) {
    out.rate = (n * stm - st * sm) / (n * stt - st * st);
    return out;
  }
  out.window_reached = false;
  const std::size_t last = out.time.size() - 1;
  std::size_t first = last;
  while (first > 0 && out.time[last] - out.time[first - 1] <= 1.0 + 1e-9) --first;
  out.window_start = out.time[first];
  out.window_end = out.time[last];
  out.rate = last > first ? (out.discharged[last] - out.discharged[first]) /
                                (out.time[last] - out.time[first])
                          : 0;
  return out;
}

Real beverlooWidth(Real neck) {
  const Real kc = 2.2;
  return std::max<Real>(0, neck - kc * kSiloContactRadius);
}

Real siloDensityRootGravity() {
  return kSandDensity * std::sqrt(kSiloGravity);
}

Real beverloo(Real neck) {
  const Real C = 0.58;
  return C * kSandDensity * std::sqrt(kSiloGravity) * std::pow(beverlooWidth(neck), 1.5);
}

WorldDef granularMatrix(Real fines_content, bool fine, unsigned seed, int& plate) {
  const Real W = 0.3, wall = 0.02, a_wall = 0.005, h = fine ? 0.005 : 0.01;
  const Real x0 = 0.05, y0 = 0.05;  // inner bottom-left corner of the container
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(0.4, 0.5);
  def.cell_size = h;
  def.solver.kernel = KernelType::kGimp;
  const MaterialDef m = tableThreeSand("fines");
  def.materials.push_back(m);
  auto wallBlock = [&](const char* name, const Vec2& lo, const Vec2& hi, BodyType type) {
    BlockDef b = boxBlock(name, 0.5 * (lo + hi), hi.x() - lo.x(), hi.y() - lo.y(), a_wall, type);
    b.friction = 0.2;
    def.blocks.push_back(b);
  };
  wallBlock("floor", Vec2(x0 - wall, y0 - wall), Vec2(x0 + W + wall, y0), BodyType::kStatic);
  wallBlock("left", Vec2(x0 - wall, y0), Vec2(x0, y0 + 0.4), BodyType::kStatic);
  wallBlock("right", Vec2(x0 + W, y0), Vec2(x0 + W + wall, y0 + 0.4), BodyType::kStatic);
  // The pentagons on a jittered lattice of 6 cm pitch.
  std::mt19937 rng(seed);
  std::uniform_real_distribution<Real> u(0, 1);
  const Real a = 0.003, pitch = W / 5;
  Real solids = 0, top = y0;
  for (int j = 0; j < 5; ++j) {
    for (int i = 0; i < 5; ++i) {
      const Real R = 0.020 + 0.008 * u(rng);
      BlockDef b;
      b.name = "pentagon" + std::to_string(5 * j + i);
      const Real turn = 2 * M_PI * u(rng);
      for (int k = 0; k < 5; ++k) {
        const Real th = turn + 2 * M_PI * (k + 0.3 * (u(rng) - 0.5)) / 5;
        b.core.push_back((R - a) * Vec2(std::cos(th), std::sin(th)));
      }
      b.rounding = a;
      const Real slack = 0.5 * pitch - R - 0.001;
      b.position = Vec2(x0 + (i + 0.5) * pitch + slack * (2 * u(rng) - 1),
                        y0 + (j + 0.5) * pitch + slack * (2 * u(rng) - 1));
      b.density = 2200;
      b.friction = 0.2;
      solids += spheropolygonMass(b.core, a, b.density).mass;
      top = std::max(top, b.position.y() + R);
      def.blocks.push_back(b);
    }
  }
  // Fines: the point lattice's squares (side s = h / 2, one point each) clear of every
  // pentagon's reach (rounding plus r_p) and of the walls, picked in random order until their
  // mass is fines_content of the solids'.
  const Real rp = 0.001, s = h / 2, fines_mass = fines_content / (1 - fines_content) * solids;
  std::vector<Vec2> cells;
  for (Real cy = std::ceil((y0 + rp) / s) * s; cy + s <= y0 + W; cy += s) {
    for (Real cx = std::ceil((x0 + rp) / s) * s; cx + s <= x0 + W - rp; cx += s) {
      bool clear = true;
      for (std::size_t k = 3; k < def.blocks.size() && clear; ++k) {
        const BlockDef& b = def.blocks[k];
        const std::vector<Vec2> core = placedParts(b)[0].core;
        const Vec2 cell[4] = {Vec2(cx, cy), Vec2(cx + s, cy), Vec2(cx + s, cy + s),
                              Vec2(cx, cy + s)};
        clear = roundedGap(core.data(), static_cast<int>(core.size()), b.rounding, cell, 4, 0) > rp;
      }
      if (clear) cells.emplace_back(cx, cy);
    }
  }
  std::shuffle(cells.begin(), cells.end(), rng);
  Real filled = 0;
  for (const Vec2& c : cells) {
    if (filled >= fines_mass) break;
    BodyDef body;
    body.name = "fines";
    body.shape.type = ShapeType::kRectangle;
    body.shape.min = c;
    body.shape.max = c + Vec2(s, s);
    body.points_per_cell = 2;
    def.bodies.push_back(body);
    filled += m.density * s * s;
  }
  BlockDef p = boxBlock("plate", Vec2(x0 + W / 2, top + 0.01 + 0.01), W - 0.004, 0.02, a_wall,
                        BodyType::kKinematic);
  p.friction = 0.2;
  plate = static_cast<int>(def.blocks.size());
  def.blocks.push_back(p);
  def.coupling.normal_stiffness = 1e7;  // the default scene's: the plate loads reach 10 kN/m
  def.coupling.tangential_stiffness = 5e6;
  def.coupling.contact_radius = rp;  // Table 3
  def.coupling.verlet_distance = 0.002;
  return def;
}

Compression compressMatrix(World& w, int plate, Real speed, Real max_settlement) {
  Compression out;
  const Blocks& B = *w.blocks();
  for (int i = 0; i < B.count(); ++i)
    if (B.def(i).type == BodyType::kDynamic) out.solids_mass += B.massProperties(i).mass;
  out.fines_mass = measure(w).mass;
  out.solids_mass += out.fines_mass;
  const Real settle = 0.6;
  runUntil(w, settle);
  // The plate brought down to 5 mm above the settled sample, then driven into it.
  Real top = 0;
  for (int i = 0; i < B.count(); ++i) {
    if (B.def(i).type != BodyType::kDynamic) continue;
    for (int s = B.firstShape(i); s < B.firstShape(i) + B.shapesOf(i); ++s)
      top = std::max(top, B.bounds(s).max.y());
  }
  const Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) top = std::max(top, P.y[p]);
  const Real half = 0.5 * (B.coreVertices(plate)[2].y() - B.coreVertices(plate)[0].y());
  w.setBlockPose(B.id(plate), Vec2(B.origin(plate).x(), top + 0.005 + half + B.def(plate).rounding),
                 0);
  w.setBlockVelocity(B.id(plate), Vec2(0, -speed), 0);
  const Real weight = 9.81 * out.solids_mass;
  Real contact_y = std::numeric_limits<Real>::quiet_NaN(), next = 0;
  const Real give_up = w.time() + (0.01 + max_settlement) / speed;
  while (w.time() < give_up) {
    stepStable(w);
    const Real y = B.state(plate).position.y();
    const Real f = B.coupling()[plate].force.y() + B.blockContact(plate).force.y();
    if (std::isnan(contact_y) && f > 0.01 * weight) contact_y = y;
    if (std::isnan(contact_y) || contact_y - y < next) continue;
    next += max_settlement / 100;
    out.settlement.push_back(contact_y - y);
    out.force.push_back(f);
    if (contact_y - y >= max_settlement) break;
  }
  return out;
}

namespace {
constexpr Real kChuteDensity = 1500, kChutePhi = 0.6, kChuteI0 = 0.279;
const Real kChuteMuS = std::tan(20.9 * M_PI / 180), kChuteMu2 = std::tan(32.76 * M_PI / 180);
}  // namespace

WorldDef chute(const Chute& c) {
  const Real h = c.cell_size;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(10 * h, std::ceil(1.6 * c.depth / h) * h);
  def.domain.left.type = def.domain.right.type = WallType::kPeriodic;
  def.domain.bottom.type = WallType::kSticky;
  def.cell_size = h;
  def.solver.gravity = 9.81 * Vec2(std::sin(c.theta), -std::cos(c.theta));
  def.solver.transfer = TransferScheme::kAsflip;
  MaterialDef m;
  m.name = "beads";
  m.model = MaterialModel::kGranular;
  m.density = kChuteDensity;
  m.bulk_modulus = 1e6;
  m.shear_modulus = 6e5;
  m.mu_s = kChuteMuS;
  m.mu_2 = kChuteMu2;
  m.inertial_i0 = kChuteI0;
  m.grain_diameter = c.grain;
  m.solid_fraction = kChutePhi;
  def.materials.push_back(m);
  BodyDef b;
  b.name = "layer";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0, 0);
  b.shape.max = Vec2(10 * h, c.depth);
  b.points_per_cell = 2;
  def.bodies.push_back(b);
  return def;
}

Real bagnoldProfile(const MaterialDef& m, Real theta, Real h, Real z) {
  const Real t = std::tan(theta);
  const Real i = m.inertial_i0 * (t - m.mu_s) / (m.mu_2 - t);
  return Real(2) / 3 * i / m.grain_diameter * std::sqrt(m.solid_fraction * 9.81 * std::cos(theta)) *
         (std::pow(h, Real(1.5)) - std::pow(h - z, Real(1.5)));
}

Real bagnold(const Chute& c, Real h, Real z) {
  return bagnoldProfile(chute(c).materials.at(0), c.theta, h, z);
}

ChuteVolume chuteVolume(const World& w, const Chute& c) {
  const Particles& P = w.particles();
  const Real h = c.cell_size;
  const int nx = static_cast<int>(std::lround(w.def().domain.max.x() / h));  // periodic columns
  const int rows = static_cast<int>(std::lround(w.def().domain.max.y() / h)) + 4;
  std::vector<Real> volume(static_cast<std::size_t>(nx) * rows, 0);  // row j holds node j - 1
  auto node = [&](int i, int j) -> Real& { return volume[(j + 1) * nx + ((i % nx) + nx) % nx]; };
  auto stencil = [&](Real x, Real y, Stencil1D& sx, Stencil1D& sy) {
    QuadraticBSpline::stencil(x / h, 0, sx);
    QuadraticBSpline::stencil(y / h, 0, sy);
  };
  auto spread = [&](Real x, Real y, Real v) {
    Stencil1D sx, sy;
    stencil(x, y, sx, sy);
    for (int j = 0; j < QuadraticBSpline::kSupport; ++j)
      for (int i = 0; i < QuadraticBSpline::kSupport; ++i)
        if (sy.base + j >= -1 && sy.base + j < rows - 1)
          node(sx.base + i, sy.base + j) += v * sx.w[i] * sy.w[j];
  };
  Real top = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const Real v = P.volume0[p] * P.J[p] / (h * h);
    spread(P.x[p], P.y[p], v);
    // The base's mirror image, for every point whose image reaches node -1 (within 1.5 h of it).
    if (P.y[p] < 2.5 * h) spread(P.x[p], -P.y[p], v);
    top = std::max(top, P.y[p]);
  }
  ChuteVolume out;
  out.phi_min = std::numeric_limits<Real>::infinity();
  long counted = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    out.vy_max = std::max(out.vy_max, std::abs(P.vy[p]));
    if (P.J[p] >= 1) ++out.separated;
    if (P.y[p] >= top - 2 * h) continue;
    Stencil1D sx, sy;
    stencil(P.x[p], P.y[p], sx, sy);
    Real phi = 0;
    for (int j = 0; j < QuadraticBSpline::kSupport; ++j)
      for (int i = 0; i < QuadraticBSpline::kSupport; ++i)
        phi += sx.w[i] * sy.w[j] * node(sx.base + i, sy.base + j);
    out.phi_min = std::min(out.phi_min, phi);
    out.phi_max = std::max(out.phi_max, phi);
    out.phi_mean += phi;
    out.j_mean += P.J[p];
    ++counted;
  }
  if (counted > 0) out.phi_mean /= counted, out.j_mean /= counted;
  return out;
}

ChuteProfile chuteProfile(const World& w, const Chute& c) {
  const Particles& P = w.particles();
  Real top = 0;
  for (std::size_t p = 0; p < P.size(); ++p) top = std::max(top, P.y[p]);
  ChuteProfile out;
  out.depth = top + c.cell_size / 4;  // points sit a quarter cell inside the outline
  const int layers = static_cast<int>(std::round(c.depth / c.cell_size));
  std::vector<Real> sum(layers, 0), height(layers, 0), count(layers, 0);
  for (std::size_t p = 0; p < P.size(); ++p) {
    const int k = std::clamp(static_cast<int>(P.y[p] / out.depth * layers), 0, layers - 1);
    sum[k] += P.vx[p];
    height[k] += P.y[p];
    count[k] += 1;
  }
  const MaterialDef& m = w.def().materials.at(0);
  const Real scale = bagnoldProfile(m, c.theta, out.depth, out.depth);
  for (int k = 0; k < layers; ++k) {
    if (count[k] == 0) continue;
    const Real u = sum[k] / count[k];
    const Real ub = bagnoldProfile(m, c.theta, out.depth, height[k] / count[k]);
    out.worst = std::max(out.worst, std::abs(u - ub) / scale);
    if (k == layers - 1) out.surface = u / ub;
  }
  const Grid& g = w.grid();
  Real err = 0, norm = 0;
  for (int j = 0; j < g.ny; ++j)
    for (int i = Grid::kPad; i < Grid::kPad + g.cells_x; ++i) {
      const int k = g.index(i, j);
      if (!(g.mass[k] > 0)) continue;
      const Real z = std::clamp(g.origin.y() + j * g.h, Real(0), c.depth);
      const Real ub = bagnoldProfile(m, c.theta, c.depth, z);
      err += g.mass[k] * (g.vel_x[k] - ub) * (g.vel_x[k] - ub);
      norm += g.mass[k] * ub * ub;
    }
  out.l2 = norm > 0 ? std::sqrt(err / norm) : 0;
  return out;
}

WorldDef granularColumn(const GranularColumn& c) {
  const Real h = c.cell_size, height = c.aspect * c.length;
  // Room for 2.5 times the fit's run-out: 2 + 5 a^(2/3) column lengths.
  const Real length = std::ceil(c.length * (2 + 5 * std::pow(c.aspect, Real(2) / 3)) / h) * h;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(length, std::ceil(height / h + 2) * h);
  def.domain.bottom.type = WallType::kSticky;  // the rough floor; the back wall is smooth
  def.cell_size = h;
  def.solver.gravity = Vec2(0, -9.81);
  def.solver.transfer = TransferScheme::kAsflip;
  def.solver.asflip_relaxation_time = 0.03;  // as config/scenes/debris_impact_granular.yaml
  Chute beads;
  beads.grain = c.grain;
  def.materials = chute(beads).materials;
  if (c.friction_angle > 0) {
    MaterialDef& m = def.materials[0];
    const Real span = std::atan(m.mu_2) - std::atan(m.mu_s);
    m.mu_s = std::tan(c.friction_angle);
    m.mu_2 = std::tan(c.friction_angle + span);
  }
  def.domain.sidewalls.width = c.sidewall_width;
  def.domain.sidewalls.friction = c.sidewall_friction;
  BodyDef b;
  b.name = "column";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0, 0);
  b.shape.max = Vec2(c.length, height);
  b.points_per_cell = 2;
  def.bodies.push_back(b);
  return def;
}

ColumnDeposit collapseColumn(World& w, const GranularColumn& c, Real t_max) {
  ColumnDeposit out;
  const Particles& P = w.particles();
  auto fastest = [&] {
    Real v2 = 0;
    for (std::size_t p = 0; p < P.size(); ++p)
      v2 = std::max(v2, P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p]);
    return std::sqrt(v2);
  };
  // The column needs about sqrt(2 H0 / g) to fall; look for rest only after that.
  Real next_check = std::sqrt(2 * c.aspect * c.length / 9.81);
  while (w.time() < t_max - 1e-12) {
    stepStable(w, t_max);
    if (w.time() >= next_check - 1e-12) {
      next_check += 0.01;
      if (fastest() < 0.01) {
        out.at_rest = true;
        break;
      }
    }
  }
  out.time = w.time();
  out.max_speed = fastest();
  const Real h = c.cell_size;
  std::vector<char> filled(static_cast<std::size_t>(std::ceil(w.def().domain.max.x() / h)) + 1, 0);
  for (std::size_t p = 0; p < P.size(); ++p) {
    filled[static_cast<std::size_t>(P.x[p] / h)] = 1;
    out.farthest = std::max(out.farthest, P.x[p] + h / 4);
    out.height = std::max(out.height, P.y[p] + h / 4);
  }
  std::size_t front = 0;
  while (front < filled.size() && filled[front]) ++front;
  out.runout = front * h;
  return out;
}

Real lubeRunout(Real aspect) {
  if (aspect <= 1.8) return Real(1.2) * aspect;
  if (aspect >= 2.8) return Real(1.9) * std::pow(aspect, Real(2) / 3);
  return std::numeric_limits<Real>::quiet_NaN();  // between the two fits' ranges
}

Real lajeunesseRunout(Real aspect) {
  return aspect < 3 ? Real(1.8) * aspect : Real(2.3) * std::pow(aspect, Real(2) / 3);
}

Real lubeHeight(Real aspect) {
  return aspect < 1.15 ? aspect : std::pow(aspect, Real(0.4));
}

}  // namespace mpm_sdem::cases
