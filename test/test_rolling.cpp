// Rotation under friction (issue 15): an elastic disk of 10 cells per radius thrown without
// spin along a static floor block (cases::thrownDisk, IMP). Rigid-body mechanics of a solid
// cylinder: while it slides, friction mu g decelerates the centre and spins the disk up at
// 2 mu g / R; it rolls from t = v0 / (3 mu g) at 2/3 v0. The disk's elastic contact flattening
// (Hertz half-width 0.7 mm against R = 50 mm) changes none of these by more than 0.1%.
// Measured (IMP): deceleration 1.0000 mu g, spin-up 0.983, rolling at 0.991 of 2/3 v0 from 1.019
// v0 / (3 mu g), -omega R / v 1.003; over the offsets spin-up 0.980-0.984 (spread 0.40%) and
// rolling 0.991-0.992; started rolling, speed 0.993 v0 and energy -0.76%. Partitioned 1.0000,
// 0.981, 0.986, 1.028 and particle_surface 0.9999, 0.973, 0.986, 1.028 (deceleration, spin-up,
// rolling speed, rolling start).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "cases.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

namespace {

constexpr Real kG = 9.81, kR = 0.05;

// Every run of this file, by name. They run at once on first use, each on one core
// (test/parallel_runs.hpp): 12 runs of 4-16 s in about half their sum.
std::vector<std::pair<std::string, cases::ThrownDisk>> throws() {
  std::vector<std::pair<std::string, cases::ThrownDisk>> out;
  auto add = [&](std::string name, auto change) {
    cases::ThrownDisk c;
    change(c);
    out.emplace_back(std::move(name), c);
  };
  auto rolling_start = [](cases::ThrownDisk& c) {
    c.spin = true;
    c.mu = 0.5;
    c.v0 = 1;
  };
  add("imp", [](cases::ThrownDisk&) {});
  for (Real offset : {0.2, 0.4, 0.6, 0.8})
    add("offset " + std::to_string(offset), [&](cases::ThrownDisk& c) { c.offset = offset; });
  add("rolling", rolling_start);
  add("asflip", [](cases::ThrownDisk& c) { c.transfer = TransferScheme::kAsflip; });
  add("asflip rolling", [&](cases::ThrownDisk& c) {
    c.transfer = TransferScheme::kAsflip;
    rolling_start(c);
  });
  for (CouplingScheme scheme : {CouplingScheme::kPartitioned, CouplingScheme::kParticleSurface})
    add(couplingSchemeName(scheme), [&](cases::ThrownDisk& c) { c.scheme = scheme; });
  // The spin-up is fitted over [0.05, 0.6] s; the 1 cm run, the shortest, last.
  for (Real h : {0.005, 0.01})
    add("multi_velocity " + std::to_string(h), [&](cases::ThrownDisk& c) {
      c.scheme = CouplingScheme::kMultiVelocity;
      c.cell_size = h;
      c.t_end = 0.62;
    });
  return out;
}

struct Thrown {
  cases::ThrownDisk c;
  cases::Rolling r;
};

// A run of throws() by name, with what it measured printed once for all.
const Thrown& run(const std::string& name) {
  static const std::map<std::string, Thrown> runs = [] {
    const auto t = throws();
    const std::vector<cases::Rolling> r =
        test::runAll<cases::Rolling>(static_cast<int>(t.size()), [&](int i) {
          World w(cases::thrownDisk(t[i].second));
          return cases::rollDisk(w, t[i].second);
        });
    std::map<std::string, Thrown> out;
    for (std::size_t i = 0; i < t.size(); ++i) {
      const cases::ThrownDisk& c = t[i].second;
      std::printf(
          "%s: deceleration / (mu g) %.4f, spin-up / (2 mu g / R) %.4f, roll speed / (2/3 v0) "
          "%.4f (v0 for a rolling start), roll start / (v0 / 3 mu g) %.4f, -omega R / v %.4f, "
          "energy change %.2e\n",
          t[i].first.c_str(), r[i].deceleration / (c.mu * kG), r[i].spin_up / (2 * c.mu * kG / kR),
          r[i].roll_speed / (c.spin ? c.v0 : 2 * c.v0 / 3),
          r[i].roll_start / (c.v0 / (3 * c.mu * kG)), r[i].roll_ratio, r[i].energy_change);
      out[t[i].first] = {c, r[i]};
    }
    return out;
  }();
  return runs.at(name);
}

// A thrown disk against the rigid cylinder, with the tolerances: the centre decelerates
// at mu g (1%), spins up at 2 mu g / R (3%), rolls at 2/3 v0 (3%) from v0 / (3 mu g) (5%).
void expectRigidCylinder(const cases::ThrownDisk& c, const cases::Rolling& r) {
  EXPECT_NEAR(r.deceleration / (c.mu * kG), 1.0, 0.01);
  EXPECT_NEAR(r.spin_up / (2 * c.mu * kG / kR), 1.0, 0.03);
  EXPECT_NEAR(r.roll_speed / (2 * c.v0 / 3), 1.0, 0.03);
  EXPECT_NEAR(r.roll_start / (c.v0 / (3 * c.mu * kG)), 1.0, 0.05);
}

}  // namespace

// Tolerances: the 3% on the rolling speed and the spin-up, 5% on the time rolling
// starts. Before the fix (force and slip read at the point's centre, contact on the lattice's
// flat row) the disk did not spin at all on this floor (0% of the rate) and ended 38% slow.
TEST(Rolling, ThrownDiskSpinsUpThenRollsAtTwoThirdsOfItsSpeed) {
  const auto& [c, r] = run("imp");
  expectRigidCylinder(c, r);
  EXPECT_NEAR(r.roll_ratio, 1.0, 0.02) << "rolls without slip at the end";
}

// The lattice must not decide the physics: the disk and floor moved by fractions of a cell (the
// issue: within 1%). The points carry the disk's area, centroid and polar moment at every offset
// (pointVolumes); with the lattice's own staircase the spin-up spread 1.6% (centroid up to 0.16 mm
// off the outline's centre: a lever of up to e / (mu R) = 3% of the friction's moment).
TEST(Rolling, SameAtFiveLatticeOffsets) {
  std::vector<Real> spin, speed;
  for (Real offset : {0.0, 0.2, 0.4, 0.6, 0.8}) {
    const cases::Rolling& r = run(offset == 0 ? "imp" : "offset " + std::to_string(offset)).r;
    spin.push_back(r.spin_up);
    speed.push_back(r.roll_speed);
  }
  auto spread = [](const std::vector<Real>& v) {
    const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
    return (*hi - *lo) / *hi;
  };
  EXPECT_LT(spread(speed), 0.01);
  EXPECT_LT(spread(spin), 0.01);
}

// A disk rolling without slip on a flat floor keeps its energy: the contact's damping acts only
// on the normal motion, and rolling has none but the lattice's (issue: within 1% over 1 s).
TEST(Rolling, RollingDiskKeepsItsEnergy) {
  const auto& [c, r] = run("rolling");
  EXPECT_NEAR(r.energy_change, 0.0, 0.01);
  EXPECT_NEAR(r.roll_speed / c.v0, 1.0, 0.01);
  EXPECT_NEAR(r.roll_ratio, 1.0, 0.02);
}

// Issue 40's transfer, ASFLIP, on the same throw and the same rolling start, with the same
// tolerances. Measured: spin-up 0.9868, roll speed 0.9932, rolling energy -0.31% (APIC 0.9827,
// 0.9906, -0.76%). The softer disk of issue 40 (E = 1 MPa) is not asserted: APIC 0.937, 0.970,
// -2.7%; ASFLIP 0.947, 0.977, -0.91% (docs/method.md, Transfers).
TEST(Rolling, AsflipSpinsUpRollsAndKeepsTheRollingEnergy) {
  const auto& [c, r] = run("asflip");
  expectRigidCylinder(c, r);
  const auto& [rolling, e] = run("asflip rolling");
  EXPECT_NEAR(e.energy_change, 0.0, 0.01);
  EXPECT_NEAR(e.roll_speed / rolling.v0, 1.0, 0.01);
}

// The other schemes on the same throw, with the tolerances. Partitioned (seed 003): the
// wall of boundary particles moves with its host points and touches the block at the body's
// outline; its loads carry their moment from the contact point (the nodes lie 0.83 mm inside the
// outline, which cost 1.7% of the spin-up: 0.965). Before, the wall drifted off the turning disk
// (+-0.8 mm after a turn) and the disk hopped: 75% of the rate. Particle-to-surface (seed 002
// sec. 3): the friction impulse acts at the contact point, not at the point's centre (0.940).
TEST(Rolling, PartitionedAndParticleSurfaceSpinTheDiskUp) {
  for (CouplingScheme scheme : {CouplingScheme::kPartitioned, CouplingScheme::kParticleSurface}) {
    SCOPED_TRACE(couplingSchemeName(scheme));
    const auto& [c, r] = run(couplingSchemeName(scheme));
    expectRigidCylinder(c, r);
  }
}

// Multi-velocity (seed 002 sec. 2.4): the contact acts at grid nodes within half a cell of the
// contact point, and the material ahead of it is the side that approaches, so the normal impulses
// sit up to h/2 ahead and cost up to h / (2 mu R) of the friction's torque, a first-order error
// (0% spin before the distance check). CI compares 1 cm with 5 mm (5 and 10 cells per radius);
// the validation report's rolling case adds 2.5 mm for every scheme (at 2.5 mm the centre
// decelerates 1.8% faster than mu g, an open item in docs/limitations.md).
TEST(Rolling, MultiVelocitySpinUpConverges) {
  Real error[2];
  for (int k = 0; k < 2; ++k) {
    const auto& [c, r] = run("multi_velocity " + std::to_string(k == 0 ? 0.01 : 0.005));
    EXPECT_NEAR(r.deceleration / (c.mu * kG), 1.0, 0.02);
    error[k] = 1 - r.spin_up / (2 * c.mu * kG / kR);
    // The normal impulses lie at most half a cell ahead of the contact point.
    EXPECT_GT(error[k], -0.03);
    EXPECT_LT(error[k], c.cell_size / (2 * c.mu * kR));
  }
  // First order halves the error (measured: 0.466 at 1 cm, 0.162 at 5 mm). The disk rattles on
  // its nodal contacts, which scatters the spin-up by about +-0.03 (runs that differ only in
  // round-off or the floor's length): 0.5 + 2 x 0.03 / 0.466 = 0.63 is the bound.
  EXPECT_LT(error[1], 0.63 * error[0]) << "the error must shrink with the cell";
}
