#include "mpm_sdem/core/world.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <type_traits>

#include "coupling/imp_coupling.hpp"
#include "mpm/transfer.hpp"
#include "mpm_sdem/core/exclusions.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "parallel.hpp"
#include "sph/sph_stages.hpp"

namespace mpm_sdem {

World::~World() = default;
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;

World::World(const WorldDef& def)
    : def_(def), mpm_(def.domain, def.cell_size, def.solver, def.materials, def.bodies) {
  if (const Problem p = periodicProblem(def); !p.empty()) throw std::invalid_argument(p.text());
  if (const Problem p = combinationProblem(def); !p.empty()) throw std::invalid_argument(p.text());
  const Particles& points = mpm_.particles();
  lightest_point_ = std::numeric_limits<Real>::infinity();
  largest_spring_scale_ = 0;
  for (std::size_t q = 0; q < points.size(); ++q) {
    const Real scale = impSpringScale(def.coupling.stiffness_per, points, q, def.cell_size);
    // The springs move the point's inertial mass (SolverDef::inertia_scale).
    lightest_point_ = std::fmin(lightest_point_, points.mass[q] * def.solver.inertia_scale / scale);
    largest_spring_scale_ = std::fmax(largest_spring_scale_, scale);
  }
  if (!(largest_spring_scale_ > 0)) largest_spring_scale_ = 1;

  if (def.sph.enabled()) initSph();
  if (!def.blocks.empty())
    blocks_ = std::make_unique<Blocks>(def.blocks, def.block_contact, def.solver.gravity);
  if (!def.fem_bodies.empty()) {
    fem_ = std::make_unique<FemBodies>(def.fem_bodies, def.solver.gravity);
    if (def.time_step.fem_subcycled) fem_->setMaxSubstep(def.time_step.cfl * fem_->elementStep());
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
  compose();
}

void World::initSph() {
  const Problem problem = sphProblem(def_.sph, def_.cell_size);
  if (!problem.empty()) throw std::invalid_argument("sph." + problem.text());
  sph_ = detail::startSph(sphWorld());
}

detail::SphWorld World::sphWorld() {
  return {mpm_.particles(),
          mpm_.grid(),
          mpm_.tiles(),
          mpm_.params(),
          def_.solver,
          def_.sph,
          static_cast<int>(def_.bodies.size()),
          def_.domain.min,
          def_.domain.max};
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
  coupling_->setInertiaScale(def_.solver.inertia_scale);
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

TimeStepChoice World::chooseTimeStep() {
  const detail::SerialScope serial(!sharesWork());
  StageTimer timer(profile_, Stage::kTimeStep);
  if (!def_.time_step.automatic) return {def_.time_step.fixed, StepLimit::kFixed};
  return stepBound(def_.time_step.cfl, def_.time_step.contact_factor);
}

TimeStepChoice World::stepBound(Real cfl, Real kappa2) const {
  TimeStepChoice choice = mpm_.materialStep(cfl, def_.time_step.max);
  if (sph_) {
    const Real dt =
        detail::sphStableStep(*sph_, mpm_.particles(), mpm_.tiles(), mpm_.params(), cfl);
    choice.takeShorter(dt, StepLimit::kSph);
  }
  if (fem_) {
    // Subcycled, the elements bound their substeps, at most kMaxElementSubsteps to a step.
    constexpr Real kMaxElementSubsteps = 1000;
    const Real substeps = def_.time_step.fem_subcycled ? kMaxElementSubsteps : 1;
    choice.takeShorter(substeps * cfl * fem_->elementStep(), StepLimit::kElement);
  }
  // The springs between bodies never bound this step (the bodies take substeps within their
  // own bound).
  if (hasContactBodies() && coupling_->hasSprings()) {
    // Subcycled springs bound their substeps, and a step holds at most kMaxContactSubsteps of
    // them: a contact too stiff for its mass (a tiny or light obstacle) shortens the step as an
    // explicit one does, rather than making one step endless (the node refuses such a block
    // once the step falls below limits::kMinTimeStep).
    constexpr Real kMaxContactSubsteps = 1000;
    const Real dt = (coupling_->subcycles() ? kMaxContactSubsteps : 1) * springStep(kappa2);
    choice.takeShorter(dt, StepLimit::kContact);
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
  // Only the awake points take part (SolverDef::sleep).
  const long points = static_cast<long>(mpm_.particles().size()) - mpm_.sleep().sleepingPoints();
  return sph_ || points >= def_.solver.parallel_min_points;
}

StepMakeup World::makeup() const {
  StepMakeup m;
  m.usl = def_.solver.stress_update == StressUpdate::kUsl;
  m.sph = sph_ != nullptr;
  m.sleep = mpm_.sleep().on();
  m.periodic = mpm_.periodicX();
  m.sidewalls = mpm_.hasSidewalls();
  m.inertia_scaled = def_.solver.inertia_scale != 1;
  m.volume_fit = mpm_.fits();
  m.volumetric_average = def_.solver.volumetric_average;
  m.point_loads = !point_loads_.empty();
  m.contact_bodies = hasContactBodies();
  if (m.contact_bodies) {
    m.hooks = coupling_->hooks();
    m.corrects = coupling_->correctsVelocities();
    m.subcycles = coupling_->subcycles();
  }
  m.blocks = blocks_ != nullptr;
  return m;
}

void World::compose() {
  const StepMakeup m = makeup();
  stages_ = composeStep(m);
  damped_kick_ = !(m.contact_bodies && m.corrects);
  profile_.used[static_cast<int>(Stage::kTimeStep)] = true;
  for (const Stage s : stages_) profile_.used[static_cast<int>(s)] = true;
}

void World::resetProfile() {
  profile_ = Profile();
  compose();
}

StepInfo World::step(Real dt) {
  const detail::SerialScope serial(!sharesWork());
  StepInfo info;
  info.dt = dt;
  // Seed 000 eq. 17: p^{n+1/2} = p^{n-1/2} + f^n dt. The kick spans from the velocity's time to
  // half a step past the positions' time.
  StepScratch scratch{dt, Real(0.5) * dt + velocity_lag_, info};
  for (const Stage stage : stages_) {
    StageTimer timer(profile_, stage);
    runStage(stage, scratch);
  }
  velocity_lag_ = Real(0.5) * dt;
  time_ += dt;
  ++steps_;
  ++profile_.steps;
  return info;
}

void World::runStage(Stage stage, StepScratch& s) {
  MpmSolver& mpm = mpm_;
  // Each case is one row of step_stages.cpp's table, which says when it runs.
  switch (stage) {
    case Stage::kTimeStep:
    case Stage::kCount:
      break;
    case Stage::kBodiesBegin:
      contactBodies()->beginCoupling(s.dt);  // FEM bodies' internal forces (seed 002 sec. 2.3)
      break;
    case Stage::kContactSearch:
      couplingStage(s.dt, s.kick, &Coupling::beforeStep);
      break;
    case Stage::kSort:
      mpm.bin();
      break;
    case Stage::kSphSort:
      detail::binWithSph(*sph_, sphWorld());
      break;
    case Stage::kSleep:
      keepBlocksAwake();
      mpm.updateSleep(s.dt);
      break;
    case Stage::kClearGrid:
      mpm.clearGrid();
      break;
    case Stage::kSphGradient:
      // The SPH particles' velocity gradient and stress first: it needs no grid, and the band's
      // particles lend the grid their affine velocity (transfer.hpp) and their stress.
      detail::sphStress(*sph_, sphWorld(), stress_lag_);
      break;
    case Stage::kP2G:
      mpm.particleToGrid(true, false);
      break;
    case Stage::kP2GForce:
      mpm.particleToGrid(true, true);
      break;
    case Stage::kSleepMass:
      mpm.addSleepersMass();
      break;
    case Stage::kSidewallLoad:
      mpm.sidewallLoad();
      break;
    case Stage::kFoldMomentum:
      mpm.foldMomentum();
      break;
    case Stage::kScaleInertia:
      mpm.scaleInertia();
      break;
    case Stage::kGridVelocity:
      mpm.gridVelocity(0, false);
      break;
    case Stage::kVolumetricAverage:
      mpm.averageVolumetricRate();
      break;
    case Stage::kStressForce:
      // USF: the stress of the velocities at the start of the step, lagging the positions by the
      // last step (seed 000 eq. 17); the next step's lag is this one.
      mpm.stressAndInternalForce(stress_lag_);
      stress_lag_ = s.dt;
      break;
    case Stage::kSleepForce:
      mpm.addSleepersForce();
      break;
    case Stage::kSphForces:
      detail::sphForces(*sph_, sphWorld());  // before any point moves: the pairs are read at x^n
      break;
    case Stage::kPointLoads:
      point_loads_.spread(def_.solver.kernel, mpm.particles(), mpm.grid(),
                          sph_ ? sph_->columns.ax.data() : nullptr,
                          sph_ ? sph_->columns.ay.data() : nullptr);
      break;
    case Stage::kContactForces:
      couplingStage(s.dt, s.kick, &Coupling::addGridForces);
      break;
    case Stage::kFoldForces:
      mpm.foldForces();
      break;
    case Stage::kKick:
      mpm.gridVelocity(s.kick, true, damped_kick_);
      break;
    case Stage::kSidewallFriction:
      mpm.sidewallFriction(s.kick);
      break;
    case Stage::kContactCorrect:
      couplingStage(s.dt, s.kick, &Coupling::correctGridVelocity);
      break;
    case Stage::kCorrectedWalls:
      correctedWalls(s.kick);
      break;
    case Stage::kG2P:
      mpm.gridToParticle(s.dt, sph_ ? &mpm.tiles() : nullptr, s.info.clamped, s.info.finite);
      break;
    case Stage::kSleepNote:
      mpm.noteMovingNodes();
      break;
    case Stage::kSphMove:
      detail::sphMove(*sph_, sphWorld(), s.dt, s.kick, s.info.clamped, s.info.finite);
      break;
    case Stage::kConstitutive:
      mpm.constitutiveUpdate(s.dt);
      stress_lag_ = 0;  // USL: the stress is at the positions' time
      break;
    case Stage::kVolumeFit:
      mpm.fitVolumes(s.dt);
      break;
    case Stage::kContactReactions:
      couplingStage(s.dt, s.kick, &Coupling::afterMaterialStep);
      break;
    case Stage::kBodies:
      stepBodies(s.dt);
      break;
    case Stage::kCheckBlocks:
      checkBlocks(s.info);
      break;
  }
}

void World::keepBlocksAwake() {
  Sleep& sleep = mpm_.sleep();
  if (!sleep.on()) return;
  // Every block keeps the tiles within the margin of its box awake, moving or not (a block at
  // rest on the material may be pushed again by the node); so does every point load.
  if (hasContactBodies()) {
    const ContactBodies& bodies = *contactBodies();
    for (int b = 0; b < bodies.shapeCount(); ++b) {
      const Box box = bodies.bounds(b);
      sleep.keepAwake(box.min, box.max);
    }
  }
  const Particles& P = mpm_.particles();
  for (const PointLoads::Load& l : point_loads_.loads()) {
    const Vec2 x(P.x[l.particle], P.y[l.particle]);
    sleep.keepAwake(x, x);
  }
}

void World::correctedWalls(Real kick) {
  // A correction's impulses are forces the local damping must see, or it would move a static
  // equilibrium that a contact holds (it would damp the internal force and gravity alone, which
  // the contact balances): it damps the step's whole velocity change then.
  if (def_.solver.damping > 0) mpm_.dampVelocityChange(kick);
  mpm_.applyWalls();
}

void World::reverseVelocities() {
  mpm_.reverseVelocities();
  velocity_lag_ = -velocity_lag_;
  stress_lag_ = -stress_lag_;
}

void World::couplingStage(Real dt, Real kick, void (Coupling::*stage)(CouplingStep&)) {
  CouplingStep s{mpm_.particles(),   mpm_.grid(),         mpm_.tiles(), *contactBodies(),
                 def_.solver.kernel, def_.solver.gravity, dt,           kick};
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
  const bool had_loads = !point_loads_.empty();
  point_loads_.set(particle, mpm_.particles().size(), force, offset);
  const bool has_loads = !point_loads_.empty();
  if (has_loads != had_loads) compose();  // the first load came, or the last went
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
  return {};
}

}  // namespace mpm_sdem
