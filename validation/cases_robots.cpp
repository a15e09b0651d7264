// Worlds of the robot cases: the driven wheel and the blade against Reece's equation.
#include "cases.hpp"
#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/mpm/initial_stress.hpp"
#include "mpm_sdem/core/mpm/materials/drucker_prager.hpp"
#include "mpm_sdem/core/stepper.hpp"

#include "mpm_sdem/mesh/mesher.hpp"
#include "mpm_sdem/scene/scene.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "cases_common.hpp"

namespace mpm_sdem::cases {

namespace {

int wheelIndex(const std::vector<BlockDef>& blocks) {
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (blocks[i].name == "wheel") return static_cast<int>(i);
  throw std::invalid_argument("the wheel rig needs a block named 'wheel'");
}

}  // namespace

void setWheelRig(WorldDef& def, Real slip, Real load) {
  BlockDef& wheel = def.blocks[wheelIndex(def.blocks)];
  wheel.density *= load / (blockMass(wheel).mass * def.solver.gravity.norm());
  const Real rim_speed = std::abs(wheel.drive.angular_velocity) * wheel.rounding;
  wheel.drive.velocity.x() = (1 - slip) * rim_speed;
}

WheelRun runWheel(World& w, Real t_end) {
  const int wheel = wheelIndex(w.def().blocks);
  const Real radius = w.def().blocks[wheel].rounding;
  const Real spin = w.def().blocks[wheel].drive.angular_velocity;
  Real top = -std::numeric_limits<Real>::infinity();
  for (const BodyDef& b : w.def().bodies)
    if (b.name == "bed") top = b.shape.max.y();
  WheelRun out;
  out.radius = radius;
  Real sum2 = 0;
  int n = 0;
  while (w.time() < t_end - 1e-12) {
    stepStable(w, t_end);
    const Blocks& B = *w.blocks();
    const Real sinkage = top - (B.state(wheel).position.y() - radius);
    out.final_sinkage = sinkage;
    if (w.time() < t_end / 2) continue;
    const Blocks::Load& c = B.coupling()[wheel];
    out.pull += c.force.x();
    sum2 += c.force.x() * c.force.x();
    out.torque -= std::copysign(c.torque, spin);  // the motor's, in the sense of the spin
    out.sinkage += sinkage;
    ++n;
  }
  out.pull /= n;
  out.torque /= n;
  out.sinkage /= n;
  out.pull_spread = std::sqrt(std::fmax(sum2 / n - out.pull * out.pull, Real(0)));
  return out;
}

namespace {

// The shipped blade scene (config/scenes/excavator_blade.yaml) with overrides.
WorldDef bladeScene(const std::vector<std::string>& set) {
  return shippedScene("excavator_blade", set);
}

// The overrides of the blade scene's sand: the case's elasticity and friction angle.
std::vector<std::string> sandSet(const Blade& c) {
  return {"materials.sand.friction_angle=" + exact(c.friction_angle),
          "materials.sand.youngs_modulus=" + exact(c.young_modulus),
          "materials.sand.poisson_ratio=" + exact(c.poisson_ratio)};
}

}  // namespace

MaterialDef bladeSand(const Blade& c) {
  const MaterialDef m = bladeScene(sandSet(c)).materials.at(0);
  // The granular sand flows at the same in-plane angle (bladeFrictionAngle); grains of 1 mm.
  return c.sand == Blade::Sand::kGranular ? matchedGranular(m, 0.001) : m;
}

Real bladeFrictionAngle(const Blade& c) {
  const MaterialDef m = bladeSand(c);
  return m.model == MaterialModel::kGranular ? std::asin(m.mu_s)
                                             : flowingFrictionAngle(m.friction_angle);
}

WorldDef excavatorBlade(const Blade& c) {
  const Real h = c.cell_size, H = c.bed, d = c.depth;
  const Real alpha = c.rake * M_PI / 180;
  const Real t = c.thickness, a = c.rounding;
  const Real face = 0.05;     // x of the blade's front face at the free surface (m)
  const Real top = H + 0.08;  // the blade's upper end (m)
  const Vec2 domain_max(std::round(0.4 / h) * h, std::round((top + 0.04) / h) * h);
  // The blade: a parallelogram core, its lower edge horizontal at a above the cut (the rounded
  // outline's lowest line at H - d), its front edge along u = (-cos alpha, sin alpha) and a
  // normal thickness t - 2a; the outline is that grown by a.
  const Vec2 n(std::sin(alpha), std::cos(alpha));  // outward normal of the front face
  const Real y0 = H - d + a, y1 = top - a, run = (y1 - y0) / std::tan(alpha);
  const Real width = (t - 2 * a) / std::sin(alpha);  // horizontal width of the core
  // The front edge grown by a passes through (face, H): where its core edge starts at y0.
  const Real x_front = face - a * n.x() + (H - y0 - a * n.y()) / std::tan(alpha);
  std::vector<Vec2> core = {Vec2(x_front, y0), Vec2(x_front - run, y1),
                            Vec2(x_front - width - run, y1), Vec2(x_front - width, y0)};
  makeCounterClockwise(core);
  Vec2 centre = Vec2::Zero();
  for (const Vec2& v : core) centre += v / 4;
  for (Vec2& v : core) v -= centre;  // in the blade's frame
  // The layer: full ahead of the blade's grown front edge, cut to H - d behind it.
  auto faceAt = [&](Real y) { return face - (y - H) / std::tan(alpha); };
  const std::vector<Vec2> bed = {
      Vec2(0, 0),         Vec2(domain_max.x(), 0),    Vec2(domain_max.x(), H),
      Vec2(faceAt(H), H), Vec2(faceAt(H - d), H - d), Vec2(0, H - d)};
  // The shipped scene with what the case sweeps: its cell, sand, depth, blade (rake, thickness,
  // rounding, friction, speed), and every point awake (the reference for the scene's sleeping
  // material). Contact disks of half the point spacing, as the scene's (its header says why).
  std::vector<std::string> set = sandSet(c);
  set.insert(
      set.end(),
      {"grid.cell_size=" + exact(h), "domain.max=" + exact(domain_max), "solver.sleep_speed=0",
       "solver.damping=" + exact(c.damping), "bodies.bed.vertices=" + exact(bed),
       "bodies.bed.points_per_cell=" + std::to_string(c.points_per_cell),
       // pushBlade sets the layer's weight as its stress (c.geostatic)
       "bodies.bed.initial_stress=none", "blocks.blade.position=" + exact(centre),
       "blocks.blade.vertices=" + exact(core), "blocks.blade.rounding=" + exact(a),
       "blocks.blade.friction=" + exact(c.friction),
       "blocks.blade.velocity=" + exact(Vec2(c.speed, 0)),
       "coupling.contact_radius=" + exact(0.5 * h / c.points_per_cell)});
  WorldDef def = bladeScene(set);
  def.materials.at(0) = bladeSand(c);
  return def;
}

void layerWeightAsStress(World& w, Real spacing) {
  Particles& P = w.particles();
  setLayerWeightAsStress(P, 0, P.size(), w.def().materials[0], -w.def().solver.gravity.y(), spacing,
                         w.def().domain.min.x());
}

BladePush pushBlade(World& w, const Blade& c, Real travel) {
  BladePush out;
  const auto t0 = std::chrono::steady_clock::now();
  const Blocks& B = *w.blocks();
  out.points = w.particles().size();
  if (c.geostatic) layerWeightAsStress(w, c.cell_size / c.points_per_cell);
  const Real x0 = B.state(0).position.x(), sample = travel / 200;
  Real next = sample, sum_h = 0, sum_v = 0, span = 0;
  while (true) {
    // The commanded speed, eased in over `ramp` as (1 - cos(pi t / ramp)) / 2: a blade started
    // at once sends a compression wave of rho c v into the layer (c = 30 m/s: 2.2 kPa at 5 cm/s,
    // as much as the passive pressure at the edge of a 4 cm cut).
    const Real ease = w.time() < c.ramp ? (1 - std::cos(M_PI * w.time() / c.ramp)) / 2 : 1;
    w.setBlockVelocity(B.id(0), Vec2(c.speed * ease, 0), 0);
    const TimeStepChoice choice = w.chooseTimeStep();
    const Real dt = choice.dt;
    w.step(dt);
    ++out.steps;
    if (choice.limit == StepLimit::kContact) ++out.contact_steps;
    // The force the material put on the blade in this step, weighted by the step.
    sum_h += -B.coupling()[0].force.x() * dt;
    sum_v += B.coupling()[0].force.y() * dt;
    span += dt;
    const Real x = B.state(0).position.x() - x0;
    if (x < next - 1e-12) continue;
    out.displacement.push_back(x);
    out.horizontal.push_back(sum_h / span);
    out.vertical.push_back(sum_v / span);
    sum_h = sum_v = span = 0;
    next += sample;
    if (x >= travel - 1e-12) break;
  }
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

Reece reece(Real alpha, Real phi, Real delta) {
  // Equilibrium of the wedge (weight W = gamma d^2 (cot alpha + cot beta) / 2 per metre; the
  // blade's force P at delta to its normal; the reaction on the failure plane at phi to its
  // normal) gives P = W / (cos(alpha + delta) + sin(alpha + delta) cot(beta + phi)). The soil
  // fails on the plane that needs the least P: N_gamma is minimised over beta, by a scan of
  // 0.01 deg and a golden-section refinement around its best point.
  auto n_gamma = [&](Real beta) {
    const Real den = std::cos(alpha + delta) + std::sin(alpha + delta) / std::tan(beta + phi);
    return den > 0 ? (1 / std::tan(alpha) + 1 / std::tan(beta)) / (2 * den)
                   : std::numeric_limits<Real>::infinity();
  };
  const Real step = 0.01 * M_PI / 180;
  Real best = step;
  for (Real b = step; b < M_PI / 2; b += step)
    if (n_gamma(b) < n_gamma(best)) best = b;
  Real lo = best - step, hi = best + step;
  const Real g = (std::sqrt(5.0) - 1) / 2;
  for (int i = 0; i < 60; ++i) {
    const Real m1 = hi - g * (hi - lo), m2 = lo + g * (hi - lo);
    if (n_gamma(m1) < n_gamma(m2))
      hi = m2;
    else
      lo = m1;
  }
  Reece r;
  r.beta = (lo + hi) / 2;
  r.n_gamma = n_gamma(r.beta);
  r.horizontal = r.n_gamma * std::sin(alpha + delta);
  r.vertical = -r.n_gamma * std::cos(alpha + delta);
  return r;
}

Real reeceHorizontal(const Blade& c) {
  const Real phi = bladeFrictionAngle(c);
  const Reece r = reece(c.rake * M_PI / 180, phi, std::atan(c.friction));
  return bladeSand(c).density * 9.81 * c.depth * c.depth * r.horizontal;
}

Real wedgeRise(const Blade& c) {
  const Real alpha = c.rake * M_PI / 180;
  const Reece r = reece(alpha, bladeFrictionAngle(c), std::atan(c.friction));
  return std::sin(alpha) * std::sin(r.beta) / std::sin(alpha + r.beta);
}

BladeForce bladeForce(const BladePush& p, Real depth, Real from, Real to) {
  BladeForce out;
  std::vector<Real> x, f;
  Real v = 0;
  for (std::size_t i = 0; i < p.displacement.size(); ++i) {
    const Real s = p.displacement[i] / depth;
    if (s < from - 1e-9 || s > to + 1e-9) continue;
    x.push_back(p.displacement[i]);
    f.push_back(p.horizontal[i]);
    v += p.vertical[i];
    out.peak = std::max(out.peak, p.horizontal[i]);
  }
  const Real n = static_cast<Real>(x.size());
  if (n < 3) return out;
  Real mx = 0, mf = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    mx += x[i] / n;
    mf += f[i] / n;
  }
  Real sxx = 0, sxf = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sxx += (x[i] - mx) * (x[i] - mx);
    sxf += (x[i] - mx) * (f[i] - mf);
  }
  out.slope = sxf / sxx;
  out.onset = mf - out.slope * mx;
  out.mean = mf;
  out.vertical = v / n;
  // The samples' scatter about the line is correlated from one sample to the next (the force
  // rises and falls over several of them): the standard errors use the effective number of
  // independent samples n (1 - r) / (1 + r), r the residuals' lag-one autocorrelation.
  std::vector<Real> e(x.size());
  Real see = 0, lag = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    e[i] = f[i] - out.onset - out.slope * x[i];
    see += e[i] * e[i];
    if (i > 0) lag += e[i] * e[i - 1];
  }
  const Real r = see > 0 ? std::clamp<Real>(lag / see, 0, 0.98) : 0;
  const Real n_eff = std::max<Real>(3, n * (1 - r) / (1 + r));
  const Real s2 = see / (n - 2) * (n / n_eff);  // residual variance, per independent sample
  out.onset_error = std::sqrt(s2 * (1 / n + mx * mx / sxx));
  Real sff = 0;
  for (const Real fi : f) sff += (fi - mf) * (fi - mf);
  out.mean_error = std::sqrt(sff / (n - 1) / n_eff);
  return out;
}

Richardson richardson(Real a1, Real a2, Real a3, Real ratio) {
  const Real d1 = a2 - a1, d2 = a3 - a2;
  Richardson out;
  out.change_ratio = d2 / d1;
  if (!(d1 * d2 > 0 && std::abs(d2) < std::abs(d1))) {
    out.order = out.limit = std::numeric_limits<Real>::quiet_NaN();
    return out;
  }
  out.order = std::log(d1 / d2) / std::log(ratio);
  out.limit = a3 + d2 / (std::pow(ratio, out.order) - 1);
  return out;
}

PowerLaw powerLaw(const std::vector<Real>& x, const std::vector<Real>& y,
                  const std::vector<Real>& y_error) {
  Real sw = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Real lx = std::log(x[i]), ly = std::log(y[i]);
    const Real sigma = y_error[i] / y[i];  // error of log y
    const Real w = 1 / (sigma * sigma);
    sw += w;
    sx += w * lx;
    sy += w * ly;
    sxx += w * lx * lx;
    sxy += w * lx * ly;
  }
  const Real det = sw * sxx - sx * sx;
  const Real k = (sw * sxy - sx * sy) / det, a = (sxx * sy - sx * sxy) / det;
  // The errors given, or the scatter about the line where it is larger (chi^2 per degree of
  // freedom above 1).
  Real chi2 = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    const Real r = (std::log(y[i]) - a - k * std::log(x[i])) / (y_error[i] / y[i]);
    chi2 += r * r;
  }
  const Real dof = static_cast<Real>(x.size()) - 2;
  const Real scale = dof > 0 ? std::max<Real>(1, chi2 / dof) : 1;
  return {k, std::sqrt(scale * sw / det)};
}

namespace {

// Where the plate's centre starts: over the layer by its covered depth plus a point's contact
// reach and a millimetre (no contact yet), so far left of the domain's middle that the path's
// middle is there (gamma > 0), or 1.5 L left of it (gamma = 0, dragged 3 L).
// The IMP contact disks' radius: half the point spacing, so that a face's points cover it edge
// to edge and reach no further (as the blade's, excavatorBlade).
Real plateContactRadius(const Plate& c) {
  return 0.5 * c.cell_size / c.points_per_cell;
}

Vec2 plateStart(const Plate& c) {
  const Real lift = plateCovered(c) + plateContactRadius(c) + 0.001;
  const Real gamma = c.direction * M_PI / 180;
  const Real run = c.direction > 0 ? (c.reach + lift) / std::tan(gamma) : 3 * c.length;
  return Vec2(0.5 * c.width - 0.5 * run, c.bed + lift);
}

}  // namespace

Real plateCovered(const Plate& c) {
  return 0.5 * c.length * std::fabs(std::sin(c.angle * M_PI / 180)) + 0.5 * c.thickness;
}

WorldDef plateIntrusion(const Plate& c) {
  const Real h = c.cell_size;
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(std::round(c.width / h) * h, std::round((c.bed + c.length + 0.05) / h) * h);
  def.domain.bottom.type = WallType::kSticky;
  def.cell_size = h;
  def.solver.gravity = Vec2(0, -c.gravity);
  def.solver.transfer = c.transfer;
  def.solver.sleep.speed = c.sleep_speed;
  def.solver.stress_update = c.stress_update;
  def.solver.kernel = c.kernel;
  def.solver.volumetric_average = c.volumetric_average;
  def.time_step.cfl *= c.step_scale;
  def.time_step.contact_factor *= c.step_scale;
  Blade sand;  // the blade's sand
  sand.friction_angle = c.friction_angle;
  def.materials.push_back(bladeSand(sand));
  def.materials.back().cohesion = c.cohesion;
  def.materials.back().separation_volume_ratio = c.separation;
  // A kinematic block's mass is not used.
  BlockDef plate = boxBlock("plate", plateStart(c), c.length, c.thickness, c.rounding,
                            BodyType::kKinematic, 7850);
  plate.angle = c.angle * M_PI / 180;
  plate.friction = c.friction;
  plate.restitution = c.restitution;
  def.blocks.push_back(plate);
  BodyDef bed;
  bed.name = "bed";
  bed.shape.type = ShapeType::kRectangle;
  bed.shape.min = Vec2(0, 0);
  bed.shape.max = Vec2(def.domain.max.x(), c.bed);
  if (!c.wake && c.direction == 0) {
    // The layer less a trench behind the plate's start, from its trailing face down to its
    // lower edge.
    const Vec2 start = plateStart(c);
    const Real half_width =  // the plate's half extent along x
        0.5 * c.length * std::fabs(std::cos(c.angle * M_PI / 180)) + 0.5 * c.thickness;
    const Real trail = start.x() - half_width - plateContactRadius(c);
    const Real floor = c.bed - c.depth - plateCovered(c);
    bed.shape.type = ShapeType::kPolygon;
    bed.shape.vertices = {Vec2(0, 0),         Vec2(bed.shape.max.x(), 0), bed.shape.max,
                          Vec2(trail, c.bed), Vec2(trail, floor),         Vec2(0, floor)};
  }
  bed.points_per_cell = c.points_per_cell;
  def.bodies.push_back(bed);
  // The blade's contact (excavatorBlade): springs per metre of contact.
  def.coupling.scheme = c.scheme;
  if (schemeTraits(c.scheme).springs) def.coupling.stiffness_per = SpringBasis::kPerLength;
  def.coupling.contact_radius = plateContactRadius(c);
  def.coupling.normal_stiffness = 5e7;
  def.coupling.tangential_stiffness = 2.5e7;
  return def;
}

namespace {

// The plate as text: what a checkpoint records and a resume compares (every field, every digit).
std::string plateText(const Plate& c) {
  std::ostringstream o;
  o.precision(17);
  o << "plate angle " << c.angle << " direction " << c.direction << " speed " << c.speed
    << " depth " << c.depth << " reach " << c.reach << " length " << c.length << " thickness "
    << c.thickness << " rounding " << c.rounding << " friction " << c.friction << " cell "
    << c.cell_size << " bed " << c.bed << " width " << c.width << " friction_angle "
    << c.friction_angle << " gravity " << c.gravity << " transfer " << static_cast<int>(c.transfer);
  if (c.cohesion > 0) o << " cohesion " << c.cohesion;
  if (c.separation > 0) o << " separation " << c.separation;
  if (c.sleep_speed > 0) o << " sleep " << c.sleep_speed;
  if (c.stress_update == StressUpdate::kUsl) o << " usl";
  if (c.kernel != KernelType::kQuadraticBSpline) o << " kernel " << static_cast<int>(c.kernel);
  if (c.points_per_cell != 2) o << " points_per_cell " << c.points_per_cell;
  if (c.scheme != CouplingScheme::kImp) o << " scheme " << couplingSchemeName(c.scheme);
  if (!c.wake) o << " no wake";
  if (c.volumetric_average) o << " volumetric average";
  if (c.step_scale != 1) o << " step scale " << c.step_scale;
  if (c.restitution != BlockDef{}.restitution) o << " restitution " << c.restitution;
  return o.str();
}

constexpr Real kPlateSample = 0.001;  // m of the plate's motion between two samples

// movePlate's own state between two steps, beside the world's.
struct PlateLoop {
  PlateRun out;
  Real next = kPlateSample, sum_x = 0, sum_z = 0, span = 0;  // the sample being summed
  bool descended = false;
  Vec2 from = Vec2(0, 0);  // where the sampled motion began
  double seconds = 0;      // wall time of the parts before this one
};

constexpr const char* kPlateMagic = "mpm_sdem plate run 1";

// The run's progress as text (17 digits: read back exactly), then the world's checkpoint; written
// beside the file and renamed over it, so that a kill leaves the old file or the new one.
void savePlate(World& w, const Plate& c, const PlateLoop& s, const std::string& path) {
  std::ostringstream o;
  o.precision(17);
  o << kPlateMagic << '\n'
    << s.out.steps << ' ' << s.seconds << ' ' << s.next << ' ' << s.sum_x << ' ' << s.sum_z << ' '
    << s.span << ' ' << s.descended << ' ' << s.from.x() << ' ' << s.from.y() << '\n'
    << s.out.travel.size() << '\n';
  for (std::size_t k = 0; k < s.out.travel.size(); ++k)
    o << s.out.travel[k] << ' ' << s.out.depth[k] << ' ' << s.out.fx[k] << ' ' << s.out.fz[k]
      << '\n';
  const std::string world = saveCheckpoint(w, plateText(c));
  o << "world " << world.size() << '\n' << world;
  const std::string part = path + ".part";
  {
    std::ofstream f(part, std::ios::binary | std::ios::trunc);
    f << o.str();
    if (!f.flush()) throw std::runtime_error("cannot write the checkpoint " + part);
  }
  std::filesystem::rename(part, path);
}

// The checkpoint at path into w and s. False, with the reason on stderr, when there is none or it
// was written by another build or for another plate: the run then starts over.
bool loadPlate(World& w, const Plate& c, PlateLoop& s, const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  auto refuse = [&](const std::string& why) {
    std::fprintf(stderr, "%s: %s; starting the run over\n", path.c_str(), why.c_str());
    return false;
  };
  std::string magic, word;
  std::getline(in, magic);
  if (magic != kPlateMagic) return refuse("not a plate run's checkpoint");
  std::size_t samples = 0, bytes = 0;
  in >> s.out.steps >> s.seconds >> s.next >> s.sum_x >> s.sum_z >> s.span >> s.descended;
  Real fx = 0, fy = 0;
  in >> fx >> fy >> samples;
  s.from = Vec2(fx, fy);
  if (!in || samples > (1u << 24)) return refuse("damaged progress");
  s.out.travel.resize(samples), s.out.depth.resize(samples);
  s.out.fx.resize(samples), s.out.fz.resize(samples);
  for (std::size_t k = 0; k < samples; ++k)
    in >> s.out.travel[k] >> s.out.depth[k] >> s.out.fx[k] >> s.out.fz[k];
  in >> word >> bytes;
  in.get();  // the newline before the world's bytes
  std::string world(bytes, '\0');
  in.read(world.data(), static_cast<std::streamsize>(bytes));
  if (!in || word != "world") return refuse("damaged progress");
  CheckpointHeader h;
  try {
    h = readCheckpointHeader(world);
  } catch (const CheckpointError& e) {
    return refuse(e.what());
  }
  const std::string other = buildDifference(h.build, buildId());
  if (!other.empty()) return refuse("written by another build: " + other);
  if (h.scene != plateText(c)) return refuse("written for another plate (" + h.scene + ")");
  if (h.steps != s.out.steps) return refuse("its progress and world disagree");
  restoreCheckpoint(w, world);  // same build, same plate, checksum good: a throw here is fatal
  s.out.resumed_from = s.out.steps;
  std::fprintf(stderr, "%s: continuing from step %ld (t = %.6f s)\n", path.c_str(), s.out.steps,
               h.time);
  return true;
}

}  // namespace

PlateRun movePlate(World& w, const Plate& c, const PlateCheckpoints& k) {
  using Clock = std::chrono::steady_clock;
  const auto t0 = Clock::now();
  auto last = t0;
  const Blocks& B = *w.blocks();
  PlateLoop s;
  const bool resumed = !k.path.empty() && loadPlate(w, c, s, k.path);
  if (!resumed) {
    s = PlateLoop{};
    layerWeightAsStress(w, 0.5 * c.cell_size);
    s.from = B.state(0).position;
  }
  PlateRun& out = s.out;
  out.points = w.particles().size();
  const Real gamma = c.direction * M_PI / 180;
  const Vec2 along = c.direction > 0 ? Vec2(std::cos(gamma), -std::sin(gamma)) : Vec2(1, 0);
  const bool drag = c.direction <= 0;
  if (!resumed) s.descended = !drag;
  auto wall = [&] { return s.seconds + std::chrono::duration<double>(Clock::now() - t0).count(); };
  while (true) {
    // Between two steps the loop's state is whole: where a checkpoint is taken.
    if (!k.path.empty()) {
      const bool stop = out.steps == k.stop_at_step && out.steps != out.resumed_from;
      if (stop || std::chrono::duration<double>(Clock::now() - last).count() >= k.every) {
        PlateLoop copy = s;
        copy.seconds = wall();
        savePlate(w, c, copy, k.path);
        last = Clock::now();
        if (stop) {
          out.seconds = wall();
          out.finished = false;
          return out;
        }
      }
    }
    const Vec2 x = B.state(0).position;
    const Real depth = c.bed - x.y();
    if (!s.descended && depth >= c.depth - 1e-12) {  // at the drag's depth: along +x from here
      s.descended = true;
      s.from = x;
      s.sum_x = s.sum_z = s.span = 0;
    }
    const Vec2 velocity = c.speed * (s.descended ? along : Vec2(0, -1));
    // The last step of the descent lands on the depth exactly.
    const TimeStepChoice choice = w.chooseTimeStep();
    Real dt = choice.dt;
    if (!s.descended) dt = std::min(dt, (c.depth - depth) / c.speed);
    w.setBlockVelocity(B.id(0), velocity, 0);
    w.step(dt);
    ++out.steps;
    if (!s.descended) continue;
    s.sum_x += B.coupling()[0].force.x() * dt;
    s.sum_z += B.coupling()[0].force.y() * dt;
    s.span += dt;
    const Real travelled = (B.state(0).position - s.from).norm();
    if (travelled < s.next - 1e-12) continue;
    out.travel.push_back(travelled);
    out.depth.push_back(c.bed - B.state(0).position.y());
    out.fx.push_back(s.sum_x / s.span);
    out.fz.push_back(s.sum_z / s.span);
    s.sum_x = s.sum_z = s.span = 0;
    s.next += kPlateSample;
    if (drag ? travelled >= 3 * c.length - 1e-12 : out.depth.back() >= c.reach - 1e-12) break;
  }
  out.seconds = wall();
  if (!k.path.empty()) {
    std::filesystem::remove(k.path);
    std::filesystem::remove(k.path + ".part");  // a write a kill cut short
  }
  return out;
}

Real pushWindowStart(const Plate& c) {
  return plateCovered(c) + 0.01;
}

PlateLines pushLines(const Plate& c, const PlateRun& p) {
  LineFit x, z, log_f;
  for (std::size_t k = 0; k < p.depth.size(); ++k) {
    if (p.depth[k] < pushWindowStart(c)) continue;
    x.add(p.depth[k], p.fx[k]);
    z.add(p.depth[k], p.fz[k]);
    log_f.add(std::log(p.depth[k]), std::log(std::hypot(p.fx[k], p.fz[k])));
  }
  return {x.intercept(), x.slope(), z.intercept(), z.slope(), log_f.slope()};
}

Vec2 pushMean(const Plate& c, const PlateRun& p) {
  Vec2 sum(0, 0);
  int n = 0;
  for (std::size_t k = 0; k < p.depth.size(); ++k)
    if (p.depth[k] >= pushWindowStart(c)) sum += Vec2(p.fx[k], p.fz[k]), ++n;
  return sum / n;
}

Vec2 dragMean(const Plate& c, const PlateRun& p) {
  Vec2 sum(0, 0);
  int n = 0;
  for (std::size_t k = 0; k < p.depth.size(); ++k)
    if (p.travel[k] >= 1.5 * c.length) sum += Vec2(p.fx[k], p.fz[k]), ++n;
  return sum / n;
}

BearingFactors bearingFactors(Real phi) {
  BearingFactors f;
  f.n_q = std::exp(M_PI * std::tan(phi)) * std::pow(std::tan(M_PI / 4 + phi / 2), 2);
  f.n_gamma = (f.n_q - 1) * std::tan(1.4 * phi);
  return f;
}

RftStress rftGeneric(Real beta, Real gamma) {
  // Li et al. 2013's generic coefficients (N/cm^3): A00, A10, B11, B01, B-11 for alpha_z and
  // C11, C01, C-11, D10 for alpha_x, the terms of sum_mn [A_mn cos(2 m beta + n gamma) + B_mn
  // sin(2 m beta + n gamma)] (and C, D for alpha_x) that their fit kept.
  const Real a00 = 0.206, a10 = 0.169, b11 = 0.212, b01 = 0.358, bm11 = 0.055;
  const Real c11 = -0.124, c01 = 0.253, cm11 = 0.007, d10 = 0.088;
  RftStress s;
  s.z = a00 + a10 * std::cos(2 * beta) + b11 * std::sin(2 * beta + gamma) + b01 * std::sin(gamma) +
        bm11 * std::sin(-2 * beta + gamma);
  s.x = c11 * std::cos(2 * beta + gamma) + c01 * std::cos(gamma) +
        cm11 * std::cos(-2 * beta + gamma) + d10 * std::sin(2 * beta);
  s.x *= 1e6;
  s.z *= 1e6;
  return s;
}

}  // namespace mpm_sdem::cases
