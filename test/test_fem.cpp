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
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "cases.hpp"
#include "mpm_sdem/core/fem/fem_bodies.hpp"
#include "mpm_sdem/mesh/mesher.hpp"

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
  EXPECT_EQ(meshProblem(m), "");
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
  EXPECT_NE(meshProblem(m).find("node 3 belongs to no triangle"), std::string::npos);
  m.nodes.pop_back();
  EXPECT_EQ(meshProblem(m), "");
  m.triangles = {{0, 2, 1}};
  EXPECT_NE(meshProblem(m).find("clockwise"), std::string::npos);
  m.triangles = {{0, 1, 7}};
  EXPECT_NE(meshProblem(m).find("names node 7"), std::string::npos);
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
// Timoshenko's shear adds 0.26% to the deflection). At h = H/8 the deflection alone is 0.987 of
// Euler-Bernoulli (6,542 elements, 150 s: too long for CI).
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
    while (world.time() < M_PI) world.step(world.chooseTimeStep().dt);
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
// more than half a percent, and within 4% of eq. 55. Measured: 3.7% at R = 1, 2.8% at R = 8.
TEST(FemIncline, DiskSlidesAndRollsOnAnFemPlateAtEveryElementSize) {
  const Real h = 0.01;
  const Real rigid = inclineAcceleration(0.4, h, CouplingScheme::kParticleSurface);
  std::printf("rigid incline, mu = 0.4: %.4f m/s^2\n", rigid);
  for (const Real R : {1.0, 8.0}) {
    for (const Real mu : {0.2, 0.4}) {
      const Real a = femInclineAcceleration(mu, h, R * h);
      std::printf("R = %g, mu = %g: %.4f m/s^2 against %.4f\n", R, mu, a, inclineAnalytic(mu));
      if (mu < 0.3) {
        EXPECT_NEAR(a / inclineAnalytic(mu), 1, 0.02) << "R = " << R;
      } else {
        const Real a0 = inclineAnalytic(mu);
        EXPECT_LT(std::abs(a / a0 - 1), std::abs(rigid / a0 - 1) + 0.005) << "R = " << R;
        EXPECT_NEAR(a / a0, 1, 0.04) << "R = " << R;
      }
    }
  }
  // IMP's springs against the plate's segments (seed 000's scheme on an FEM body).
  const Real imp = femInclineAcceleration(0.2, h, h, CouplingScheme::kImp);
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
  while (world.time() < 1.0) world.step(world.chooseTimeStep().dt);
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
