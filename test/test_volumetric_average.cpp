// The volumetric average (SolverDef::volumetric_average, VolumetricAverage): each point's
// velocity divergence replaced by the volume-weighted mean over the nodes around it.
//  - A uniform divergence is its own mean: under a linear velocity field every point keeps its
//    gradient, at the free surface too (the weights of the nodes a point touches sum to one).
//  - Under an arbitrary field only the divergence moves (L - Lbar is a multiple of I at every
//    point), and the body's volume rate sum_p V_p tr L_p is kept (partition of unity): the
//    average redistributes the volume change, it does not make or lose any.
//  - In a world, the internal forces of the averaged stress still sum to zero: a free elastic
//    block ringing without gravity keeps its momentum to round-off, and its energy does not grow.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "helpers.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/mpm/mpm_solver.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/world.hpp"

using namespace mpm_sdem;

namespace {

// A 10 x 6 cm elastic block in a 20 x 20 cm box of 1 cm cells, binned and its grid filled.
MpmSolver block(KernelType kernel, bool averaged) {
  DomainDef domain;
  domain.min = Vec2(0, 0);
  domain.max = Vec2(0.2, 0.2);
  SolverDef solver;
  solver.kernel = kernel;
  solver.volumetric_average = averaged;
  BodyDef b;
  b.name = "block";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0.05, 0.07);
  b.shape.max = Vec2(0.15, 0.13);
  MpmSolver s(domain, 0.01, solver, {test::elastic(1000, 1e6, 0.3)}, {b});
  s.bin();
  s.clearGrid();
  s.particleToGrid(true, false);
  return s;
}

// Every node's pre-kick velocity set by f(x, y).
template <class F>
void setVelocity(Grid& G, F f) {
  for (int j = 0; j < G.ny; ++j)
    for (int i = 0; i < G.nx; ++i) {
      const Vec2 x = G.origin + Vec2(i, j) * G.h;
      const Vec2 v = f(x);
      G.vel0_x[G.index(i, j)] = v.x();
      G.vel0_y[G.index(i, j)] = v.y();
    }
}

const KernelType kKernels[] = {KernelType::kQuadraticBSpline, KernelType::kCubicBSpline,
                               KernelType::kGimp};

}  // namespace

TEST(VolumetricAverage, ALinearFieldKeepsEveryGradient) {
  const Mat2 A = (Mat2() << 0.3, -1.2, 0.7, -0.8).finished();  // 1/s, divergence -0.5
  for (KernelType k : kKernels) {
    MpmSolver s = block(k, true);
    setVelocity(s.grid(), [&](const Vec2& x) { return Vec2(A * x + Vec2(0.1, -0.2)); });
    s.averageVolumetricRate();
    const Particles& P = s.particles();
    ASSERT_GT(P.size(), 0u);
    Real worst = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Mat2 L = (Mat2() << P.lxx[p], P.lxy[p], P.lyx[p], P.lyy[p]).finished();
      worst = std::fmax(worst, (L - A).cwiseAbs().maxCoeff());
    }
    EXPECT_LT(worst, 1e-12) << "kernel " << static_cast<int>(k);
  }
}

TEST(VolumetricAverage, OnlyTheDivergenceMovesAndTheVolumeRateIsKept) {
  for (KernelType k : kKernels) {
    MpmSolver own = block(k, false), mean = block(k, true);
    std::mt19937 rng(7);
    std::uniform_real_distribution<Real> u(-1, 1);
    std::vector<Vec2> field(own.grid().mass.size());
    for (Vec2& v : field) v = Vec2(u(rng), u(rng));
    for (MpmSolver* s : {&own, &mean}) {
      Grid& G = s->grid();
      for (std::size_t n = 0; n < field.size(); ++n) {
        G.vel0_x[n] = field[n].x();
        G.vel0_y[n] = field[n].y();
      }
    }
    own.stressAndInternalForce(0);  // its own gradients, no stress update
    mean.averageVolumetricRate();
    const Particles &P = own.particles(), &Q = mean.particles();
    Real rate_own = 0, rate_mean = 0, scale = 0, worst = 0, moved = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Real v = P.volume0[p] * P.J[p];
      rate_own += v * (P.lxx[p] + P.lyy[p]);
      rate_mean += v * (Q.lxx[p] + Q.lyy[p]);
      scale += v * std::fabs(P.lxx[p] + P.lyy[p]);
      // L - Lbar = c I: the shear, the spin and the normal difference unchanged.
      worst = std::fmax(worst, std::fabs(P.lxy[p] - Q.lxy[p]) + std::fabs(P.lyx[p] - Q.lyx[p]) +
                                   std::fabs((P.lxx[p] - P.lyy[p]) - (Q.lxx[p] - Q.lyy[p])));
      moved = std::fmax(moved, std::fabs(P.lxx[p] - Q.lxx[p]));
    }
    EXPECT_LT(worst, 1e-9) << "kernel " << static_cast<int>(k);
    EXPECT_NEAR(rate_mean, rate_own, 1e-12 * scale) << "kernel " << static_cast<int>(k);
    EXPECT_GT(moved, 1.0) << "the average changed nothing";  // divergences of order 100 1/s
  }
}

// A free block ringing from a squeeze (each point's velocity towards the centre), no gravity,
// no wall reached in 0.05 s: momentum exact, and the energy of the averaged stress at most
// what it started with (the average removes volumetric stiffness, it adds none).
TEST(VolumetricAverage, AFreeBlockKeepsItsMomentumAndMakesNoEnergy) {
  WorldDef def;
  def.domain.min = Vec2(0, 0);
  def.domain.max = Vec2(0.2, 0.2);
  def.cell_size = 0.01;
  def.solver.gravity = Vec2(0, 0);
  def.solver.volumetric_average = true;
  def.materials = {test::elastic(1000, 1e6, 0.45)};
  BodyDef b;
  b.name = "block";
  b.shape.type = ShapeType::kRectangle;
  b.shape.min = Vec2(0.05, 0.07);
  b.shape.max = Vec2(0.15, 0.13);
  b.velocity = Vec2(0.3, 0.1);
  def.bodies = {b};
  World w(def);
  const std::vector<Stage>& stages = w.stages();
  ASSERT_NE(std::find(stages.begin(), stages.end(), Stage::kVolumetricAverage), stages.end());
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {  // squeezed towards the centre, and drifting
    P.vx[p] += -2.0 * (P.x[p] - 0.1);
    P.vy[p] += 1.0 * (P.y[p] - 0.1);
  }
  const Diagnostics d0 = measure(w);
  Real worst_momentum = 0, most_energy = 0;
  while (w.time() < 0.05) {
    stepStable(w);
    const Diagnostics d = measure(w);
    worst_momentum =
        std::fmax(worst_momentum, (d.momentum - d0.momentum).norm() / d0.momentum.norm());
    most_energy = std::fmax(most_energy, d.total() / d0.total());
  }
  std::printf("momentum error %.2e, largest energy / initial %.6f\n", worst_momentum, most_energy);
  EXPECT_LT(worst_momentum, 1e-12);
  EXPECT_LE(most_energy, 1.0 + 1e-6);
}
