// Issue 44: intrusion forces against resistive force theory (cases::Plate, validation case
// intrusion), at the CI resolution (1 cm cells: the 5 cm plate 5 cells long).
//  - RFT's generic stresses (Li, Zhang & Goldman 2013) at the angles where their Fourier series
//    reduces to sums of its published coefficients.
//  - The horizontal plate pushed down is a strip footing: its force a line in depth whose slope
//    is bearing capacity's gamma N_q B and whose intercept gamma B^2 N_gamma / 2 (the term RFT
//    leaves out); the vertical plate dragged along x at 4 and 8 cm: the force per depth nearly
//    constant (RFT's linear law), and its ratio to the push's the generic shapes' (no zeta).
//  - Without weight or strength the plate meets the swept material's momentum, rho L v^2.
//  - Under ASFLIP the dragged plate's force does not move when the step halves (issue 90).
//  - A run stopped at a checkpoint and continued in a new world is the run that never stopped,
//    bit for bit (the report's 1.25 mm runs take hours; cases::PlateCheckpoints).
// The bands come from the report's study at 1 cm, 5 mm and 2.5 mm (docs/validation/REPORT.md,
// cases intrusion and intrusion_transfer; docs/robots.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "cases.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

// alpha_z(0, pi/2): A00 + A10 + B11 + B01 + B-11 = 1.000 N/cm^3 (a flat plate pushed straight
// down); alpha_x(pi/2, 0): -C11 + C01 - C-11 = 0.370 (a vertical plate dragged); alpha_x(beta,
// pi/2) = (-C11 + C-11 + D10) sin 2 beta = 0.219 sin 2 beta; alpha_z(pi/2, pi/2) = A00 - A10 +
// B01 - B11 - B-11 = 0.128. Exact sums of the published coefficients.
TEST(Rft, GenericStressesAreThePublishedSums) {
  EXPECT_NEAR(cases::rftGeneric(0, M_PI / 2).z, 1.000e6, 1e-6);
  EXPECT_NEAR(cases::rftGeneric(0, M_PI / 2).x, 0, 1e-6);
  EXPECT_NEAR(cases::rftGeneric(M_PI / 2, 0).x, 0.370e6, 1e-6);
  EXPECT_NEAR(cases::rftGeneric(M_PI / 2, M_PI / 2).z, 0.128e6, 1e-6);
  for (const double beta : {-1.2, -0.5, 0.3, 0.9})
    EXPECT_NEAR(cases::rftGeneric(beta, M_PI / 2).x, 0.219e6 * std::sin(2 * beta), 1e-6);
}

// The bands: the push's slope over gamma N_q B within 0.95-1.3 and its intercept over
// gamma B^2 N_gamma / 2 within 0.8-2.6 (the report: 1.02-1.19 and 1.04-2.01 from 2.5 mm to 1 cm);
// the drag's force ratio from 4 to 8 cm within 1.5-2.0 (RFT: 2) and alpha_x(drag) / alpha_z(push)
// within RFT's 0.37 +- 30%. Measured: 1.15, 2.01, 1.70, 0.352.
TEST(Intrusion, PushedPlateIsAStripFootingAndDragsKeepRftsShape) {
  cases::Plate push;
  push.cell_size = 0.01;
  // The push and the two drags at once (test/parallel_runs.hpp).
  auto drag_at = [](double depth) {
    cases::Plate c;
    c.cell_size = 0.01;
    c.angle = 90;
    c.direction = 0;
    c.depth = depth;
    return c;
  };
  struct Moved {
    cases::PlateLines line;
    double drag = 0;
  };
  const std::vector<Moved> runs = test::runAll<Moved>(3, [&](int i) {
    Moved out;
    const cases::Plate c = i == 0 ? push : drag_at(i == 1 ? 0.04 : 0.08);
    World w(cases::plateIntrusion(c));
    if (i == 0)
      out.line = cases::pushLines(c, cases::movePlate(w, c));
    else
      out.drag = -cases::dragMean(c, cases::movePlate(w, c)).x();
    return out;
  });
  const cases::PlateLines& line = runs[0].line;
  const double phi = cases::bladeFrictionAngle(cases::Blade());
  const cases::BearingFactors f = cases::bearingFactors(phi);
  const double nq = f.n_q, ng = f.n_gamma, gamma = 1500 * 9.81, B = push.length;
  std::printf("push: F_z = %.0f + %.0f z N/m (bearing capacity: %.0f + %.0f z)\n", line.az, line.kz,
              0.5 * gamma * B * B * ng, gamma * nq * B);
  EXPECT_GT(line.kz / (gamma * nq * B), 0.95);
  EXPECT_LT(line.kz / (gamma * nq * B), 1.3);
  EXPECT_GT(line.az / (0.5 * gamma * B * B * ng), 0.8);
  EXPECT_LT(line.az / (0.5 * gamma * B * B * ng), 2.6);

  const double drag[2] = {runs[1].drag, runs[2].drag};
  const double alpha_drag = drag[1] / (0.08 * 0.05), alpha_push = line.kz / 0.05;
  std::printf(
      "drag: %.1f N/m at 4 cm, %.1f at 8 cm; alpha_x(90, drag) / alpha_z(0, push) %.3f "
      "(generic %.3f)\n",
      drag[0], drag[1], alpha_drag / alpha_push,
      cases::rftGeneric(M_PI / 2, 0).x / cases::rftGeneric(0, M_PI / 2).z);
  EXPECT_GT(drag[1] / drag[0], 1.5);
  EXPECT_LT(drag[1] / drag[0], 2.0);
  EXPECT_GT(alpha_drag / alpha_push, 0.26);
  EXPECT_LT(alpha_drag / alpha_push, 0.48);
}

// Inertia alone: without gravity and without shear strength (phi 0: the points carry pressure
// only) the plate pushed down at constant speed meets nothing but the momentum of the material
// it sweeps; given the plate's speed, that is rho L v^2 (lambda_0 = 1, dynamic RFT's inertial
// term), and it scales as v^2 (no other stress scale). ASFLIP at 1 cm: measured 1.08 and 1.17
// at 1 and 2 m/s, at 5 mm 1.01 and 0.99 (validation case intrusion_transfer); the band 25%
// holds the 1 cm cells' 8-17% above the finer. APIC at 1 cm gives 2.03 and 1.68 (its loss per
// transfer drags on the shear bands), so the bound also catches a transfer that loses.
TEST(Intrusion, WithoutWeightOrStrengthThePlateMeetsTheSweptMomentum) {
  double lambda[2];
  for (int k = 0; k < 2; ++k) {
    cases::Plate c;
    c.cell_size = 0.01;
    c.speed = k == 0 ? 1.0 : 2.0;
    c.gravity = 0;
    c.friction_angle = 0;
    c.transfer = TransferScheme::kAsflip;
    World w(cases::plateIntrusion(c));
    const double force = cases::pushMean(c, cases::movePlate(w, c)).y();
    lambda[k] = force / (1500 * c.length * c.speed * c.speed);
    std::printf("v %.0f m/s: mean F_z %.1f N/m, lambda_0 %.3f\n", c.speed, force, lambda[k]);
  }
  EXPECT_NEAR(lambda[0], 1, 0.25);
  EXPECT_NEAR(lambda[1], 1, 0.25);
  EXPECT_GT(lambda[1] / lambda[0], 0.9);
  EXPECT_LT(lambda[1] / lambda[0], 1.2);
}

// Issue 90: a tool's force must not depend on the step. Under APIC it does: each transfer loses
// the velocity jump between the points the contact drives and the sand sliding past the tool,
// and the tool pays for it again every step, a force that grows as v / dt (docs/robots.md, What
// the cell does to a tool's force). ASFLIP keeps that jump. The upright plate dragged at 6 cm,
// 2 cm cells: ASFLIP measured 383.7 / 384.3 N/m at the full and the half step (0.14%; 377.1 /
// 376.7 at 1 cm), APIC 656.3 / 641.5 (2.2%; 508.7 / 550.7 at 1 cm, 8%). The 1% band holds
// ASFLIP and catches a transfer that loses per step.
TEST(Intrusion, DragUnderAsflipDoesNotMoveWhenTheStepHalves) {
  double drag[2];
  for (int k = 0; k < 2; ++k) {
    cases::Plate c;
    c.cell_size = 0.02;
    c.angle = 90, c.direction = 0, c.depth = 0.06;
    c.transfer = TransferScheme::kAsflip;
    c.step_scale = k == 0 ? 1 : 0.5;
    World w(cases::plateIntrusion(c));
    drag[k] = -cases::dragMean(c, cases::movePlate(w, c)).x();
    std::printf("step x%g: drag %.2f N/m\n", c.step_scale, drag[k]);
  }
  EXPECT_NEAR(drag[1] / drag[0], 1, 0.01);
}

// A drag stopped once while it descends and once while it is dragged, each time continued in a
// new world from the checkpoint it wrote: every sample, the step count and the end equal the
// uninterrupted run's to the bit, and the finished run removes its checkpoint; a run writing
// checkpoints as it goes (42 of them here, counted with strace) computes the same. A checkpoint
// written for another plate is not used (the run starts over).
TEST(Intrusion, RunContinuedFromACheckpointIsTheUninterruptedRun) {
  cases::Plate c;
  c.cell_size = 0.01;
  c.direction = 0;  // a drag: descends to 3 cm, then 3 L along x
  c.depth = 0.03;
  c.length = 0.03;
  c.speed = 1;  // ten times the report's: a tenth of the steps
  World whole(cases::plateIntrusion(c));
  const cases::PlateRun a = cases::movePlate(whole, c);
  ASSERT_GT(a.travel.size(), 50u);
  const std::string path = ::testing::TempDir() + "mpm_sdem_plate.checkpoint";
  std::filesystem::remove(path);
  const long descending = 20;  // of about 300 steps down
  for (const long stop : {descending, a.steps / 2}) {
    World first(cases::plateIntrusion(c));
    const cases::PlateRun part = cases::movePlate(first, c, {path, 600, stop});
    EXPECT_FALSE(part.finished);
    EXPECT_EQ(part.steps, stop);
    ASSERT_TRUE(std::filesystem::exists(path));
    World second(cases::plateIntrusion(c));
    const cases::PlateRun rest = cases::movePlate(second, c, {path});
    EXPECT_TRUE(rest.finished);
    EXPECT_EQ(rest.resumed_from, stop);
    EXPECT_FALSE(std::filesystem::exists(path));
    EXPECT_EQ(rest.steps, a.steps);
    EXPECT_EQ(rest.travel, a.travel);
    EXPECT_EQ(rest.depth, a.depth);
    EXPECT_EQ(rest.fx, a.fx);
    EXPECT_EQ(rest.fz, a.fz);
    EXPECT_EQ(second.time(), whole.time());
  }
  // Writing checkpoints as it goes (one every 20 ms of wall time, many in a run of seconds) does
  // not change the run that goes on after each.
  {
    World saving(cases::plateIntrusion(c));
    const cases::PlateRun b = cases::movePlate(saving, c, {path, 0.02});
    EXPECT_EQ(b.steps, a.steps);
    EXPECT_EQ(b.fx, a.fx);
    EXPECT_EQ(b.fz, a.fz);
    EXPECT_FALSE(std::filesystem::exists(path));
  }
  World first(cases::plateIntrusion(c));
  cases::movePlate(first, c, {path, 600, descending});
  cases::Plate other = c;
  other.speed = 2;
  World w(cases::plateIntrusion(other));
  const cases::PlateRun fresh = cases::movePlate(w, other, {path, 600, 5});
  EXPECT_EQ(fresh.resumed_from, 0);
  EXPECT_EQ(fresh.steps, 5);
  std::filesystem::remove(path);
}
