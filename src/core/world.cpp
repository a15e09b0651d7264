#include "mpm_sdem/core/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "coupling/imp_coupling.hpp"
#include "mpm/transfer.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/core/rigid/block_checks.hpp"
#include "parallel.hpp"
#include "sph/sph_stages.hpp"

namespace mpm_sdem {

const char* stepLimitName(StepLimit limit) {
  switch (limit) {
    case StepLimit::kFixed:
      return "fixed";
    case StepLimit::kCfl:
      return "cfl";
    case StepLimit::kContact:
      return "contact";
    case StepLimit::kElement:
      return "element";
    case StepLimit::kViscous:
      return "viscous";
    case StepLimit::kSph:
      return "sph";
    case StepLimit::kMax:
      return "max";
  }
  return "?";
}

namespace {

int cellCount(Real extent, Real h, const char* what) {
  const Real n = extent / h;
  const long r = std::lround(n);
  if (r < 1 || std::abs(n - r) > 1e-6 * std::max<Real>(1, n)) {
    throw std::invalid_argument(std::string("domain ") + what + " is not a whole number of cells");
  }
  return static_cast<int>(r);
}

}  // namespace

Problem sizeProblem(const DomainDef& domain, Real cell_size, const std::vector<BodyDef>& bodies) {
  if (const Problem p = limits::rangeProblem(cell_size, limits::kCellSize); !p.empty())
    return "cell_size " + p.message;
  const Vec2 cells = (domain.max - domain.min) / cell_size;
  const double pad = 2 * Grid::kPad + 1;
  double points = 0;
  for (const BodyDef& b : bodies) {
    Vec2 lo, hi;
    bounds(b.shape, lo, hi);
    const Vec2 extent = (hi - lo) / cell_size * b.points_per_cell;
    points += (extent.x() + 1) * (extent.y() + 1);  // at most one point per lattice site
  }
  return limits::memoryProblem((cells.x() + pad) * (cells.y() + pad), points);
}

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::World(const WorldDef& def) : def_(def) {
  if (const Problem p = sizeProblem(def.domain, def.cell_size, def.bodies); !p.empty())
    throw std::invalid_argument("the world " + p.message);
  const Vec2 size = def.domain.max - def.domain.min;
  grid_.init(def.domain.min, cellCount(size.x(), def.cell_size, "width"),
             cellCount(size.y(), def.cell_size, "height"), def.cell_size);
  tiles_.init(grid_);
  tiles_.periodic_x = periodicX();
  if (const Problem p = periodicProblem(def); !p.empty()) throw std::invalid_argument(p.text());
  for (const MaterialDef& m : def.materials) {
    params_.push_back(makeMaterialParams(m));
    if (m.model == MaterialModel::kFluid && m.viscosity > 0)
      viscous_dt_ =
          std::fmin(viscous_dt_, def.cell_size * def.cell_size * m.density / (2 * m.viscosity));
  }

  std::size_t count = 0;
  std::vector<std::vector<Vec2>> filled;
  for (const BodyDef& b : def.bodies) {
    if (b.material < 0 || b.material >= static_cast<int>(params_.size())) {
      throw std::invalid_argument("body '" + b.name + "' names no material");
    }
    if (b.points_per_cell < 1) throw std::invalid_argument("points_per_cell must be >= 1");
    filled.push_back(fillPoints(b.shape, def.domain.min, def.cell_size, b.points_per_cell));
    count += filled.back().size();
  }
  particles_.resize(count);
  std::size_t p = 0;
  for (std::size_t b = 0; b < def.bodies.size(); ++b) {
    const BodyDef& body = def.bodies[b];
    const MaterialDef& mat = def.materials[body.material];
    const Real spacing = def.cell_size / body.points_per_cell;
    const std::vector<Real> volumes = pointVolumes(body.shape, filled[b], spacing);
    for (std::size_t k = 0; k < filled[b].size(); ++k) {
      const Vec2& x = filled[b][k];
      particles_.x[p] = x.x();
      particles_.y[p] = x.y();
      particles_.vx[p] = body.velocity.x();
      particles_.vy[p] = body.velocity.y();
      particles_.volume0[p] = volumes[k];
      particles_.mass[p] = mat.density * volumes[k];
      particles_.half_size[p] = Real(0.5) / body.points_per_cell;
      particles_.depth[p] = std::max(outlineDistance(body.shape, x), Real(0));
      particles_.material[p] = static_cast<std::uint16_t>(body.material);
      particles_.body[p] = static_cast<std::uint16_t>(b);
      ++p;
    }
  }
  // Points in tile order from the start, so that the sweeps read them in sequence.
  tiles_.bin(particles_, grid_);
  particles_.permute(tiles_.order);
  lightest_point_ = std::numeric_limits<Real>::infinity();
  largest_spring_scale_ = 0;
  for (std::size_t q = 0; q < particles_.size(); ++q) {
    const Real scale = impSpringScale(def.coupling.stiffness_per, particles_, q, def.cell_size);
    lightest_point_ = std::fmin(lightest_point_, particles_.mass[q] / scale);
    largest_spring_scale_ = std::fmax(largest_spring_scale_, scale);
  }
  if (!(largest_spring_scale_ > 0)) largest_spring_scale_ = 1;

  if (def.sph.enabled()) initSph();
  if (!def.blocks.empty())
    blocks_ = std::make_unique<Blocks>(def.blocks, def.block_contact, def.solver.gravity);
  if (!def.fem_bodies.empty()) {
    if (const Problem p = schemeProblem(def.coupling.scheme, true, false); !p.empty())
      throw std::invalid_argument(p.text());
    fem_ = std::make_unique<FemBodies>(def.fem_bodies, def.solver.gravity);
  }
  if (blocks_ || fem_) {
    linkContactBodies();
    initCoupling();
  }
  if (!def.time_step.automatic) {
    // A fixed step past the critical one (eq. 51 with kappa_1 = 1 and pi kappa_2 = 1) would blow
    // up: refuse it before the first step, naming the term and the step that would be taken.
    const TimeStepChoice critical = stepBound(1, 1 / M_PI);
    if (def.time_step.fixed > critical.dt) {
      const TimeStepChoice safe = stepBound(0.3, 0.1);
      char msg[320];
      std::snprintf(msg, sizeof msg,
                    "time.dt = %.3g s is above the critical step %.3g s of the %s term (seed 000 "
                    "eq. 51 with kappa_1 = 1, kappa_2 = 1/pi) at the start; set time.dt: auto "
                    "(it would take %.3g s) or a fixed step below that",
                    def.time_step.fixed, critical.dt, stepLimitName(critical.limit), safe.dt);
      throw std::invalid_argument(msg);
    }
  }
  // A step below the floor would freeze simulated time (a stiffness or modulus far beyond the
  // others, a sliver of a block): refuse it with the term that sets it.
  const TimeStepChoice first = def.time_step.automatic
                                   ? stepBound(def.time_step.cfl, def.time_step.contact_factor)
                                   : TimeStepChoice{def.time_step.fixed, StepLimit::kFixed};
  if (!(first.dt >= limits::kMinTimeStep)) {
    char msg[320];
    std::snprintf(msg, sizeof msg,
                  "the stable step at the start is %.3g s (the %s term of seed 000 eq. 51), "
                  "below %.3g s: a simulated second would take over %.3g steps; check the "
                  "moduli, densities, spring stiffnesses and block sizes",
                  first.dt, stepLimitName(first.limit), limits::kMinTimeStep,
                  1 / limits::kMinTimeStep);
    throw std::invalid_argument(msg);
  }
}

void World::initSph() {
  const Problem problem =
      sphProblem(def_.sph, def_.cell_size, def_.solver.stress_update == StressUpdate::kUsf);
  if (!problem.empty()) throw std::invalid_argument("sph." + problem.text());
  if (const Problem p = schemeProblem(def_.coupling.scheme, false, true); !p.empty())
    throw std::invalid_argument(p.text());
  sph_ = detail::startSph(sphWorld());
}

detail::SphWorld World::sphWorld() {
  return {particles_,
          grid_,
          tiles_,
          params_,
          def_.solver,
          def_.sph,
          static_cast<int>(def_.bodies.size()),
          def_.domain.min,
          def_.domain.max,
          profile_};
}

CouplingDef World::resolvedCoupling() const {
  CouplingDef c = def_.coupling;
  int ppc = 1;
  for (const BodyDef& b : def_.bodies) ppc = std::max(ppc, b.points_per_cell);
  // Eq. 45 asks h / sqrt(n) < r_p < h with n points per cell: the geometric mean of the bounds.
  if (c.contact_radius <= 0) c.contact_radius = def_.cell_size / std::sqrt(static_cast<Real>(ppc));
  if (c.verlet_distance <= 0) c.verlet_distance = 0.5 * def_.cell_size;
  // Seed 003: boundary particles a third of the point spacing inside the outline.
  if (c.boundary_inset <= 0) c.boundary_inset = def_.cell_size / (3 * ppc);
  return c;
}

void World::initCoupling() {
  coupling_ = makeCoupling(resolvedCoupling(), def_.domain.min, def_.domain.max, def_.cell_size,
                           def_.bodies);
}

Problem World::placementProblem(const BlockDef& d, bool allow_overlap, BlockId moving) const {
  if (Problem own = blockProblem(d, def_.block_contact.model); !own.empty()) return own;
  if (!coupling_ && !schemeTraits(def_.coupling.scheme).takes_later_blocks && steps_ > 0)
    return {"", std::string("the ") + couplingSchemeName(def_.coupling.scheme) +
                    " coupling builds its wall from the material's initial outline: give the "
                    "scene a block from the start, or use another coupling scheme"};
  if (moving.isNull() && blocks_ && !blocks_->find(d.name).isNull())
    return {"name", "a block named '" + d.name + "' exists"};
  if (Problem where = domainProblem(d, def_.domain.min, def_.domain.max); !where.empty())
    return where;
  if (allow_overlap) return {};
  const std::vector<Spheropolygon> parts = placedParts(d);
  if (blocks_) {
    for (int i = 0; i < blocks_->count(); ++i) {
      if (blocks_->id(i) == moving) continue;
      if (const Real depth = startingOverlap(parts, blocks_->currentParts(i)); depth > 0)
        return {"position", "it overlaps block '" + blocks_->def(i).name + "' by " +
                                std::to_string(depth) + " m"};
    }
  }
  const Particles& P = particles_;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (insideOutline(parts, Vec2(P.x[p], P.y[p])))
      return {"position", "it overlaps the material (point " + std::to_string(p) + " is inside)"};
  }
  return {};
}

BlockId World::addBlock(const BlockDef& d) {
  if (!blocks_)
    blocks_ = std::make_unique<Blocks>(std::vector<BlockDef>{}, def_.block_contact,
                                       def_.solver.gravity, std::sqrt(blockMass(d).area));
  const BlockId id = blocks_->add(d);
  linkContactBodies();
  if (!coupling_) initCoupling();
  coupling_->bodiesChanged();
  if (command_log_) {
    WorldCommand c = command(WorldCommand::Kind::kAddBlock, id);
    c.def = blocks_->def(blocks_->indexOf(id));
    command_log_(c);
  }
  return id;
}

void World::removeBlock(BlockId id) {
  if (!blocks_) throw std::invalid_argument("removeBlock: the world has no blocks");
  const WorldCommand c = command_log_ && blocks_->indexOf(id) >= 0
                             ? command(WorldCommand::Kind::kRemoveBlock, id)
                             : WorldCommand();
  blocks_->remove(id);
  linkContactBodies();
  coupling_->bodiesChanged();
  if (command_log_) command_log_(c);
}

WorldCommand World::command(WorldCommand::Kind kind, BlockId id) {
  WorldCommand c;
  c.kind = kind;
  c.time = time_;
  c.step = steps_;
  c.sequence = commands_++;
  if (!id.isNull()) c.block = blocks_->def(blocks_->indexOf(id)).name;
  return c;
}

void World::linkContactBodies() {
  if (!fem_) return;
  const WallDef walls[4] = {def_.domain.left, def_.domain.right, def_.domain.bottom,
                            def_.domain.top};
  fem_->setSurroundings(def_.domain.min, def_.domain.max, walls, blocks_.get());
  if (!blocks_) return;
  if (set_)
    set_->refresh();
  else
    set_ = std::make_unique<ContactSet>(std::vector<ContactBodies*>{blocks_.get(), fem_.get()});
}

void World::setBlockPose(BlockId id, const Vec2& origin, Real angle) {
  blocks_->setPose(id, origin, angle);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetPose, id);
  c.point = origin;
  c.scalar = angle;
  command_log_(c);
}

void World::setBlockVelocity(BlockId id, const Vec2& origin_velocity, Real angular_velocity) {
  blocks_->setVelocity(id, origin_velocity, angular_velocity);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetVelocity, id);
  c.vector = origin_velocity;
  c.scalar = angular_velocity;
  command_log_(c);
}

void World::addBlockLoad(BlockId id, const Vec2& force, const Vec2& point, Real torque) {
  if (!blocks_) throw std::invalid_argument("addBlockLoad: this world has no blocks");
  blocks_->addLoad(id, force, point, torque);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kAddLoad, id);
  c.vector = force;
  c.point = point;
  c.scalar = torque;
  command_log_(c);
}

Problem World::gravityProblem(const Vec2& g) {
  if (!std::isfinite(g.x()) || !std::isfinite(g.y())) return {"gravity", "must be finite"};
  if (const Problem p = limits::rangeProblem(g.norm(), limits::kGravity); !p.empty())
    return {"gravity", "its magnitude " + p.message};
  return {};
}

void World::applyGravity(const Vec2& g) {
  def_.solver.gravity = g;
  if (blocks_) blocks_->setGravity(g);
  if (fem_) fem_->setGravity(g);
}

void World::setGravity(const Vec2& g) {
  if (const Problem p = gravityProblem(g); !p.empty()) throw std::invalid_argument(p.text());
  applyGravity(g);
  if (!command_log_) return;
  WorldCommand c = command(WorldCommand::Kind::kSetGravity, BlockId());
  c.vector = g;
  command_log_(c);
}

std::string applyCommand(World& world, const WorldCommand& c) {
  if (c.kind == WorldCommand::Kind::kSetGravity) {
    if (const Problem p = World::gravityProblem(c.vector); !p.empty())
      return "cannot set gravity: " + p.message;
    world.setGravity(c.vector);
    return "";
  }
  if (c.kind == WorldCommand::Kind::kAddBlock) {
    if (Problem p = world.placementProblem(c.def, true); !p.empty())
      return "cannot add block '" + c.def.name + "': " + p.text();
    world.addBlock(c.def);
    return "";
  }
  const BlockId id = world.blocks() ? world.blocks()->find(c.block) : BlockId();
  if (id.isNull()) return "no block named '" + c.block + "'";
  switch (c.kind) {
    case WorldCommand::Kind::kAddBlock:
    case WorldCommand::Kind::kSetGravity:
      break;
    case WorldCommand::Kind::kRemoveBlock:
      world.removeBlock(id);
      break;
    case WorldCommand::Kind::kSetPose:
      world.setBlockPose(id, c.point, c.scalar);
      break;
    case WorldCommand::Kind::kSetVelocity:
      world.setBlockVelocity(id, c.vector, c.scalar);
      break;
    case WorldCommand::Kind::kAddLoad:
      world.addBlockLoad(id, c.vector, c.point, c.scalar);
      break;
  }
  return "";
}

World::Memory World::memory() const {
  Memory m;
  particles_.forEachColumn(
      [&m](const auto& c) { m.particle_bytes += c.capacity() * sizeof(c[0]); });
  m.particle_bytes += tiles_.particleBytes();
  grid_.forEachField([&m](const auto& a) { m.grid_bytes += a.capacity() * sizeof(a[0]); });
  m.grid_nodes = grid_.nodeCount();
  m.active_nodes = tiles_.active.size() * Tiles::kSize * Tiles::kSize;
  return m;
}

TimeStepChoice World::chooseTimeStep() {
  const detail::SerialScope serial(!sharesWork());
  StageTimer timer(profile_, Stage::kTimeStep);
  if (!def_.time_step.automatic) return {def_.time_step.fixed, StepLimit::kFixed};
  return stepBound(def_.time_step.cfl, def_.time_step.contact_factor);
}

TimeStepChoice World::stepBound(Real cfl, Real kappa2) const {
  // Seed 000 eq. 51, first term: dt = kappa_1 h / max_p (c_p + |v_p|), with the P-wave speed
  // c_p = sqrt((K + 4G/3) / rho_p) at the current density rho_p = rho_0 / J_p; none in a point
  // whose grains have separated (MaterialDef::separation_volume_ratio).
  const Particles& P = particles_;
  const long n = static_cast<long>(P.size());
  Real fastest = 0;
  auto fastestWith = [&](auto modulusOverDensity) {
    // The faster of s and the point's speed; a NaN speed is skipped, as fmax would.
    auto faster = [&](Real s, long p) {
      const Real c2 = modulusOverDensity(p, P.J[p]);
      const Real v2 = P.vx[p] * P.vx[p] + P.vy[p] * P.vy[p];
      const Real speed = std::sqrt(c2 > 0 ? c2 : Real(0)) + std::sqrt(v2);
      return speed > s ? speed : s;
    };
    if (detail::singleThread()) {
#pragma omp simd reduction(max : fastest)
      for (long p = 0; p < n; ++p) fastest = faster(fastest, p);
      return;
    }
#pragma omp parallel for simd schedule(static) reduction(max : fastest)
    for (long p = 0; p < n; ++p) fastest = faster(fastest, p);
  };
  if (params_.size() == 1 && params_[0].model != MaterialModel::kFluid) {
    // One solid material: no lookup and no pow, so the loop vectorises.
    const Real k = params_[0].modulus_over_density, loose = params_[0].separation;
    fastestWith([k, loose](long, Real J) { return J > loose ? Real(0) : k * J; });
  } else {
    fastestWith([this, &P](long p, Real J) { return squaredWaveSpeed(params_[P.material[p]], J); });
  }
  const Real cfl_dt = fastest > 0 ? cfl * grid_.h / fastest : std::numeric_limits<Real>::infinity();
  TimeStepChoice choice{def_.time_step.max, StepLimit::kMax};
  if (cfl_dt < choice.dt) choice = {cfl_dt, StepLimit::kCfl};
  // Explicit viscous diffusion: dt <= kappa_1 h^2 / (2 nu) with the kinematic viscosity nu =
  // eta / rho0 of the most diffusive fluid (the diffusion number h^2 / (4 nu) of an explicit
  // 2D Laplacian at kappa_1 = 0.5).
  if (viscous_dt_ < choice.dt / cfl) choice = {cfl * viscous_dt_, StepLimit::kViscous};
  if (sph_) {
    const Real dt = detail::sphStableStep(*sph_, particles_, tiles_, params_, cfl);
    if (dt < choice.dt) choice = {dt, StepLimit::kSph};
  }
  if (fem_ && cfl * fem_->elementStep() < choice.dt)
    choice = {cfl * fem_->elementStep(), StepLimit::kElement};
  // The springs between bodies never bound this step (the bodies take substeps within their
  // own bound).
  if (hasContactBodies() && coupling_->hasSprings()) {
    // Subcycled springs bound their substeps, and a step holds at most kMaxContactSubsteps of
    // them: a contact too stiff for its mass (a tiny or light obstacle) shortens the step as an
    // explicit one does, rather than making one step endless (the node refuses such a block
    // once the step falls below limits::kMinTimeStep).
    constexpr Real kMaxContactSubsteps = 1000;
    const Real dt = (coupling_->subcycles() ? kMaxContactSubsteps : 1) * springStep(kappa2);
    if (dt < choice.dt) choice = {dt, StepLimit::kContact};
  }
  return choice;
}

Real World::springStep(Real kappa2) const {
  // Eq. 51, second term, for the coupling springs (lightest point or body).
  const ContactBodies& bodies = *contactBodies();
  const CouplingDef& c = coupling_->def();
  const Real zeta = bodies.maxDampingRatio();  // the most damped contact bounds the step
  const Real block = bodies.lightestMass() / largest_spring_scale_;
  if (c.normal_integration == ContactIntegration::kExact) {
    // Integrated exactly, a normal spring allows any step on its point; the block still takes
    // the summed forces explicitly (its own term), and the points the tangential springs
    // (undamped, explicit).
    return std::fmin(contactTimeStep(block, c.normal_stiffness, zeta, 1, kappa2),
                     contactTimeStep(lightest_point_, c.tangential_stiffness, 0, 1, kappa2));
  }
  return contactTimeStep(std::fmin(lightest_point_, block), c.normal_stiffness, zeta, 1, kappa2);
}

bool World::sharesWork() const {
  // An SPH particle's neighbour sums cost many material points' work: SPH worlds always share.
  return sph_ || static_cast<long>(particles_.size()) >= def_.solver.parallel_min_points;
}

StepInfo World::step(Real dt) {
  const detail::SerialScope serial(!sharesWork());
  StepInfo info;
  info.dt = dt;
  // Seed 000 eq. 17: p^{n+1/2} = p^{n-1/2} + f^n dt. The kick spans from the velocity's time to
  // half a step past the positions' time.
  const Real kick = Real(0.5) * dt + velocity_lag_;
  // Seed 000 sec. 4.2: contact forces from the state at the start of the step, the MPM step with
  // them on the grid (eq. 48), then the blocks with the reactions. Each coupling scheme does its
  // part in the stages of coupling.hpp.
  const bool coupled = hasContactBodies();
  const bool corrected = coupled && coupling_->correctsVelocities();
  // A correction's impulses are forces the local damping must see, or it would move a static
  // equilibrium that a contact holds (it would damp the internal force and gravity alone, which
  // the contact balances): it damps the step's whole velocity change then. A correction may
  // also push into a wall.
  auto correctedWalls = [this](Real kick) {
    if (def_.solver.damping > 0) dampVelocityChange(kick);
    applyWalls(grid_.vel_x, grid_.vel_y);
  };
  if (coupled) {
    StageTimer timer(profile_, Stage::kBodies);  // FEM bodies' internal forces (eq. 20)
    contactBodies()->beginCoupling(dt);
  }
  auto stage = [&](void (Coupling::*f)(CouplingStep&)) {
    if (coupled) couplingStage(dt, kick, f);
  };
  stage(&Coupling::beforeStep);
  binParticles();
  clearGrid();
  if (def_.solver.stress_update == StressUpdate::kUsf) {
    // The SPH particles' velocity gradient and stress first: it needs no grid, and the band's
    // particles lend the grid their affine velocity (transfer.hpp) and their stress.
    if (sph_) detail::sphStress(*sph_, sphWorld(), stress_lag_);
    particleToGrid(true, false);
    foldPeriodic({&grid_.mass, &grid_.mom_x, &grid_.mom_y});
    gridVelocity(0, false);
    stressAndInternalForce(stress_lag_);  // and the side walls' load
    if (sph_)
      detail::sphForces(*sph_, sphWorld());  // before any point moves: the pairs are read at x^n
    spreadPointLoads();
    stage(&Coupling::addGridForces);
    foldPeriodic({&grid_.force_x, &grid_.force_y, &sidewall_load_});
    gridVelocity(kick, true, !corrected);
    sidewallFriction(kick);
    stage(&Coupling::correctGridVelocity);
    if (corrected) correctedWalls(kick);
    gridToParticle(dt, info);
    if (sph_) detail::sphMove(*sph_, sphWorld(), dt, kick, info.clamped, info.finite);
    stress_lag_ = dt;
  } else {
    particleToGrid(true, true);
    sidewallLoad();
    spreadPointLoads();
    stage(&Coupling::addGridForces);
    foldPeriodic(
        {&grid_.mass, &grid_.mom_x, &grid_.mom_y, &grid_.force_x, &grid_.force_y, &sidewall_load_});
    gridVelocity(0, false);
    gridVelocity(kick, true, !corrected);
    sidewallFriction(kick);
    stage(&Coupling::correctGridVelocity);
    if (corrected) correctedWalls(kick);
    gridToParticle(dt, info);
    constitutiveUpdate(dt);
    stress_lag_ = 0;
  }
  stage(&Coupling::afterMaterialStep);
  if (coupled && !coupling_->subcycles()) stepBodies(dt);  // else in correctGridVelocity
  if (blocks_) checkBlocks(info);
  velocity_lag_ = Real(0.5) * dt;
  time_ += dt;
  ++steps_;
  ++profile_.steps;
  return info;
}

void World::reverseVelocities() {
  Particles& P = particles_;
  for (auto* v : {&P.vx, &P.vy, &P.bxx, &P.bxy, &P.byx, &P.byy}) {
    for (Real& a : *v) a = -a;
  }
  velocity_lag_ = -velocity_lag_;
  stress_lag_ = -stress_lag_;
}

void World::couplingStage(Real dt, Real kick, void (Coupling::*stage)(CouplingStep&)) {
  StageTimer timer(profile_, Stage::kContact);
  CouplingStep s{particles_,          grid_, tiles_, *contactBodies(), def_.solver.kernel,
                 def_.solver.gravity, dt,    kick};
  if (stage == &Coupling::correctGridVelocity && coupling_->subcycles()) {
    s.contact_substep = springStep(def_.time_step.contact_factor);
    s.body_substep = contactBodies()->stableStep(def_.time_step.contact_factor);
  }
  if (sph_) {
    s.sph_ax = sph_->columns.ax.data();
    s.sph_ay = sph_->columns.ay.data();
  }
  ((*coupling_).*stage)(s);
}

void World::stepBodies(Real dt) {
  StageTimer timer(profile_, Stage::kBodies);
  ContactBodies& bodies = *contactBodies();
  bodies.step(dt, bodies.stableStep(def_.time_step.contact_factor));
}

void World::checkBlocks(StepInfo& info) const {
  const Blocks& B = *blocks_;
  const Vec2 &lo = def_.domain.min, &hi = def_.domain.max;
  for (const int i : B.movingBlocks()) {
    const BlockState& s = B.state(i);
    if (!s.position.allFinite() || !std::isfinite(s.angle) || !s.velocity.allFinite() ||
        !std::isfinite(s.angular_velocity)) {
      info.finite = false;
      info.block_problem =
          "block '" + B.def(i).name + "': its position, angle or velocity is no longer finite";
      return;
    }
    // Its centre, not its outline: a block resting on a floor at the domain's edge overlaps the
    // floor by its contact springs' compression, past the edge.
    if ((s.position.array() < lo.array()).any() || (s.position.array() > hi.array()).any()) {
      char where[160];
      std::snprintf(where, sizeof where,
                    ": its centre of mass (%.4g, %.4g) m left the domain [%.4g, %.4g] x "
                    "[%.4g, %.4g] m",
                    s.position.x(), s.position.y(), lo.x(), hi.x(), lo.y(), hi.y());
      info.block_problem = "block '" + B.def(i).name + "'" + where;
      return;
    }
  }
}

void World::setPointLoad(int particle, const Vec2& force, const Vec2& offset) {
  if (particle < 0 || static_cast<std::size_t>(particle) >= particles_.size() ||
      !force.allFinite() || !offset.allFinite())
    throw std::invalid_argument("setPointLoad: no such point, or a non-finite force or offset");
  auto it = std::find_if(point_loads_.begin(), point_loads_.end(),
                         [particle](const PointLoad& l) { return l.particle == particle; });
  if (it == point_loads_.end()) {
    if (force.isZero()) return;
    point_loads_.push_back({particle, force, offset});
  } else if (force.isZero()) {
    point_loads_.erase(it);
  } else {
    *it = {particle, force, offset};
  }
}

void World::spreadPointLoads() {
  if (point_loads_.empty()) return;
  StageTimer timer(profile_, Stage::kStress);
  detail::withKernel(def_.solver.kernel, [&](auto k) {
    const Particles& P = particles_;
    for (const PointLoad& l : point_loads_) {
      if (P.kind[l.particle] == kSphParticle) {  // moved by its own acceleration, not the grid
        sph_->columns.ax[l.particle] += l.force.x() / P.mass[l.particle];
        sph_->columns.ay[l.particle] += l.force.y() / P.mass[l.particle];
        continue;
      }
      const Vec2 at = Vec2(P.x[l.particle], P.y[l.particle]) + l.offset;
      detail::spreadPointLoad<decltype(k)>(grid_, at, P.half_size[l.particle], l.force);
    }
  });
}

void World::binParticles() {
  if (sph_) return detail::binWithSph(*sph_, sphWorld());
  StageTimer timer(profile_, Stage::kSort);
  tiles_.bin(particles_, grid_);
}

template <class F>
void World::forActiveNodes(const std::vector<int>& tiles, F&& f) {
  tiles_.nodeRuns(grid_, tiles, node_runs_);
  detail::parallelFor(static_cast<long>(node_runs_.size()),
                      [&](long k) { f(node_runs_[k].first, node_runs_[k].end); });
}

void World::clearGrid() {
  // Only the tiles the last step used hold values; every other node is zero already.
  StageTimer timer(profile_, Stage::kClearGrid);
  Grid& G = grid_;
  // Velocities are overwritten on every active node; a tile leaving the set is zeroed whole.
  forActiveNodes(tiles_.previous, [&G](int first, int end) {
    for (auto* a : {&G.mass, &G.mom_x, &G.mom_y, &G.force_x, &G.force_y})
      std::fill(a->data() + first, a->data() + end, Real(0));
  });
  forActiveNodes(tiles_.retired, [&G](int first, int end) {
    for (auto* a : {&G.vel_x, &G.vel_y, &G.vel0_x, &G.vel0_y})
      std::fill(a->data() + first, a->data() + end, Real(0));
  });
}

void World::particleToGrid(bool momentum, bool force) {
  StageTimer timer(profile_, Stage::kP2G);
  detail::particleToGrid(def_.solver.kernel,
                         {momentum, force, momentum && carriesAffine(def_.solver.transfer)},
                         particles_, grid_, tiles_);
}

void World::gridVelocity(Real kick, bool after_force, bool damp) {
  StageTimer timer(profile_, Stage::kGridUpdate);
  Grid& G = grid_;
  if (!after_force) {
    // Eq. 20: v_I = p_I / m_I; nodes without mass carry no velocity.
    forActiveNodes(tiles_.active, [&G](int first, int end) {
      const Real *m = G.mass.data(), *px = G.mom_x.data(), *py = G.mom_y.data();
      Real *vx = G.vel0_x.data(), *vy = G.vel0_y.data();
#pragma omp simd
      for (int i = first; i < end; ++i) {
        vx[i] = m[i] > 0 ? px[i] / m[i] : Real(0);
        vy[i] = m[i] > 0 ? py[i] / m[i] : Real(0);
      }
    });
    applyWalls(G.vel0_x, G.vel0_y);
    return;
  }
  const Real gx = def_.solver.gravity.x(), gy = def_.solver.gravity.y();
  const Real damping = damp ? def_.solver.damping : Real(0);
  forActiveNodes(tiles_.active, [&](int first, int end) {
    const Real *m = G.mass.data(), *fx = G.force_x.data(), *fy = G.force_y.data();
    const Real *vx0 = G.vel0_x.data(), *vy0 = G.vel0_y.data();
    Real *vx = G.vel_x.data(), *vy = G.vel_y.data();
#pragma omp simd
    for (int i = first; i < end; ++i) {
      // Eq. 11 and 17: total nodal force, internal plus gravity (eq. 13-14).
      const Real ax = detail::localDamping(fx[i] + m[i] * gx, vx0[i], damping);
      const Real ay = detail::localDamping(fy[i] + m[i] * gy, vy0[i], damping);
      vx[i] = m[i] > 0 ? vx0[i] + kick * ax / m[i] : Real(0);
      vy[i] = m[i] > 0 ? vy0[i] + kick * ay / m[i] : Real(0);
    }
  });
  applyWalls(G.vel_x, G.vel_y);
}

void World::dampVelocityChange(Real kick) {
  if (kick == 0) return;
  StageTimer timer(profile_, Stage::kGridUpdate);
  Grid& G = grid_;
  const Real damping = def_.solver.damping;
  forActiveNodes(tiles_.active, [&](int first, int end) {
    const Real *vx0 = G.vel0_x.data(), *vy0 = G.vel0_y.data();
    Real *vx = G.vel_x.data(), *vy = G.vel_y.data();
#pragma omp simd
    for (int i = first; i < end; ++i) {
      // The same law as gridVelocity's on the force per unit mass (v - v0) / kick.
      vx[i] = vx0[i] + kick * detail::localDamping((vx[i] - vx0[i]) / kick, vx0[i], damping);
      vy[i] = vy0[i] + kick * detail::localDamping((vy[i] - vy0[i]) / kick, vy0[i], damping);
    }
  });
}

void World::applyWalls(std::vector<Real>& vx, std::vector<Real>& vy) const {
  // Nodes on and beyond a domain side belong to its wall; corner nodes see both walls.
  const Grid& G = grid_;
  const int left = Grid::kPad, right = Grid::kPad + G.cells_x;
  const int bottom = Grid::kPad, top = Grid::kPad + G.cells_y;
  const DomainDef& d = def_.domain;
  for (int j = 0; j < G.ny; ++j) {
    for (int i = 0; i < G.nx; ++i) {
      if (i > left && i < right && j > bottom && j < top) {
        i = right - 1;  // skip the interior of the row
        continue;
      }
      const int k = G.index(i, j);
      if (vx[k] == 0 && vy[k] == 0) continue;  // every wall keeps a node at rest (most are)
      if (i <= left) applyWall(d.left, -1, 0, vx[k], vy[k]);
      if (i >= right) applyWall(d.right, 1, 0, vx[k], vy[k]);
      if (j <= bottom) applyWall(d.bottom, 0, -1, vx[k], vy[k]);
      if (j >= top) applyWall(d.top, 0, 1, vx[k], vy[k]);
    }
  }
}

Problem periodicProblem(const WorldDef& def) {
  const bool left = def.domain.left.type == WallType::kPeriodic;
  const bool right = def.domain.right.type == WallType::kPeriodic;
  if (left != right) return {"domain.walls", "left and right must both be periodic, or neither"};
  if (def.domain.bottom.type == WallType::kPeriodic || def.domain.top.type == WallType::kPeriodic)
    return {"domain.walls", "only left and right can be periodic"};
  if (!left) return {};
  const Real cells = (def.domain.max.x() - def.domain.min.x()) / def.cell_size;
  if (cells < 2 * Grid::kPad + 1 - 1e-9)
    return {"domain.walls", "a periodic domain needs at least " +
                                std::to_string(2 * Grid::kPad + 1) +
                                " cells across, so that no node has two images"};
  if (!def.blocks.empty() || !def.fem_bodies.empty() || def.sph.enabled())
    return {"domain.walls", "periodic sides are for material alone: no blocks, FEM bodies or SPH"};
  return {};
}

void World::foldPeriodic(std::initializer_list<std::vector<Real>*> fields) {
  if (!periodicX()) return;
  StageTimer timer(profile_, Stage::kGridUpdate);
  const int nx = grid_.nx, cells = grid_.cells_x, pairs = nx - cells;
  for (std::vector<Real>* a : fields) {
    if (a->empty()) continue;  // a field this scene does not use
    for (int j = 0; j < grid_.ny; ++j) {
      Real* row = a->data() + static_cast<std::size_t>(j) * nx;
      for (int i = 0; i < pairs; ++i) row[i] = row[i + cells] = row[i] + row[i + cells];
    }
  }
}

Real* World::clearedSidewallLoad() {
  if (!(def_.domain.sidewalls.width > 0)) return nullptr;
  sidewall_load_.resize(grid_.nodeCount());
  forActiveNodes(tiles_.active, [this](int first, int end) {
    std::fill(sidewall_load_.data() + first, sidewall_load_.data() + end, Real(0));
  });
  return sidewall_load_.data();
}

Real World::sidewallCoefficient() const {
  return 2 * def_.domain.sidewalls.friction / def_.domain.sidewalls.width;
}

void World::sidewallLoad() {
  StageTimer timer(profile_, Stage::kStress);
  Real* load = clearedSidewallLoad();
  if (!load) return;
  detail::withKernel(def_.solver.kernel, [&](auto k) {
    detail::sidewallLoad<decltype(k)>(particles_, grid_, tiles_, sidewallCoefficient(), load);
  });
}

void World::sidewallFriction(Real kick) {
  if (!(def_.domain.sidewalls.width > 0) || kick == 0) return;
  StageTimer timer(profile_, Stage::kGridUpdate);
  Grid& G = grid_;
  forActiveNodes(tiles_.active, [&](int first, int end) {
    const Real *m = G.mass.data(), *load = sidewall_load_.data();
    Real *vx = G.vel_x.data(), *vy = G.vel_y.data();
    for (int i = first; i < end; ++i) {
      // Coulomb friction on the node's velocity after the kick: it takes off at most
      // kick load / m of speed, and stops the node rather than reversing it, so that it can
      // hold material at rest (a static pile leaning on its walls).
      const Real speed = std::hypot(vx[i], vy[i]);
      if (!(m[i] > 0) || speed == 0) continue;
      const Real scale = std::fmax(0, 1 - kick * load[i] / (m[i] * speed));
      vx[i] *= scale;
      vy[i] *= scale;
    }
  });
}

void World::stressAndInternalForce(Real dt) {
  StageTimer timer(profile_, Stage::kStress);
  detail::SidewallLoad walls;
  if (Real* load = clearedSidewallLoad()) walls = {sidewallCoefficient(), load};
  detail::stressAndInternalForce(def_.solver.kernel, particles_, grid_, tiles_, params_, dt, walls);
}

void World::gridToParticle(Real dt, StepInfo& info) {
  StageTimer timer(profile_, Stage::kG2P);
  const detail::G2PSettings s{def_.solver.pic_fraction,
                              dt,
                              def_.domain.min,
                              def_.domain.max,
                              periodicX(),
                              detail::asflipKeep(dt, def_.solver.asflip_relaxation_time)};
  const bool usl = def_.solver.stress_update == StressUpdate::kUsl;
  const Tiles* material_points = sph_ ? &tiles_ : nullptr;  // only those, with SPH
  detail::gridToParticle(def_.solver.kernel, def_.solver.transfer, usl, particles_, grid_, s,
                         info.clamped, info.finite, material_points);
}

void World::constitutiveUpdate(Real dt) {
  StageTimer timer(profile_, Stage::kConstitutive);
  if (dt == 0) return;
  detail::updateStresses(particles_, params_, dt);
}

}  // namespace mpm_sdem
