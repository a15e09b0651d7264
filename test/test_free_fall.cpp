// Test 2: one material point in free fall follows x = x0 + v0 t + g t^2 / 2 to round-off at every
// step, for every kernel, transfer and stress-update order. A solver that starts the leapfrog
// with a full kick instead of half of one is off by g t dt / 2 (2.5 mm here), a million times the
// tolerance of 1e-9 m.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "helpers.hpp"

using namespace mpm_sdem;

namespace {

struct Case {
  KernelType kernel;
  TransferScheme transfer;
  StressUpdate update;
};

class FreeFall : public ::testing::TestWithParam<Case> {};

void fall(const Case& c, Real inertia_scale) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(4, 10), 0.1);
  def.solver.kernel = c.kernel;
  def.solver.transfer = c.transfer;
  def.solver.pic_fraction = 0;
  def.solver.stress_update = c.update;
  def.solver.gravity = Vec2(0, -9.81);
  def.solver.inertia_scale = inertia_scale;
  def.time_step.automatic = false;
  def.time_step.fixed = 1e-3;
  def.materials.push_back(test::elastic(1000, 1e6, 0.3));
  // One point: a 1-point-per-cell body covering a single lattice site.
  BodyDef b = test::rectangle(Vec2(1.0, 6.0), Vec2(1.1, 6.1), 1);
  b.velocity = Vec2(1.5, 2.0);
  def.bodies.push_back(b);
  World w(def);
  ASSERT_EQ(w.particles().size(), 1u);
  const Vec2 x0(w.particles().x[0], w.particles().y[0]);
  const Vec2 v0 = b.velocity;
  for (int n = 1; n <= 500; ++n) {
    w.step(1e-3);
    const Real t = w.time();
    const Vec2 expected = x0 + v0 * t + 0.5 * def.solver.gravity / inertia_scale * t * t;
    ASSERT_NEAR(w.particles().x[0], expected.x(), 1e-9) << "step " << n;
    ASSERT_NEAR(w.particles().y[0], expected.y(), 1e-9) << "step " << n;
  }
}

TEST_P(FreeFall, FollowsTheParabola) {
  fall(GetParam(), 1);
}

// Scaled inertia (SolverDef::inertia_scale s): the weight keeps the true mass and the inertia is
// s times it, so a free point falls at g / s, to the same round-off.
TEST_P(FreeFall, ScaledInertiaFallsAtGOverS) {
  fall(GetParam(), 16);
}

INSTANTIATE_TEST_SUITE_P(
    AllSchemes, FreeFall,
    ::testing::Values(Case{KernelType::kQuadraticBSpline, TransferScheme::kApic,
                           StressUpdate::kUsf},
                      Case{KernelType::kQuadraticBSpline, TransferScheme::kPic, StressUpdate::kUsl},
                      Case{KernelType::kCubicBSpline, TransferScheme::kFlip, StressUpdate::kUsf},
                      Case{KernelType::kGimp, TransferScheme::kFlip, StressUpdate::kUsl},
                      Case{KernelType::kGimp, TransferScheme::kApic, StressUpdate::kUsf}));

}  // namespace

// A fixed step above the critical one is refused before the first step, naming the term and the
// step the automatic choice would take (issue 7, stability on hard cases). The body: E = 1 MPa,
// nu = 0.3, rho = 1000 kg/m^3 (P-wave speed 36.7 m/s) at 2.5 m/s in 10 cm cells: critical CFL
// step h / (c + |v|) = 2.55 ms, automatic 0.3 of it; 1 ms runs (above), 10 ms is refused.
TEST(FixedStep, AboveTheCriticalStepIsRefused) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(4, 10), 0.1);
  def.time_step.automatic = false;
  def.time_step.fixed = 1e-2;
  def.materials.push_back(test::elastic(1000, 1e6, 0.3));
  BodyDef b = test::rectangle(Vec2(1.0, 6.0), Vec2(1.1, 6.1), 1);
  b.velocity = Vec2(1.5, 2.0);
  def.bodies.push_back(b);
  try {
    World w(def);
    FAIL() << "a 10 ms step was accepted";
  } catch (const std::invalid_argument& e) {
    const std::string msg = e.what();
    const Real E = 1e6, nu = 0.3, K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
    const Real critical = 0.1 / (std::sqrt((K + 4 * G / 3) / 1000) + 2.5);
    char expected[160];
    std::snprintf(expected, sizeof expected,
                  "time.dt = 0.01 s is above the critical step %.3g s of the cfl term", critical);
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
    std::snprintf(expected, sizeof expected, "set time.dt: auto (it would take %.3g s)",
                  0.3 * critical);
    EXPECT_NE(msg.find(expected), std::string::npos) << msg;
  }
}
