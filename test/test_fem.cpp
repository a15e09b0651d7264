// Deformable FEM bodies (seed 002 sec. 2.3 and 3, issue 18):
//  - Meshes: CGAL's mesher fills an L-shaped outline (area, closed boundary, edge sizes);
//    meshProblem names what is wrong with a bad mesh.
//  - Segments: a point near the outline belongs to the nearest boundary segment, inside or out.
//  - Elements: a plane-strain cantilever under its own weight against Euler-Bernoulli in tip
//    deflection and first frequency, converging at second order in the element size; a free
//    corotational body spinning a full turn keeps its energy and gains no strain.
//  - Contact: the elastic disk of seed 002 sec. 4.1 (2D) slides and rolls on an FEM plate at
//    eq. 55's acceleration for R = element / cell = 1 and 8; an FEM block falls onto a static
//    block and a wall and rests on them.
//  - Issue 18's validation 4: an elastic bounce off the material loses no more energy than a
//    rigid block's; no material point enters the body in a 20 m/s impact.
//  - Seed 002 sec. 4.3: the water column through the elastic gate, the gate's peak against the
//    published range.
//  - Issue 77, multi-rate FEM: the contact impulse reaches a body whole in any number of
//    substeps; the layer on a clamped beam deflects as single-rate within 1% at kappa_1 0.15
//    and 0.075 (5.0% above it at 0.3), and no run gains energy.
// Measured: cantilever tip 0.8286 and 0.9481 of Euler-Bernoulli's 5.356 mm (extrapolated 0.988),
// frequency 9.310 and 8.683 Hz (extrapolated 8.474 against 8.467 Hz); the disk on the plate
// slides at 5.532 (R = 1) and 5.530 (R = 8) against 5.549 m/s^2 and rolls at 4.437 and 4.497
// against 4.624 (rigid incline 4.424), IMP slides at 5.519; the bounce loses 60.31% against the
// rigid block's 60.56%; the impact puts no point inside (particle_surface) and at most 1.83 mm
// deep with r_p = 7.07 mm (IMP); the gate peaks at 46.15 mm at 0.242 s, Mach 0.066; the layer on
// the beam 2.1689 mm single-rate (47,982 steps), multi-rate 2.2769 / 2.1839 / 2.1665 mm at kappa_1
// 0.3 / 0.15 / 0.075 (2,330 / 4,650 / 9,296 steps).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "cases.hpp"
#include "helpers.hpp"
#include "mpm_sdem/core/fem/fem_bodies.hpp"
#include "mpm_sdem/mesh/mesher.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;
using namespace mpm_sdem::cases;

namespace {

Real meshArea(const FemMesh& m) {
  Real a = 0;
  for (const auto& t : m.triangles)
    a += 0.5 * cross(m.nodes[t[1]] - m.nodes[t[0]], m.nodes[t[2]] - m.nodes[t[0]]);
  return a;
}

// The shape forEachContact would pick for x among the body's segments: the least distance.
CoreDistance nearest(const FemBodies& B, const Vec2& x, int& shape) {
  CoreDistance best;
  best.distance = std::numeric_limits<Real>::infinity();
  for (int s = 0; s < B.shapeCount(); ++s) {
    const CoreDistance d = B.closest(s, x);
    if (d.distance < best.distance) {
      best = d;
      shape = s;
    }
  }
  return best;
}

FemBodyDef squareBody(Real side, Real size) {
  FemBodyDef d;
  d.name = "square";
  d.mesh = meshPolygon({{0, 0}, {side, 0}, {side, side}, {0, side}}, size);
  return d;
}

}  // namespace

TEST(FemMesh, LShapeIsFilledWithSmallTrianglesAndAClosedBoundary) {
  const std::vector<Vec2> L = {{0, 0}, {2, 0}, {2, 1}, {1, 1}, {1, 2}, {0, 2}};
  const Real size = 0.1;
  const FemMesh m = meshPolygon(L, size);
  EXPECT_EQ(meshProblem(m).text(), "");
  EXPECT_NEAR(meshArea(m), 3.0, 1e-12);
  Real longest = 0;
  for (const auto& t : m.triangles)
    for (int k = 0; k < 3; ++k)
      longest = std::max(longest, (m.nodes[t[k]] - m.nodes[t[(k + 1) % 3]]).norm());
  EXPECT_LE(longest, size * (1 + 1e-9));
  // The boundary is one closed loop of the outline's length (8 m): every node on it starts one
  // edge and ends one.
  const std::vector<BoundaryEdge> edges = boundaryEdges(m);
  Real perimeter = 0;
  std::multiset<int> starts, ends;
  for (const BoundaryEdge& e : edges) {
    perimeter += (m.nodes[e.b] - m.nodes[e.a]).norm();
    starts.insert(e.a);
    ends.insert(e.b);
  }
  EXPECT_NEAR(perimeter, 8.0, 1e-12);
  EXPECT_EQ(starts, ends);
  EXPECT_EQ(starts.size(), std::set<int>(starts.begin(), starts.end()).size());
}

TEST(FemMesh, ProblemsAreNamed) {
  FemMesh m;
  m.nodes = {{0, 0}, {1, 0}, {0, 1}, {5, 5}};
  m.triangles = {{0, 1, 2}};
  EXPECT_NE(meshProblem(m).message.find("node 3 belongs to no triangle"), std::string::npos);
  m.nodes.pop_back();
  EXPECT_EQ(meshProblem(m).text(), "");
  m.triangles = {{0, 2, 1}};
  EXPECT_NE(meshProblem(m).message.find("clockwise"), std::string::npos);
  m.triangles = {{0, 1, 7}};
  EXPECT_NE(meshProblem(m).message.find("names node 7"), std::string::npos);
  EXPECT_THROW(meshPolygon({{0, 0}, {1, 1}, {1, 0}, {0, 1}}, 0.1), std::invalid_argument);
  EXPECT_THROW(meshPolygon({{0, 0}, {1, 0}, {0, 1}}, 1e-5), std::invalid_argument);
}

TEST(FemSegments, APointBelongsToTheNearestFaceInsideAndOut) {
  // A 1 m square of 0.25 m triangles: the claim behind a face is half its triangle's depth.
  const FemBodies B({squareBody(1, 0.25)}, Vec2(0, 0));
  int s = -1;
  // Above the top face.
  CoreDistance d = nearest(B, Vec2(0.4, 1.03), s);
  EXPECT_NEAR(d.distance, 0.03, 1e-12);
  EXPECT_NEAR(d.normal.y(), 1, 1e-12);
  // 1 cm inside the top face, 3 cm from the left one: the top face's (a corner's two claims
  // are split by its bisector).
  d = nearest(B, Vec2(0.03, 0.99), s);
  EXPECT_NEAR(d.distance, -0.01, 1e-12);
  EXPECT_NEAR(d.normal.y(), 1, 1e-12);
  d = nearest(B, Vec2(0.01, 0.97), s);
  EXPECT_NEAR(d.distance, -0.01, 1e-12);
  EXPECT_NEAR(d.normal.x(), -1, 1e-12);
  // Outside a corner: the distance to the corner, along the diagonal.
  d = nearest(B, Vec2(1.03, 1.04), s);
  EXPECT_NEAR(d.distance, 0.05, 1e-12);
  EXPECT_NEAR(d.normal.x(), 0.6, 1e-12);
  // Deep inside: no face claims it.
  d = nearest(B, Vec2(0.5, 0.5), s);
  EXPECT_TRUE(std::isinf(d.distance));
}

// Linear triangles are too stiff in bending by O(h^2) (the constant-strain element's parasitic
// shear): at h = H/2 and H/4 the errors must fall about fourfold, and the Richardson
// extrapolation (4 f(h/2) - f(h)) / 3 must meet Euler-Bernoulli within 2% (the beam is L/H = 20:
// Timoshenko's shear adds 0.26% to the deflection). At h = H/8 the deflection alone is 0.981 of
// Euler-Bernoulli (6,542 elements, 244 s: too long for CI; the report's fem_cantilever).
TEST(FemCantilever, DeflectionAndFrequencyConvergeToEulerBernoulli) {
  const Cantilever coarse = cantilever(0.025), fine = cantilever(0.0125);
  const Real e1 = 1 - coarse.static_tip / coarse.euler_bernoulli;
  const Real e2 = 1 - fine.static_tip / fine.euler_bernoulli;
  std::printf("tip: %.4g, %.4g m against %.4g m (%d, %d elements, %.1f s)\n", coarse.static_tip,
              fine.static_tip, fine.euler_bernoulli, coarse.elements, fine.elements,
              coarse.seconds + fine.seconds);
  std::printf("frequency: %.4f, %.4f Hz against %.4f Hz\n", coarse.frequency, fine.frequency,
              fine.frequency_eb);
  EXPECT_GT(e1, 0);  // stiff, from below
  EXPECT_GT(e1 / e2, 3.0);
  EXPECT_LT(e1 / e2, 5.0);
  const Real tip = (4 * fine.static_tip - coarse.static_tip) / 3;
  EXPECT_NEAR(tip / fine.euler_bernoulli, 1, 0.02);
  const Real f = (4 * fine.frequency - coarse.frequency) / 3;
  EXPECT_NEAR(f / fine.frequency_eb, 1, 0.02);
  EXPECT_GT(coarse.frequency, fine.frequency);  // stiff: converging from above
}

// The corotational element takes a rigid rotation out before its linear law: a free square
// spinning at 2 rad/s for a full turn keeps its kinetic energy and builds next to no strain (the
// centrifugal stretch: rho w^2 L^2 / E ~ 4e-9 of the energy), while the linear element reads the
// rotation as strain and does not.
TEST(FemCorotational, AFreeSpinningBodyKeepsItsEnergyThroughAFullTurn) {
  auto spin = [](FemModel model) {
    FemBodyDef d = squareBody(1, 0.2);
    d.model = model;
    d.youngs_modulus = 1e7;
    WorldDef w;
    w.domain.min = Vec2(-2, -2);
    w.domain.max = Vec2(3, 3);
    w.cell_size = 0.5;
    w.solver.gravity = Vec2(0, 0);
    d.angular_velocity = 2;
    w.fem_bodies = {d};
    World world(w);
    const FemBodies& F = *world.femBodies();
    const Real k0 = F.kineticEnergy();
    runUntil(world, M_PI);
    return std::make_pair(F.kineticEnergy() / k0, F.strainEnergy() / k0);
  };
  const auto [kinetic, strain] = spin(FemModel::kCorotational);
  EXPECT_NEAR(kinetic, 1, 1e-3);
  EXPECT_LT(strain, 1e-3);
  // The linear element errs by more than ten times that bound (6.6% here).
  const auto [kinetic_linear, strain_linear] = spin(FemModel::kLinear);
  EXPECT_GT(std::abs(kinetic_linear - 1) + strain_linear, 0.01);
}

// Seed 002 sec. 4.1 and Table 1 in 2D: the elastic disk on an FEM plate, particle-to-surface
// contact, R = 1 and 8. Eq. 55 (cylinder): 5.549 m/s^2 sliding (mu = 0.2), 4.624 rolling
// (mu = 0.4); the seed reports under 6% at every R. Sliding must be within 2%. Rolling, the disk
// of 5 cells' radius is itself slow on a rigid incline at this cell (4.3% with this scheme; its
// own deformation and the contact's reach, test_rolling): the plate may not make that worse by
// more than half a percent, and must stay within the seed's 6% of eq. 55. Measured: 3.7% at
// R = 1 and 2.8% at R = 8 with -march=native, 4.05% and 2.76% in the portable build (the
// rigid incline 4.33% in both): the plate at R = 1 lands on either side of the rigid incline's
// figure with the build's rounding, so a bound below that figure (4%, before issue 42) tested
// the rounding, not the plate.
TEST(FemIncline, DiskSlidesAndRollsOnAnFemPlateAtEveryElementSize) {
  const Real h = 0.01;
  // The six runs at once (test/parallel_runs.hpp): the rigid incline, the plate at R = 1 and 8
  // with mu = 0.2 and 0.4, IMP's springs against the plate.
  const std::vector<Real> runs = test::runAll<Real>(6, [h](int i) {
    if (i == 0) return inclineAcceleration(0.4, h, CouplingScheme::kParticleSurface);
    if (i == 5) return femInclineAcceleration(0.2, h, h, CouplingScheme::kImp);
    return femInclineAcceleration(i % 2 ? 0.2 : 0.4, h, (i < 3 ? 1.0 : 8.0) * h);
  });
  const Real rigid = runs[0];
  std::printf("rigid incline, mu = 0.4: %.4f m/s^2\n", rigid);
  int k = 1;
  for (const Real R : {1.0, 8.0}) {
    for (const Real mu : {0.2, 0.4}) {
      const Real a = runs[k++];
      std::printf("R = %g, mu = %g: %.4f m/s^2 against %.4f\n", R, mu, a, inclineAnalytic(mu));
      if (mu < 0.3) {
        EXPECT_NEAR(a / inclineAnalytic(mu), 1, 0.02) << "R = " << R;
      } else {
        const Real a0 = inclineAnalytic(mu);
        EXPECT_LT(std::abs(a / a0 - 1), std::abs(rigid / a0 - 1) + 0.005) << "R = " << R;
        EXPECT_NEAR(a / a0, 1, 0.06) << "R = " << R;  // the seed's bound
      }
    }
  }
  // IMP's springs against the plate's segments (seed 000's scheme on an FEM body).
  const Real imp = runs[5];
  std::printf("IMP, R = 1, mu = 0.2: %.4f m/s^2\n", imp);
  EXPECT_NEAR(imp / inclineAnalytic(0.2), 1, 0.02);
}

// An FEM block dropped onto a static block and next to a wall comes to rest on them: its
// lowest node neither sinks into the block nor its side into the wall, and the time step names
// the elements.
TEST(FemSurroundings, ABlockFallsOntoAStaticBlockAndRests) {
  WorldDef w;
  w.domain.min = Vec2(0, 0);
  w.domain.max = Vec2(1, 1);
  w.cell_size = 0.05;
  w.domain.left.type = WallType::kSlip;
  FemBodyDef d = squareBody(0.2, 0.05);
  for (Vec2& v : d.mesh.nodes) v += Vec2(0.0, 0.3);  // touching the left wall, 0.1 m up
  d.youngs_modulus = 1e6;
  d.mass_damping = 20;
  w.fem_bodies = {d};
  BlockDef floor;
  floor.name = "floor";
  floor.core = {{-0.5, -0.05}, {0.5, -0.05}, {0.5, 0.05}, {-0.5, 0.05}};
  floor.rounding = 0.005;
  floor.position = Vec2(0.5, 0.145);  // top at 0.2 m
  floor.type = BodyType::kStatic;
  w.blocks = {floor};
  World world(w);
  EXPECT_EQ(world.chooseTimeStep().limit, StepLimit::kElement);
  runUntil(world, 1.0);
  const FemBodies& F = *world.femBodies();
  Real lowest = 1, leftmost = 1;
  for (int k = 0; k < F.totalNodes(); ++k) {
    lowest = std::min(lowest, F.position(k).y());
    leftmost = std::min(leftmost, F.position(k).x());
  }
  // Weight 0.2^2 * 1000 * 9.81 on E = 1 MPa: the base compresses by about 8e-5 m; rests on the
  // block's rounded top at 0.2 m within a step's travel.
  EXPECT_NEAR(lowest, 0.2, 2e-4);
  EXPECT_GE(leftmost, -1e-6);
  EXPECT_LT(F.kineticEnergy(), 1e-6);
}

namespace {

// An elastic slab of material (0.4 x 0.1 m, rho 1000, E 1 MPa, nu 0.3) on a sticky floor, and
// a 6 cm square above it falling at v0: an FEM body (E = 100 MPa, rho 2000) or a rigid block of
// the same outline and mass. Gravity is off, so that every joule is in the kinetic and elastic
// energies of the three: what the bounce loses is what the contact and the material dissipate.
WorldDef slabImpact(Real v0, CouplingScheme scheme, bool fem, MaterialModel model) {
  WorldDef w;
  const Real h = 0.01;
  w.domain.min = Vec2(0, 0);
  w.domain.max = Vec2(0.4, 0.4);
  w.domain.bottom.type = WallType::kSticky;
  w.cell_size = h;
  w.solver.gravity = Vec2(0, 0);
  // E 1 MPa, nu 0.3; granular: phi 30 deg.
  w.materials = {model == MaterialModel::kDruckerPrager ? test::druckerPrager(1000, 1e6, 0.3, 30, 0)
                                                        : test::elastic(1000, 1e6, 0.3)};
  w.bodies = {test::rectangle(Vec2(0, 0), Vec2(0.4, 0.1), 2)};
  w.coupling.scheme = scheme;
  const Real side = 0.06, y0 = 0.1 + 0.005 + side / 2;
  if (fem) {
    FemBodyDef d;
    d.name = "square";
    d.mesh = meshPolygon({{0.17, y0 - side / 2},
                          {0.23, y0 - side / 2},
                          {0.23, y0 + side / 2},
                          {0.17, y0 + side / 2}},
                         0.01);
    d.density = 2000;
    d.youngs_modulus = 1e8;
    d.friction = 0.3;
    d.restitution = 1;
    d.velocity = Vec2(0, -v0);
    w.fem_bodies = {d};
  } else {
    // The same outline, its corners rounded by 0.5 mm.
    BlockDef b = boxBlock("square", Vec2(0.2, y0), side, side, 0.0005, BodyType::kDynamic, 2000);
    b.friction = 0.3;
    b.restitution = 1;
    b.velocity = Vec2(0, -v0);
    w.blocks = {b};
  }
  return w;
}

// Whether x lies inside the FEM bodies' deformed outline (crossings of a ray along +x with the
// boundary segments: an odd count is inside).
bool insideFem(const FemBodies& F, const Vec2& x) {
  int crossings = 0;
  for (int s = 0; s < F.shapeCount(); ++s) {
    const Vec2* v = F.coreVertices(s);
    const Vec2 a = v[0], b = v[1];
    if ((a.y() > x.y()) == (b.y() > x.y())) continue;
    const Real at = a.x() + (x.y() - a.y()) / (b.y() - a.y()) * (b.x() - a.x());
    if (at > x.x()) ++crossings;
  }
  return crossings % 2 == 1;
}

}  // namespace

// Issue 18, validation 4: with e = 1 springs (IMP), an FEM square bouncing off an elastic slab
// loses no more energy than the same bounce of a rigid block of its outline and mass, which is
// the material's own dissipation (its transfers, and the waves the grid cannot carry); the FEM
// body's vibration is energy kept, not lost. The material loses energy with every transfer
// (APIC keeps affine fields only), so both run at the FEM body's element step (3.4 us; the
// rigid block alone would take 80 us and lose 35% by 0.2 s instead). Measured 0.05 s after
// release at 2 m/s, the bounce over (contact from 2.5 to 15 ms): rigid 60.31%, FEM 60.07% lost,
// nearly all of it the slab's waves; rebound 1.209 and 1.205 m/s.
TEST(FemEnergy, ABounceWithElasticContactLosesNoMoreThanTheMaterialDoes) {
  Real step = 0;
  auto loss = [&step](bool fem) {
    WorldDef def = slabImpact(2, CouplingScheme::kImp, fem, MaterialModel::kLinearElastic);
    if (!fem) def.time_step.max = step;
    World w(def);
    if (fem) step = w.chooseTimeStep().dt;
    const Real e0 = measure(w).total();
    Real vy_after = 0;
    runUntil(w, 0.05);
    if (fem) {
      const FemBodies& F = *w.femBodies();
      Real m = 0, p = 0;
      for (int k = 0; k < F.totalNodes(); ++k) {
        m += F.nodeMass(k);
        p += F.nodeMass(k) * F.velocity(k).y();
      }
      vy_after = p / m;
    } else {
      vy_after = w.blocks()->state(0).velocity.y();
    }
    const Diagnostics d = measure(w);
    std::printf(
        "%s: energy %.5f -> %.5f J/m (%.2f%% lost), rebound %.3f m/s, FEM strain %.2e J/m, "
        "dt %.3g s\n",
        fem ? "FEM" : "rigid", e0, d.total(), 100 * (1 - d.total() / e0), vy_after, d.fem_strain,
        w.chooseTimeStep().dt);
    EXPECT_GT(vy_after, 0.5) << "no rebound";
    return 1 - d.total() / e0;
  };
  const Real fem = loss(true), rigid = loss(false);
  EXPECT_GT(rigid, 0);
  EXPECT_LT(fem, rigid + 0.01);  // a percent of the energy: the outlines' corners differ
}

// Issue 18, validation 4: a 20 m/s impact of the FEM square into a granular bed. With the
// particle-to-surface contact (seed 002's scheme for FEM bodies) no material point is ever
// inside the body. IMP is a penalty scheme: its springs act once a point's disk of radius r_p
// overlaps the outline, so a point's centre may cross it by less than r_p (the rigid blocks'
// rounding takes that overlap; a segment has none); measured 1.9 mm of r_p = 7.1 mm.
TEST(FemImpact, NoMaterialPointEverEntersTheBodyAt20MetresPerSecond) {
  for (const CouplingScheme scheme : {CouplingScheme::kParticleSurface, CouplingScheme::kImp}) {
    World w(slabImpact(20, scheme, true, MaterialModel::kDruckerPrager));
    const FemBodies& F = *w.femBodies();
    const Particles& P = w.particles();
    int worst = 0;
    Real lowest = 1, deepest = 0;
    while (w.time() < 0.02) {
      stepStable(w);
      int inside = 0;
      for (std::size_t p = 0; p < P.size(); ++p) {
        const Vec2 x(P.x[p], P.y[p]);
        if (!insideFem(F, x)) continue;
        ++inside;
        Real depth = 1;
        for (int s = 0; s < F.shapeCount(); ++s) {
          const Vec2 a = F.coreVertices(s)[0], b = F.coreVertices(s)[1];
          const Real t = std::clamp((x - a).dot(b - a) / (b - a).squaredNorm(), Real(0), Real(1));
          depth = std::min(depth, (a + t * (b - a) - x).norm());
        }
        deepest = std::max(deepest, depth);
      }
      worst = std::max(worst, inside);
      for (int k = 0; k < F.totalNodes(); ++k) lowest = std::min(lowest, F.position(k).y());
    }
    const Real r_p = w.resolvedCoupling().contact_radius;
    std::printf(
        "%s: deepest node at y = %.4f m (bed top 0.1 m), most points inside at once %d, "
        "deepest %.2f mm (r_p %.2f mm)\n",
        couplingSchemeName(scheme), lowest, worst, 1e3 * deepest, 1e3 * r_p);
    EXPECT_LT(lowest, 0.09) << "the body did not enter the bed";
    if (scheme == CouplingScheme::kParticleSurface) {
      EXPECT_EQ(worst, 0);
    } else {
      EXPECT_LT(deepest, r_p);
    }
  }
}

// Seed 002 sec. 4.3 at its resolution (4 mm cells and elements, points 2 mm apart): the shipped
// water_gate scene's gate tip peaks within the range of the five published histories (41.4 to
// 48.2 mm at 0.231 to 0.255 s; cases::gateReference), and the water stays below the Mach number
// the runner warns at (kMachWarning, 0.1). Measured: 45.90 mm at 0.242 s, Mach 0.064, 17 s.
TEST(FemWater, GateTipPeaksWithinThePublishedRange) {
  const Scene scene =
      loadScene(std::string(MPM_SDEM_SOURCE_DIR) + "/config/scenes/water_gate.yaml");
  World w(scene.world);
  const GateRun g = runWaterGate(w, 0.3, 0.002);
  const GateReference ref = gateReference();
  std::printf(
      "peak %.2f mm at %.3f s (published %.1f-%.1f mm at %.3f-%.3f s), max Mach %.3f, %.1f s\n",
      1e3 * g.peak, g.peak_time, 1e3 * ref.peak_min, 1e3 * ref.peak_max, ref.time_min, ref.time_max,
      g.max_mach, g.seconds);
  EXPECT_GE(g.peak, ref.peak_min);
  EXPECT_LE(g.peak, ref.peak_max);
  EXPECT_GE(g.peak_time, ref.time_min);
  EXPECT_LE(g.peak_time, ref.time_max);
  EXPECT_LT(g.max_mach, kMachWarning);
}

namespace {

// A soft elastic layer (E = 0.1 MPa, 5 cm) resting on a clamped FEM beam (0.6 x 0.04 m,
// E = 20 MPa) over 0.6 s: the beam's mean mid-span deflection over the last 0.1 s, the steps
// taken and the largest total energy over the run's first (J/m; none may be created).
struct LayerOnBeam {
  Real deflection = 0;  // mid-span, mean over the last 0.1 s (m)
  Real period = 0;      // of the mid-span's swing about its mean, when the beam is undamped (s)
  long steps = 0;
  Real energy_gain = 0;
};
// The layer on the clamped beam below, run for `end` seconds; with swing, the beam undamped and
// the period of its mid-span's swing measured from the upward crossings of its mean after 0.05 s.
LayerOnBeam layerOnBeam(CouplingScheme scheme, Real damping, bool fem_subcycled = false,
                        Real cfl = 0.3, bool swing = false, Real end = 0.6) {
  const Real h = 0.01, E = 20e6, nu = 0.3, rho = 1000, L = 0.6, H = 0.04;
  WorldDef def;
  def.domain.min = Vec2(-0.1, -0.1);
  def.domain.max = Vec2(0.7, 0.2);
  def.cell_size = h;
  def.solver.gravity = Vec2(0, -9.81);
  def.solver.damping = damping;
  def.time_step.cfl = cfl;
  def.time_step.fem_subcycled = fem_subcycled;
  MaterialDef m;
  m.name = "layer";
  m.density = 1000;
  m.bulk_modulus = 0.1e6 / (3 * (1 - 2 * nu));
  m.shear_modulus = 0.1e6 / (2 * (1 + nu));
  def.materials.push_back(m);
  BodyDef layer;
  layer.name = "layer";
  layer.shape.type = ShapeType::kRectangle;
  // The lowest points' contact disks reach the beam's top face (contact_radius capped at
  // their depth).
  layer.shape.min = Vec2(0.05, H / 2);
  layer.shape.max = Vec2(L - 0.05, H / 2 + 0.05);
  layer.points_per_cell = 2;
  def.bodies.push_back(layer);
  FemBodyDef beam;
  beam.name = "beam";
  beam.mesh = meshPolygon({{0, -H / 2}, {L, -H / 2}, {L, H / 2}, {0, H / 2}}, H / 2);
  beam.youngs_modulus = E;
  beam.poisson_ratio = nu;
  beam.density = rho;
  beam.friction = 0.5;
  // Clamped: both ends' nodes held.
  beam.held = {Box{Vec2(-1, -1), Vec2(1e-9, 1)}, Box{Vec2(L - 1e-9, -1), Vec2(1, 1)}};
  const Real Ep = E / (1 - nu * nu), I = H * H * H / 12;
  beam.mass_damping = swing ? 0 : 2 * 22.37 / (L * L) * std::sqrt(Ep * I / (rho * H));
  def.fem_bodies.push_back(beam);
  def.coupling.scheme = scheme;
  def.coupling.normal_stiffness = 1e6;
  def.coupling.tangential_stiffness = 5e5;
  World w(def);
  const FemBodies& F = *w.femBodies();
  int mid = 0;  // the bottom node nearest mid-span
  for (int k = 0; k < F.totalNodes(); ++k)
    if ((F.reference(k) - Vec2(L / 2, -H / 2)).norm() <
        (F.reference(mid) - Vec2(L / 2, -H / 2)).norm())
      mid = k;
  Real sum = 0;
  long samples = 0;
  LayerOnBeam r;
  const Real start = measure(w).total();
  std::vector<std::pair<Real, Real>> history;  // (t, deflection) after 0.05 s
  while (w.time() < end) {
    stepStable(w);
    r.energy_gain = std::max(r.energy_gain, measure(w).total() - start);
    const Real d = F.reference(mid).y() - F.position(mid).y();
    if (w.time() >= 0.05) history.emplace_back(w.time(), d);
    if (w.time() < end - 0.1) continue;
    sum += d;
    ++samples;
  }
  r.deflection = sum / samples;
  r.steps = w.stepCount();
  Real mean = 0;
  for (const auto& [t, d] : history) mean += d / history.size();
  std::vector<Real> up;  // upward crossings of the mean, linearly interpolated
  for (std::size_t i = 1; i < history.size(); ++i) {
    const Real a = history[i - 1].second - mean, b = history[i].second - mean;
    if (a < 0 && b >= 0)
      up.push_back(history[i - 1].first +
                   (history[i].first - history[i - 1].first) * (-a) / (b - a));
  }
  if (up.size() > 1) r.period = (up.back() - up.front()) / (up.size() - 1);
  return r;
}

}  // namespace

// Issue 40: local damping is a numerical knob, so it may not move a static equilibrium. A soft
// elastic layer (E = 0.1 MPa, 5 cm) rests on a clamped FEM beam (0.6 x 0.04 m, E = 20 MPa); the
// beam's mid-span deflection with solver.damping 0.3 and without must agree within 1% for the
// penalty-free scheme (its impulses come after the velocity update: damping that saw only the
// internal force and gravity, which the contact balances, held the layer 16% heavier on the
// beam) and for IMP's springs. The beam settles under critical mass damping of its first mode
// (zero force at rest); the undamped layer keeps ringing, so both runs average the last 0.1 s
// of 0.6 s (the layer's vertical period is about 0.02 s). Measured: particle_surface 2.1724 /
// 2.1689 mm damped / undamped, imp 2.1852 / 2.1797 mm.
TEST(FemLayer, LocalDampingLeavesARestingLayersLoadWhereItIs) {
  const CouplingScheme schemes[] = {CouplingScheme::kParticleSurface, CouplingScheme::kImp};
  // The four runs at once (test/parallel_runs.hpp): each scheme damped and undamped.
  const std::vector<Real> runs = test::runAll<Real>(
      4, [&](int i) { return layerOnBeam(schemes[i / 2], i % 2 ? 0 : 0.3).deflection; });
  for (int k = 0; k < 2; ++k) {
    const CouplingScheme scheme = schemes[k];
    const Real damped = runs[2 * k], free = runs[2 * k + 1];
    std::printf("%s: mid-span deflection %.4f mm damped, %.4f mm undamped\n",
                couplingSchemeName(scheme), 1e3 * damped, 1e3 * free);
    EXPECT_NEAR(damped / free, 1, 0.01) << couplingSchemeName(scheme);
  }
}

// Issue 77, multi-rate FEM (time.fem_integration: subcycled): the elements take substeps of
// kappa_1 times their element step inside the material's step, free of the material, and the
// material's impulse on them comes as a kick at the step's end. The exchange's momentum is
// exact: a free body's momentum changes by the step times the contact force, to round-off, in
// 1 and in 25 substeps (the kick carries the whole impulse; the substeps carry none of it).
TEST(FemMultiRate, TheContactImpulseReachesTheBodyWhole) {
  for (const int substeps : {1, 25}) {
    FemBodyDef d = squareBody(0.2, 0.05);
    d.youngs_modulus = 1e6;
    d.poisson_ratio = 0.3;
    d.density = 1000;
    FemBodies B({d}, Vec2(0, 0));
    const Real dt = 1e-3;
    B.setMaxSubstep(dt / substeps);
    ASSERT_EQ(B.substepsFor(dt), substeps);
    B.beginCoupling(dt);
    const Vec2 force(3.0, -7.0);  // N/m, on a segment's middle
    const Vec2 at = 0.5 * (B.coreVertices(0)[0] + B.coreVertices(0)[1]);
    B.applyForce(0, force, at);
    B.step(dt, std::numeric_limits<Real>::infinity());
    Vec2 momentum(0, 0);
    for (int k = 0; k < B.totalNodes(); ++k) momentum += B.nodeMass(k) * B.velocity(k);
    EXPECT_NEAR(momentum.x(), dt * force.x(), 1e-15) << substeps << " substeps";
    EXPECT_NEAR(momentum.y(), dt * force.y(), 1e-15) << substeps << " substeps";
  }
}

// The layer on the clamped beam above, its beam (element step about 26 us at kappa_1 = 0.3)
// ten times stiffer than its layer's step (about 260 us): multi-rate, the world takes the
// layer's step and the beam about ten substeps in each. The split's error is first order in
// the step (the material's load reaches the beam as a kick at each step's end): at kappa_1 =
// 0.3 the mid-span deflection is 5.0% above the single-rate run's, at 0.15 it must agree
// within 1% (the step-halving bound), and again within 1% when the step halves to
// 0.075. No run may gain energy (kinetic, elastic, gravitational, both bodies) beyond 1e-4 of
// the layer's weight times a cell (round-off: the runs lose energy to the beam's damping).
// 1e-4 of the layer's weight times a cell (J/m): what a multi-rate run may gain, round-off.
constexpr Real kRoundOffEnergy = 1e-4 * 1000 * 0.5 * 0.05 * 9.81 * 0.01;
TEST(FemMultiRate, ALayerOnABeamDeflectsAsInOneRate) {
  const Real cfl[] = {0.3, 0.3, 0.15, 0.075};
  const std::vector<LayerOnBeam> runs = test::runAll<LayerOnBeam>(
      4, [&](int i) { return layerOnBeam(CouplingScheme::kParticleSurface, 0, i > 0, cfl[i]); });
  const Real single = runs[0].deflection;
  std::printf("mid-span deflection: single-rate %.4f mm (%ld steps)\n", 1e3 * single,
              runs[0].steps);
  for (int i = 1; i < 4; ++i)
    std::printf("multi-rate at kappa_1 %.3f: %.4f mm (%+.2f%%, %ld steps)\n", cfl[i],
                1e3 * runs[i].deflection, 100 * (runs[i].deflection / single - 1), runs[i].steps);
  EXPECT_NEAR(runs[2].deflection / single, 1, 0.01);
  EXPECT_NEAR(runs[3].deflection / runs[2].deflection, 1, 0.01);
  EXPECT_LT(runs[2].steps * 5, runs[0].steps);  // the material's step, not the elements'
  for (const LayerOnBeam& r : runs) EXPECT_LT(r.energy_gain, kRoundOffEnergy);
}

// The same beam undamped, swinging under the layer it carries: its period multi-rate must
// converge to the single-rate one as the step shrinks (within 1% at kappa_1 0.15 and 0.075).
// Analytic reference: the clamped beam's first mode, 2 pi / (22.37 / L^2 sqrt(E' I / m)),
// 59.07 ms alone (m = rho H = 40 kg/m) and 88.59 ms carrying the layer as mass (50 kg/m over
// 0.05-0.55 m, which holds 99.94% of the mode's phi^2). The single-rate period must lie in
// [0.91, 1] of the loaded value: the mesh's two triangles through the depth are stiff
// (FemCantilever: 0.829 of Euler-Bernoulli's deflection, a period sqrt(0.829) = 0.91 of its),
// and a layer that rides on the beam only in part lengthens it less. Measured: single-rate
// 84.73 ms (27,990 steps), multi-rate 84.58 ms (-0.18%) at 0.15 and 84.70 ms (-0.04%) at 0.075
// (2,732 and 5,464 steps).
TEST(FemMultiRate, ALoadedBeamSwingsAsInOneRate) {
  const Real cfl[] = {0.3, 0.15, 0.075};
  const std::vector<LayerOnBeam> runs = test::runAll<LayerOnBeam>(3, [&](int i) {
    return layerOnBeam(CouplingScheme::kParticleSurface, 0, i > 0, cfl[i], true, 0.35);
  });
  const Real single = runs[0].period;
  std::printf("period of the loaded beam: single-rate %.3f ms (%ld steps)\n", 1e3 * single,
              runs[0].steps);
  for (int i = 1; i < 3; ++i)
    std::printf("multi-rate at kappa_1 %.3f: %.3f ms (%+.2f%%, %ld steps)\n", cfl[i],
                1e3 * runs[i].period, 100 * (runs[i].period / single - 1), runs[i].steps);
  const Real loaded = 0.08859;  // s
  EXPECT_GT(single, 0.91 * loaded);
  EXPECT_LT(single, loaded);
  EXPECT_NEAR(runs[1].period / single, 1, 0.01);
  EXPECT_NEAR(runs[2].period / single, 1, 0.01);
  for (const LayerOnBeam& r : runs) EXPECT_LT(r.energy_gain, kRoundOffEnergy);  // as above
}
