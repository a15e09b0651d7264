// The five coupling schemes (coupling.hpp) on the same cases, each asserted for every scheme:
//  - Two-disk collision (seed 000 sec. 5.1.1, no gravity): material plus block momentum conserved
//    within 1% at every step, and the block leaves at least as fast as after a perfectly plastic
//    collision of the equal masses (1 m/s) less 10%, so that the contact really acted.
//  - Resting square (seed 000 sec. 5.2.1): an elastic square on a static block under g = 1 m/s^2;
//    the summed contact force on the block, averaged over 0.6 s once the square has settled,
//    equals the weight within 2%, and no point moves faster than 1 mm/s.
//  - Tunnelling: a rounded box thrown at 20 m/s into a granular bed; no material point ever
//    inside the block's core polygon, and the bed stops the block. The same rock as a cluster of
//    discs (seed 003) goes as deep as the spheropolygon.
// Scheme-specific:
//  - Particle-to-surface: the exchange never pulls (normal impulse >= 0 on every contact); at
//    every stuck contact the relative velocity after the exchange is the target normal velocity
//    (zero once the gap is closed) with no tangential part; at rest on the block the points in
//    contact move with it (normal velocity below 10 um/s, half of what gravity adds in a step).
//  - Partitioned: at every step the loads on the boundary particles sum to minus the forces on
//    the blocks, and all of it reaches the grid; in the wooden-block flow the wall's particle
//    count stays bounded by its length.
// Measured (imp, imp_grid, multi_velocity, particle_surface, partitioned): collision momentum
// error 3.0e-5, 3.0e-5, 2.0e-7, 2.5e-7, 2.0e-5; resting force 1.00000, 1.00000, 1.00000, 0.99999,
// 1.00001 W; the thrown rock's closest approach to its rounded outline (a = 5 mm) 2.94, 3.06,
// 4.91, 0.00 mm outside and 0.01 mm inside (the core never entered); the tearing flow's wall 444
// particles over 1.22 m, its fastest point after 0.6 s 0.34 m/s.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "block_helpers.hpp"
#include "cases.hpp"
#include "coupling/particle_surface.hpp"
#include "coupling/partitioned.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

namespace {

// Every scheme the table lists: a new one runs through the shared cases below.
std::vector<CouplingScheme> allSchemes() {
  std::vector<CouplingScheme> out;
  for (const SchemeTraits& t : couplingSchemes()) out.push_back(t.scheme);
  return out;
}

// Called after every step: the scheme-specific checks; "" or the first that fails. (A string,
// not assertions, so that runs on other threads report to the test that reads them.)
std::string stepProblem(const World& w) {
  const Coupling& c = *w.coupling();
  const std::string at = " at t = " + std::to_string(w.time());
  if (const auto* ps = dynamic_cast<const ParticleSurfaceCoupling*>(&c)) {
    for (const ParticleSurfaceCoupling::Record& r : ps->contacts()) {
      if (r.impulse.dot(r.normal) < 0) return "a tensile contact" + at;
      // Slip stops the approach only; stick also the sliding (eq. 47).
      const Vec2 aimed = r.stuck ? Vec2(r.target * r.normal) : Vec2(r.relative_after);
      if (std::abs(r.relative_after.dot(r.normal) - r.target) > 1e-9)
        return "normal relative velocity off its target" + at;
      if ((r.relative_after - aimed).norm() >= 1e-9) return "relative velocity off its aim" + at;
      if (r.gap <= 0 && r.target != 0) return "a closed gap with a target speed" + at;
    }
  }
  if (const auto* pt = dynamic_cast<const PartitionedCoupling*>(&c)) {
    Vec2 on_blocks(0, 0);
    for (const Blocks::Load& b : w.blocks()->coupling()) on_blocks += b.force;
    const Real scale = std::max<Real>(pt->loadSum().norm(), 1e-9);
    if ((pt->loadSum() + on_blocks).norm() >= 1e-9 * scale)
      return "boundary loads and block forces do not balance" + at;
    if ((pt->forceOnMaterial() - pt->loadSum()).norm() >= 1e-9 * scale)
      return "part of the boundary loads did not reach the grid" + at;
  }
  return "";
}

void checkStep(const World& w) {
  ASSERT_EQ(stepProblem(w), "");
}

// Seed 000 sec. 5.2.1's resting square, for every scheme at once (test/parallel_runs.hpp: 131 s
// of runs in about 66 s); each TEST_P reads its scheme's.
struct Resting {
  std::string problem;       // stepProblem's first, if any
  Real t = 0, dt = 0;        // s, at the end
  Vec2 force{0, 0};          // mean over the last 0.6 s, over the weight
  Real max_speed = 0;        // m/s, at the end
  Real fastest_contact = 0;  // particle-to-surface: fastest normal speed of a point in contact
};

Resting restingSquare(CouplingScheme scheme) {
  const Real h = 0.005, g = 1.0;
  World w(cases::restingSquare(h, 0.5, scheme));
  const Real weight = measure(w).mass * g;
  Resting out;
  auto step = [&] {
    stepStable(w);
    if (out.problem.empty()) out.problem = stepProblem(w);
  };
  // The soft contacts of the spring schemes ring with a period of about 0.3 s, decaying over
  // seconds (seed 000 Fig. 12); the penalty-free ones have no contact damping and keep a
  // vibration of about 0.1 mm/s. Settle for 2.4 s, then average over two periods.
  while (w.time() < 2.4) step();
  Vec2 sum(0, 0);
  long samples = 0;
  const Real end = w.time() + 0.6;
  while (w.time() < end) {
    step();
    sum += test::couplingForce(w, 0);
    ++samples;
    if (const auto* ps = dynamic_cast<const ParticleSurfaceCoupling*>(w.coupling())) {
      for (const ParticleSurfaceCoupling::Record& r : ps->contacts()) {
        const Vec2 v(w.particles().vx[r.particle], w.particles().vy[r.particle]);
        out.fastest_contact = std::max(out.fastest_contact, std::abs(v.dot(r.normal)));
      }
    }
  }
  out.force = sum / samples / weight;
  out.t = w.time();
  out.dt = w.chooseTimeStep().dt;
  out.max_speed = measure(w).max_speed;
  return out;
}

const Resting& resting(CouplingScheme scheme) {
  static const std::vector<Resting> all = [] {
    // multi_velocity's, the longest (it samples the 58 cm floor block every step), first.
    std::vector<CouplingScheme> order = allSchemes();
    std::stable_partition(order.begin(), order.end(),
                          [](CouplingScheme s) { return s == CouplingScheme::kMultiVelocity; });
    const std::vector<Resting> ran = test::runAll<Resting>(
        static_cast<int>(order.size()), [&](int i) { return restingSquare(order[i]); });
    std::vector<Resting> by_scheme(order.size());
    for (std::size_t i = 0; i < order.size(); ++i)
      by_scheme[static_cast<std::size_t>(order[i])] = ran[i];
    return by_scheme;
  }();
  return all.at(static_cast<std::size_t>(scheme));
}

class Schemes : public ::testing::TestWithParam<CouplingScheme> {};

TEST_P(Schemes, TwoDiskCollisionConservesMomentum) {
  cases::DiskCollision c;  // hard disk, CI resolution
  c.scheme = GetParam();
  const WorldDef def = cases::diskCollision(c);
  World w(def);
  const Diagnostics d0 = measure(w);
  Real worst = 0;
  while (w.time() < 0.02) {
    stepStable(w);
    checkStep(w);
    const Diagnostics d = measure(w);
    worst = std::max(worst, (d.momentum - d0.momentum).norm() / d0.momentum.norm());
  }
  const Real vb = w.blocks()->state(0).velocity.x();
  std::printf("%s: momentum error %.2e, block leaves at %.4f m/s\n", couplingSchemeName(GetParam()),
              worst, vb);
  EXPECT_LT(worst, 0.01);
  EXPECT_GT(vb, 0.9);
}

TEST_P(Schemes, RestingSquareForceEqualsWeight) {
  const Resting& r = resting(GetParam());
  std::printf("%s: at rest at t = %.2f s, force on the block (%.5f, %.5f) W, dt %.3g s\n",
              couplingSchemeName(GetParam()), r.t, r.force.x(), r.force.y(), r.dt);
  EXPECT_EQ(r.problem, "");
  EXPECT_NEAR(r.force.y(), -1.0, 0.02);  // the square pushes down with its weight
  EXPECT_NEAR(r.force.x(), 0.0, 0.02);
  EXPECT_LT(r.max_speed, 1e-3) << "not resting: sliding, sinking or bouncing";
  if (GetParam() == CouplingScheme::kParticleSurface) {
    EXPECT_LT(r.fastest_contact, 1e-5) << "points in contact move into or away from the block";
  }
}

TEST_P(Schemes, BlockThrownAt20MetresPerSecondDoesNotTunnel) {
  const WorldDef def = cases::rockIntoBed(GetParam());
  const BlockDef& rock = def.blocks[0];
  World w(def);
  const Particles& P = w.particles();
  Real deepest = -1;  // deepest any point came into the rounded outline (m)
  while (w.time() < 0.03) {
    stepStable(w);
    checkStep(w);
    const Blocks& B = *w.blocks();
    for (std::size_t p = 0; p < P.size(); ++p) {
      const Real d =
          closestOnCore(B.coreVertices(0), B.coreVertexCount(0), Vec2(P.x[p], P.y[p])).distance;
      deepest = std::max(deepest, rock.rounding - d);
      ASSERT_GE(d, 0) << "point " << p << " inside the block's polygon at t = " << w.time();
    }
  }
  const Real speed = w.blocks()->state(0).velocity.norm();
  std::printf(
      "%s: closest point %.2f mm outside the rounded outline (a = 5 mm), block at %.2f m/s\n",
      couplingSchemeName(GetParam()), -1e3 * deepest, speed);
  EXPECT_LT(speed, 10.0) << "the bed did not stop the block";
}

// Seed 003's clusters through the interface: the same rock as 25 discs of 5 mm filling its
// outline goes as deep into the bed, within 3% of the spheropolygon's deepest point in every
// scheme (measured 1.0-1.3%), and nothing goes non-finite.
TEST_P(Schemes, ClusterRockGoesAsDeepAsTheSpheropolygon) {
  Real deepest[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    World w(cases::rockIntoBed(GetParam(), k == 0 ? 0 : 0.005));
    const Blocks& B = *w.blocks();
    while (w.time() < 0.03) {
      stepStable(w);
      checkStep(w);
      for (int s = 0; s < B.shapesOf(0); ++s)
        deepest[k] =
            std::max(deepest[k], Real(0.08) - B.bounds(s).min.y());  // bed surface y = 8 cm
    }
  }
  std::printf("%s: deepest %.2f mm (spheropolygon), %.2f mm (cluster)\n",
              couplingSchemeName(GetParam()), 1e3 * deepest[0], 1e3 * deepest[1]);
  EXPECT_NEAR(deepest[1] / deepest[0], 1.0, 0.03);
}

// The partitioned wall in a flow that tears (the wooden-block scene at seed 003's 5 mm): each
// boundary particle follows a host point, and a segment split as the surface stretches gets a
// host of its own. The wall's length is the flow's surface: split past a cell, its segments are
// at least half a cell long where the surface stretches (2 particles per cell of length), and
// particles never merge where it shortens; the count stays within twice that density. With its
// neighbour's host, a torn gap was split again every step (the run passed 0.67 GB and did not
// finish).
// Until 0.7 s, past the settling flow's tear at 0.649 s: a boundary particle kept a host 3.2 cm
// away, whose affine field drove it into the floor, and its spring pushed the thin layer above
// up ever faster (3.5 m/s at 0.6502 s) until the step collapsed to nanoseconds. After the impact
// (t > 0.6 s) no point may move faster than it fell: sqrt(2 g H) = 1.98 m/s from the column's
// top (H = 0.2 m); the settling flow moves at 0.25 m/s.
TEST(Partitioned, WallStaysBoundedInATearingFlow) {
  WorldDef def = loadScene(test::sourcePath("config/scenes/debris_impact_fine.yaml")).world;
  def.coupling.scheme = CouplingScheme::kPartitioned;
  World w(def);
  const auto* wall = dynamic_cast<const PartitionedCoupling*>(w.coupling());
  ASSERT_NE(wall, nullptr);
  std::size_t most = 0;
  Real fastest = 0;  // after 0.6 s (m/s)
  const Real fall = std::sqrt(2 * 9.81 * 0.2);
  while (w.time() < 0.7 && fastest < fall) {  // stop as it blows up: its steps collapse
    stepStable(w);
    most = std::max(most, wall->boundaryPositions().size());
    if (w.time() < 0.6) continue;
    const Particles& P = w.particles();
    for (std::size_t p = 0; p < P.size(); ++p)
      fastest = std::max(fastest, std::hypot(P.vx[p], P.vy[p]));
  }
  Real surface = 0;  // the wall's length now (m)
  for (const auto& sg : wall->segments())
    surface += (wall->boundaryPositions()[sg[1]] - wall->boundaryPositions()[sg[0]]).norm();
  std::printf(
      "wall: %zu particles at most, %zu at %.3f s, length %.3f m; fastest point after "
      "0.6 s %.3f m/s\n",
      most, wall->boundaryPositions().size(), w.time(), surface, fastest);
  EXPECT_LT(static_cast<Real>(most), 4 * surface / def.cell_size);
  EXPECT_LT(fastest, fall);
}

// Issue 40, multi-rate contact: with coupling.normal_integration subcycled the springs take
// substeps within the material's step, so how finely they are cut (time.contact_factor) must not
// move the answer. The default scene's wooden blocks, left faces at rest after 1 s, at the
// default contact substep and at a half and a quarter of it: within 0.3 cm (the bound;
// the ensembles' spread at this cell is 0.003-0.04 cm, so 3 times it is smaller). Measured:
// 33.32 / 40.77, 33.31 / 41.00, 33.34 / 41.02 cm (the blocks' pairs stepped mode by mode at half
// their undamped bound; at the full bound block 1 moved 0.42 cm; with explicit dashpots at
// their damped bound 33.31 / 41.01, 33.34 / 40.88, 33.32 / 40.89). (The explicit springs moved
// block 1 by 4.6 cm between the same three factors; the material's own step still moves it:
// docs/method.md, Multi-rate contact.)
TEST(SubcycledContact, WoodenBlocksRestAtTheSamePlaceForEveryContactSubstep) {
  auto leftFaces = [](Real contact_factor) {
    WorldDef def = loadScene(test::sourcePath("config/scenes/debris_impact.yaml")).world;
    def.coupling.normal_integration = ContactIntegration::kSubcycled;
    def.time_step.contact_factor = contact_factor;
    World w(def);
    runUntil(w, 1.0);
    const Blocks& B = *w.blocks();
    Vec2 faces;
    for (int k = 0; k < 2; ++k) {
      const int i = B.indexOf(B.find(k == 0 ? "block2" : "block1"));
      faces[k] = B.bounds(B.firstShape(i)).min.x();
    }
    std::printf("contact_factor %g: block 2 at %.2f cm, block 1 at %.2f cm, %ld steps\n",
                contact_factor, 100 * faces[0], 100 * faces[1], w.stepCount());
    return faces;
  };
  const Vec2 base = leftFaces(0.1);
  for (const Real factor : {0.05, 0.025}) {
    const Vec2 finer = leftFaces(factor);
    EXPECT_NEAR(finer[0], base[0], 0.003) << "block 2, contact_factor " << factor;
    EXPECT_NEAR(finer[1], base[1], 0.003) << "block 1, contact_factor " << factor;
  }
}

// The table is the one statement of what each scheme is: one row per scheme in the enum's order
// (schemeTraits indexes it) and distinct names. What each can meet is the exclusions' table's
// (test_exclusions).
TEST(SchemeTraits, OneRowPerScheme) {
  const std::vector<SchemeTraits>& all = couplingSchemes();
  ASSERT_EQ(all.size(), 5u);
  std::set<std::string> names;
  for (std::size_t i = 0; i < all.size(); ++i) {
    EXPECT_EQ(static_cast<std::size_t>(all[i].scheme), i);
    EXPECT_EQ(&schemeTraits(all[i].scheme), &all[i]);
    names.insert(all[i].name);
  }
  EXPECT_EQ(names.size(), all.size());
}

INSTANTIATE_TEST_SUITE_P(AllSchemes, Schemes, ::testing::ValuesIn(allSchemes()),
                         [](const ::testing::TestParamInfo<CouplingScheme>& i) {
                           return std::string(couplingSchemeName(i.param));
                         });

}  // namespace
