#include "mpm_sdem/core/mpm/mpm_solver.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "../parallel.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "mpm_sdem/core/mpm/initial_stress.hpp"
#include "sweeps.hpp"
#include "transfer.hpp"

namespace mpm_sdem {

namespace {

int cellsAcross(Real extent, Real h, const char* what) {
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

MpmSolver::MpmSolver(const DomainDef& domain, Real cell_size, const SolverDef& solver,
                     const std::vector<MaterialDef>& materials, const std::vector<BodyDef>& bodies)
    : domain_(domain), def_(solver), viscous_dt_(std::numeric_limits<Real>::infinity()) {
  if (const Problem p = sizeProblem(domain, cell_size, bodies); !p.empty())
    throw std::invalid_argument("the world " + p.message);
  const Vec2 size = domain.max - domain.min;
  grid_.init(domain.min, cellsAcross(size.x(), cell_size, "width"),
             cellsAcross(size.y(), cell_size, "height"), cell_size);
  tiles_.init(grid_);
  tiles_.periodic_x = periodicX();
  for (const MaterialDef& m : materials) {
    params_.push_back(makeMaterialParams(m));
    flows_.push_back(materialTraits(m.model).flows);
    if (m.viscosity > 0)  // a fluid's (no other model reads it)
      viscous_dt_ = std::fmin(viscous_dt_, cell_size * cell_size * m.density *
                                               solver.inertia_scale / (2 * m.viscosity));
  }

  std::size_t count = 0;
  std::vector<std::vector<Vec2>> filled;
  for (const BodyDef& b : bodies) {
    if (b.material < 0 || b.material >= static_cast<int>(params_.size())) {
      throw std::invalid_argument("body '" + b.name + "' names no material");
    }
    if (b.points_per_cell < 1) throw std::invalid_argument("points_per_cell must be >= 1");
    filled.push_back(fillPoints(b.shape, domain.min, cell_size, b.points_per_cell));
    count += filled.back().size();
  }
  particles_.resize(count);
  std::size_t p = 0;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyDef& body = bodies[b];
    const MaterialDef& mat = materials[body.material];
    const Real spacing = cell_size / body.points_per_cell;
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
    if (body.geostatic)
      setLayerWeightAsStress(particles_, p - filled[b].size(), p, mat, -solver.gravity.y(), spacing,
                             domain.min.x());
  }
  // Points in tile order from the start, so that the sweeps read them in sequence.
  tiles_.bin(particles_, grid_);
  particles_.permute(tiles_.order);
  sleep_.init(def_.sleep, grid_, tiles_);
  // The capacities as the flowing bodies' lattice fills the nodes (the densest of them).
  int lattice = 1;
  for (const BodyDef& b : bodies)
    if (flows_[b.material]) lattice = std::max(lattice, b.points_per_cell);
  volume_fit_.init(grid_, def_.kernel, domain_.min, domain_.max, periodicX(), lattice);
  fits_ = def_.volume_fit && std::find(flows_.begin(), flows_.end(), 1) != flows_.end();
}

TimeStepChoice MpmSolver::materialStep(Real cfl, Real longest) const {
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
    if (sleep_.any()) {
      // The sleepers' speed changes only when some fall asleep or wake (their v is zero, their
      // J kept): scanned then, the awake runs every step. A maximum: the same in any order.
      if (sleepers_generation_ != sleep_.generation()) {
        sleepers_generation_ = sleep_.generation();
        sleepers_speed_ = 0;
        for (long p = 0; p < n; ++p)
          if (P.asleep[p]) sleepers_speed_ = faster(sleepers_speed_, p);
      }
      fastest = sleepers_speed_;
      for (const PointRun& r : sleep_.runs()) {
#pragma omp simd reduction(max : fastest)
        for (long p = r.begin; p < r.end; ++p) fastest = faster(fastest, p);
      }
      return;
    }
    if (detail::singleThread()) {
#pragma omp simd reduction(max : fastest)
      for (long p = 0; p < n; ++p) fastest = faster(fastest, p);
      return;
    }
#pragma omp parallel for simd schedule(static) reduction(max : fastest)
    for (long p = 0; p < n; ++p) fastest = faster(fastest, p);
  };
  // The inertia's scale s divides every squared wave speed (SolverDef::inertia_scale).
  const Real inv_s = 1 / def_.inertia_scale;
  if (params_.size() == 1 && !materialTraits(params_[0].model).own_wave_speed) {
    // One material with a solid's wave speed: no lookup and no pow, so the loop vectorises.
    const Real k = params_[0].modulus_over_density * inv_s, loose = params_[0].separation;
    fastestWith([k, loose](long, Real J) { return J > loose ? Real(0) : k * J; });
  } else {
    fastestWith([this, &P, inv_s](long p, Real J) {
      return squaredWaveSpeed(params_[P.material[p]], J) * inv_s;
    });
  }
  const Real cfl_dt = fastest > 0 ? cfl * grid_.h / fastest : std::numeric_limits<Real>::infinity();
  TimeStepChoice choice{longest, StepLimit::kMax};
  choice.takeShorter(cfl_dt, StepLimit::kCfl);
  // Explicit viscous diffusion: dt <= kappa_1 h^2 / (2 nu) with the kinematic viscosity nu =
  // eta / rho0 of the most diffusive fluid (the diffusion number h^2 / (4 nu) of an explicit
  // 2D Laplacian at kappa_1 = 0.5).
  if (viscous_dt_ < choice.dt / cfl) choice = {cfl * viscous_dt_, StepLimit::kViscous};
  return choice;
}

MpmSolver::Memory MpmSolver::memory() const {
  Memory m;
  particles_.forEachColumn(
      [&m](const auto& c) { m.particle_bytes += c.capacity() * sizeof(c[0]); });
  m.particle_bytes += tiles_.particleBytes();
  grid_.forEachField([&m](const auto& a) { m.grid_bytes += a.capacity() * sizeof(a[0]); });
  m.grid_nodes = grid_.nodeCount();
  m.active_nodes = tiles_.active.size() * Tiles::kSize * Tiles::kSize;
  return m;
}

void MpmSolver::bin() {
  tiles_.bin(particles_, grid_, false, sleep_.any() ? &sleep_.runs() : nullptr);
}

void MpmSolver::updateSleep(Real dt) {
  if (sleep_.update(particles_, tiles_, def_.kernel, dt))
    tiles_.rebin(particles_, grid_, sleep_.any() ? &sleep_.runs() : nullptr);
}

template <class F>
void MpmSolver::forActiveNodes(const std::vector<int>& tiles, F&& f) {
  tiles_.nodeRuns(grid_, tiles, node_runs_);
  detail::parallelFor(static_cast<long>(node_runs_.size()),
                      [&](long k) { f(node_runs_[k].first, node_runs_[k].end); });
}

void MpmSolver::clearGrid() {
  // Only the tiles the last step used hold values; every other node is zero already.
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

void MpmSolver::particleToGrid(bool momentum, bool force) {
  detail::particleToGrid(def_.kernel, {momentum, force, momentum && carriesAffine(def_.transfer)},
                         particles_, grid_, tiles_);
}

void MpmSolver::addSleepersMass() {
  // The sleepers' mass on the nodes the awake points use (the others are not updated).
  if (sleep_.any())
    forActiveNodes(tiles_.active,
                   [this](int first, int end) { sleep_.addMass(grid_, first, end); });
}

void MpmSolver::gridVelocity(Real kick, bool after_force, bool damp) {
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
  // The weight m g of the true mass: the grid's mass is the inertial one, s m.
  const Real gx = def_.gravity.x() / def_.inertia_scale, gy = def_.gravity.y() / def_.inertia_scale;
  const Real damping = damp ? def_.damping : Real(0);
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

void MpmSolver::scaleInertia() {
  const Real s = def_.inertia_scale;
  Grid& G = grid_;
  forActiveNodes(tiles_.active, [&G, s](int first, int end) {
    for (auto* a : {&G.mass, &G.mom_x, &G.mom_y})
      for (int i = first; i < end; ++i) (*a)[i] *= s;
  });
}

void MpmSolver::dampVelocityChange(Real kick) {
  if (kick == 0) return;
  Grid& G = grid_;
  const Real damping = def_.damping;
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

void MpmSolver::applyWalls(std::vector<Real>& vx, std::vector<Real>& vy) const {
  // Nodes on and beyond a domain side belong to its wall; corner nodes see both walls.
  const Grid& G = grid_;
  const int left = Grid::kPad, right = Grid::kPad + G.cells_x;
  const int bottom = Grid::kPad, top = Grid::kPad + G.cells_y;
  const DomainDef& d = domain_;
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

void MpmSolver::foldPeriodic(std::initializer_list<std::vector<Real>*> fields) {
  for (std::vector<Real>* a : fields)
    if (!a->empty()) grid_.foldPeriodicX(*a);  // empty: a field this scene does not use
}

Real* MpmSolver::clearedSidewallLoad() {
  if (!(domain_.sidewalls.width > 0)) return nullptr;
  sidewall_load_.resize(grid_.nodeCount());
  forActiveNodes(tiles_.active, [this](int first, int end) {
    std::fill(sidewall_load_.data() + first, sidewall_load_.data() + end, Real(0));
  });
  return sidewall_load_.data();
}

Real MpmSolver::sidewallCoefficient() const {
  return 2 * domain_.sidewalls.friction / domain_.sidewalls.width;
}

void MpmSolver::sidewallLoad() {
  Real* load = clearedSidewallLoad();
  if (!load) return;
  detail::withKernel(def_.kernel, [&](auto k) {
    detail::sidewallLoad<decltype(k)>(particles_, grid_, tiles_, sidewallCoefficient(), load);
  });
}

void MpmSolver::sidewallFriction(Real kick) {
  if (kick == 0) return;
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

void MpmSolver::stressAndInternalForce(Real dt) {
  detail::SidewallLoad walls;
  if (Real* load = clearedSidewallLoad()) walls = {sidewallCoefficient(), load};
  detail::stressAndInternalForce(def_.kernel, particles_, grid_, tiles_, params_, dt, walls,
                                 def_.volumetric_average);
}

void MpmSolver::averageVolumetricRate() {
  volumetric_average_.apply(def_.kernel, particles_, grid_, tiles_);
}

void MpmSolver::addSleepersForce() {
  if (sleep_.any())
    forActiveNodes(tiles_.active,
                   [this](int first, int end) { sleep_.addForce(grid_, first, end); });
}

void MpmSolver::gridToParticle(Real dt, const Tiles* material_points, long& clamped, bool& finite) {
  const detail::G2PSettings s{def_.pic_fraction,
                              dt,
                              domain_.min,
                              domain_.max,
                              periodicX(),
                              detail::asflipKeep(dt, def_.asflip_relaxation_time),
                              sleep_.any() ? &sleep_.runs() : nullptr};
  const bool usl = def_.stress_update == StressUpdate::kUsl;
  detail::gridToParticle(def_.kernel, def_.transfer, usl, particles_, grid_, s, clamped, finite,
                         material_points);
}

void MpmSolver::noteMovingNodes() {
  // The step's nodal velocities are final: the sleeping tiles they reach wake in the next step.
  if (sleep_.any()) sleep_.noteMovingNodes(grid_);
}

void MpmSolver::constitutiveUpdate(Real dt) {
  if (dt == 0) return;
  detail::updateStresses(particles_, params_, dt);
}

void MpmSolver::fitVolumes(Real dt) {
  if (dt == 0) return;  // the first step
  last_fit_ = volume_fit_.fit(particles_, grid_, flows_, dt);
}

Real MpmSolver::largestOverfill() {
  return volume_fit_.measure(particles_, grid_).largest_overfill;
}

void MpmSolver::reverseVelocities() {
  Particles& P = particles_;
  for (auto* v : {&P.vx, &P.vy, &P.bxx, &P.bxy, &P.byx, &P.byy}) {
    for (Real& a : *v) a = -a;
  }
}

}  // namespace mpm_sdem
