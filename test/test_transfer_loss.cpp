// Issue 40: a transfer whose energy loss does not grow as the step shrinks. A free elastic
// block in its first shear mode and a spinning elastic disk, no gravity, no walls touched: the
// total energy (kinetic and elastic) is conserved by the continuum, so whatever goes is the
// transfer's and the time integration's.
#include <gtest/gtest.h>

#include "helpers.hpp"

using namespace mpm_sdem;

namespace {

struct EnergyRun {
  Real loss;    // fraction of the total energy lost
  Real sweeps;  // full mass matrix sweeps per step
};

WorldDef freeBody(TransferScheme transfer, MassMatrix mass, Real cfl) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(1, 1), 0.04);
  def.solver.transfer = transfer;
  def.solver.mass_matrix = mass;
  def.solver.gravity = Vec2(0, 0);
  def.time_step.cfl = cfl;
  def.materials.push_back(test::elastic(1000, 1e5, 0.3));
  return def;
}

EnergyRun measureLoss(World& w, Real end) {
  const Real e0 = measure(w).total();
  test::runUntil(w, end);
  return {1 - measure(w).total() / e0, Real(w.massSweeps()) / Real(w.stepCount())};
}

// The block 0.4 m square, v_x = 0.2 cos(pi y / 0.4) m/s: its first shear mode (period 0.16 s).
EnergyRun shearMode(TransferScheme transfer, MassMatrix mass, Real cfl) {
  WorldDef def = freeBody(transfer, mass, cfl);
  def.bodies.push_back(test::rectangle(Vec2(0.3, 0.3), Vec2(0.7, 0.7), 2));
  World w(def);
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) P.vx[p] = 0.2 * std::cos(M_PI * (P.y[p] - 0.3) / 0.4);
  return measureLoss(w, 0.5);
}

// A disk of radius 0.2 m spinning rigidly at 2 rad/s.
EnergyRun spinningDisk(TransferScheme transfer, MassMatrix mass, Real cfl) {
  WorldDef def = freeBody(transfer, mass, cfl);
  def.bodies.push_back(test::disk(Vec2(0.5, 0.5), 0.2, 2));
  World w(def);
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.vx[p] = -2.0 * (P.y[p] - 0.5);
    P.vy[p] = 2.0 * (P.x[p] - 0.5);
  }
  return measureLoss(w, 1.0);
}

}  // namespace

// APIC loses a fixed part of what the grid cannot hold at every transfer, so a quarter of the
// step loses more: the shear mode at 10 cells across loses 26% at cfl 0.3 and 46% at 0.075.
TEST(TransferLoss, ApicLosesMoreWithEveryShorterStep) {
  const EnergyRun coarse = shearMode(TransferScheme::kApic, MassMatrix::kLumped, 0.3);
  const EnergyRun fine = shearMode(TransferScheme::kApic, MassMatrix::kLumped, 0.075);
  RecordProperty("loss_cfl_0.3", std::to_string(coarse.loss));
  RecordProperty("loss_cfl_0.075", std::to_string(fine.loss));
  EXPECT_GT(coarse.loss, 0.01);
  EXPECT_GT(fine.loss, 1.5 * coarse.loss);
}

// With the full mass matrix the PIC round trip is an identity and what is left is the time
// integration's error, a small gain that shrinks with the step (first order: a quarter of the
// step, a quarter of the error). Measured at 10 cells across: shear mode -4.3% -> -1.3%,
// spinning disk -0.46% -> -0.06% (at 20 cells: -0.86% -> -0.27%, -0.24% -> -0.08%).
TEST(TransferLoss, FullMassMatrixLossDoesNotGrowAsTheStepShrinks) {
  for (auto* scene : {&shearMode, &spinningDisk}) {
    const EnergyRun coarse = (*scene)(TransferScheme::kPic, MassMatrix::kFull, 0.3);
    const EnergyRun fine = (*scene)(TransferScheme::kPic, MassMatrix::kFull, 0.075);
    const bool shear = scene == &shearMode;
    SCOPED_TRACE(shear ? "shear mode" : "spinning disk");
    RecordProperty(shear ? "shear_loss_cfl_0.3" : "spin_loss_cfl_0.3", std::to_string(coarse.loss));
    RecordProperty(shear ? "shear_loss_cfl_0.075" : "spin_loss_cfl_0.075",
                   std::to_string(fine.loss));
    RecordProperty(shear ? "shear_sweeps_per_step" : "spin_sweeps_per_step",
                   std::to_string(coarse.sweeps));
    EXPECT_LT(std::abs(coarse.loss), 0.05);
    EXPECT_LT(std::abs(fine.loss), 0.5 * std::abs(coarse.loss));
    // Lumped PIC loses nearly all of it (measured 99.9%): the solve did the work.
    EXPECT_GT(coarse.sweeps, 2);
  }
}

// Momentum goes through the full mass matrix's round trip unchanged: sum_I (M v)_I = sum_p m_p
// v_p by the partition of unity, to the solve's tolerance.
TEST(TransferLoss, FullMassMatrixKeepsMomentum) {
  WorldDef def = freeBody(TransferScheme::kPic, MassMatrix::kFull, 0.3);
  def.bodies.push_back(test::disk(Vec2(0.5, 0.5), 0.2, 2));
  World w(def);
  Particles& P = w.particles();
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.vx[p] = 0.1 - 2.0 * (P.y[p] - 0.5);
    P.vy[p] = 0.05 + 2.0 * (P.x[p] - 0.5);
  }
  const Vec2 p0 = measure(w).momentum;
  test::runUntil(w, 0.2);
  EXPECT_LT((measure(w).momentum - p0).norm() / p0.norm(), 1e-5);
}
