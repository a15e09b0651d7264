// Issue 20's robot scenes.
//  - The validation's blade and rock cases start from the shipped scenes (cases::excavatorBlade,
//    rockIntoBed): the blade case's defaults are the scene's values (the same domain, grid,
//    materials, material points, blocks), but for sleep. The silo cases are the silo scene with
//    their neck, cell and sand (cases::silo).
//  - The excavator blade against Reece's fundamental earth-moving equation with McKyes' N_gamma,
//    at the CI resolution (5 mm cells: the edge 8, 12 and 16 cells deep), for a smooth vertical
//    blade, where the planar wedge is Rankine's passive state and exact. The bands come from the
//    validation report's study at 10, 5 and 2.5 mm (docs/validation/REPORT.md, case blade).
//  - The blade in real time (launch/excavator_blade_fast.launch: the blade scene with the launch
//    file's overrides): its force does not move when the step halves and quarters.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cases.hpp"
#include "helpers.hpp"
#include "mpm_sdem/core/rigid/blocks.hpp"
#include "mpm_sdem/core/rigid/spheropolygon.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "parallel_runs.hpp"

using namespace mpm_sdem;

namespace {

// The material points of a world, sorted by position, as (x, y, mass, volume).
std::vector<std::array<Real, 4>> points(const WorldDef& def) {
  World w(def);
  const Particles& P = w.particles();
  std::vector<std::array<Real, 4>> out;
  for (std::size_t p = 0; p < P.size(); ++p)
    out.push_back({P.x[p], P.y[p], P.mass[p], P.volume0[p]});
  std::sort(out.begin(), out.end());
  return out;
}

// A block's outline in the world: its core's vertices, sorted, and its rounding.
std::vector<Vec2> worldCore(const BlockDef& b) {
  std::vector<Vec2> core = placedParts(b)[0].core;
  // By x, then y, with x rounded to a nanometre (the case's vertical edges carry cot(90 deg),
  // 6e-17, in their x).
  auto key = [](const Vec2& v) { return std::pair{std::llround(v.x() * 1e9), v.y()}; };
  std::sort(core.begin(), core.end(),
            [&](const Vec2& a, const Vec2& c) { return key(a) < key(c); });
  return core;
}

void expectSameMaterial(const MaterialDef& a, const MaterialDef& b) {
  EXPECT_EQ(a.model, b.model);
  EXPECT_DOUBLE_EQ(a.density, b.density);
  EXPECT_NEAR(a.bulk_modulus, b.bulk_modulus, 1e-9 * b.bulk_modulus);
  EXPECT_NEAR(a.shear_modulus, b.shear_modulus, 1e-9 * b.shear_modulus);
  EXPECT_NEAR(a.friction_angle, b.friction_angle, 1e-12);
  EXPECT_NEAR(a.dilation_angle, b.dilation_angle, 1e-12);
  EXPECT_DOUBLE_EQ(a.cohesion, b.cohesion);
  EXPECT_DOUBLE_EQ(a.tensile_strength, b.tensile_strength);
  EXPECT_DOUBLE_EQ(a.separation_volume_ratio, b.separation_volume_ratio);
}

// Everything but the blocks' outlines, which the callers compare.
void expectSameWorld(const WorldDef& scene, const WorldDef& c) {
  EXPECT_NEAR((scene.domain.min - c.domain.min).norm(), 0, 1e-12);
  EXPECT_NEAR((scene.domain.max - c.domain.max).norm(), 0, 1e-12);
  for (const auto& [a, b] : {std::pair{scene.domain.left, c.domain.left},
                             {scene.domain.right, c.domain.right},
                             {scene.domain.bottom, c.domain.bottom},
                             {scene.domain.top, c.domain.top}})
    EXPECT_EQ(a.type, b.type);
  EXPECT_DOUBLE_EQ(scene.cell_size, c.cell_size);
  EXPECT_EQ(scene.solver.kernel, c.solver.kernel);
  EXPECT_EQ(scene.solver.transfer, c.solver.transfer);
  EXPECT_EQ(scene.solver.stress_update, c.solver.stress_update);
  EXPECT_NEAR((scene.solver.gravity - c.solver.gravity).norm(), 0, 1e-12);
  EXPECT_DOUBLE_EQ(scene.solver.damping, c.solver.damping);
  EXPECT_DOUBLE_EQ(scene.time_step.cfl, c.time_step.cfl);
  EXPECT_DOUBLE_EQ(scene.time_step.contact_factor, c.time_step.contact_factor);
  ASSERT_EQ(scene.materials.size(), c.materials.size());
  for (std::size_t i = 0; i < c.materials.size(); ++i)
    expectSameMaterial(scene.materials[i], c.materials[i]);
  EXPECT_EQ(scene.coupling.scheme, c.coupling.scheme);
  EXPECT_EQ(scene.coupling.stiffness_per, c.coupling.stiffness_per);
  EXPECT_DOUBLE_EQ(scene.coupling.normal_stiffness, c.coupling.normal_stiffness);
  EXPECT_DOUBLE_EQ(scene.coupling.tangential_stiffness, c.coupling.tangential_stiffness);
  EXPECT_NEAR(scene.coupling.contact_radius, c.coupling.contact_radius, 1e-12);
  EXPECT_NEAR(scene.coupling.verlet_distance, c.coupling.verlet_distance, 1e-12);
  // The same points: positions to round-off, masses and volumes.
  const auto a = points(scene), b = points(c);
  ASSERT_EQ(a.size(), b.size());
  Real mass_a = 0, mass_b = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_NEAR(a[i][0], b[i][0], 1e-9);
    EXPECT_NEAR(a[i][1], b[i][1], 1e-9);
    EXPECT_NEAR(a[i][2], b[i][2], 1e-9 * b[i][2]);
    EXPECT_NEAR(a[i][3], b[i][3], 1e-9 * b[i][3]);
    mass_a += a[i][2];
    mass_b += b[i][2];
  }
  EXPECT_NEAR(mass_a, mass_b, 1e-9 * mass_b);
  ASSERT_EQ(scene.blocks.size(), c.blocks.size());
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    const BlockDef &s = scene.blocks[i], &k = c.blocks[i];
    EXPECT_EQ(s.name, k.name);
    EXPECT_EQ(s.type, k.type);
    EXPECT_DOUBLE_EQ(s.friction, k.friction);
    EXPECT_DOUBLE_EQ(s.restitution, k.restitution);
    EXPECT_NEAR((s.velocity - k.velocity).norm(), 0, 1e-12) << s.name;
    EXPECT_DOUBLE_EQ(s.angular_velocity, k.angular_velocity);
    if (k.type == BodyType::kDynamic) {
      EXPECT_NEAR(spheropolygonMass(s.core, s.rounding, s.density).mass,
                  spheropolygonMass(k.core, k.rounding, k.density).mass, 1e-12)
          << s.name;
    }
  }
}

void expectSameOutline(const BlockDef& s, const BlockDef& k) {
  EXPECT_DOUBLE_EQ(s.rounding, k.rounding) << s.name;
  const std::vector<Vec2> a = worldCore(s), b = worldCore(k);
  ASSERT_EQ(a.size(), b.size()) << s.name;
  for (std::size_t j = 0; j < a.size(); ++j) EXPECT_NEAR((a[j] - b[j]).norm(), 0, 1e-9) << s.name;
}

// The bounding box of a block's rounded outline.
std::pair<Vec2, Vec2> outlineBox(const BlockDef& b) {
  Vec2 lo(1e9, 1e9), hi(-1e9, -1e9);
  for (const Vec2& v : worldCore(b)) {
    lo = lo.cwiseMin(v - Vec2::Constant(b.rounding));
    hi = hi.cwiseMax(v + Vec2::Constant(b.rounding));
  }
  return {lo, hi};
}

// The overrides of a launch file's `set` argument (its default, "['key=value', ...]"), as the
// node gets them: the launch file is their one source.
std::vector<std::string> launchSet(const std::string& launch_file) {
  std::ifstream in(launch_file);
  std::stringstream text;
  text << in.rdbuf();
  std::smatch arg;
  const std::string xml = text.str();
  if (!std::regex_search(xml, arg, std::regex(R"(<arg name="set" default="\[([^\]]*)\]")")))
    return {};
  std::vector<std::string> set;
  const std::string list = arg[1];
  const std::regex item("'([^']*)'");
  for (auto i = std::sregex_iterator(list.begin(), list.end(), item); i != std::sregex_iterator();
       ++i)
    set.push_back((*i)[1]);
  return set;
}

}  // namespace

// The blade case starts from the scene and overrides what it sweeps: at its defaults it is the
// scene, so that the report's blade at d 6 cm, 5 mm cells and friction 0.3 is the shipped one.
TEST(RobotScenes, ExcavatorBladeCaseAtItsDefaultsIsTheScene) {
  const WorldDef scene = loadScene(test::sourcePath("config/scenes/excavator_blade.yaml")).world;
  const WorldDef c = cases::excavatorBlade(cases::Blade{});  // d 6 cm, 5 mm cells, friction 0.3
  expectSameWorld(scene, c);
  // The validation starts from the layer's weight too (cases::layerWeightAsStress, the same
  // rule), set by pushBlade after building its world; it runs every point awake, the reference
  // for the scene's sleeping material.
  ASSERT_EQ(scene.bodies.size(), 1u);
  EXPECT_TRUE(scene.bodies[0].geostatic);
  EXPECT_TRUE(cases::Blade{}.geostatic);
  ASSERT_EQ(c.blocks.size(), 1u);
  expectSameOutline(scene.blocks[0], c.blocks[0]);
}

// The silo cases load the silo scene and set its neck: at the scene's own neck, cell and points
// per cell they give its world (to the last bits of the plates' arithmetic), and another neck
// moves the plates' inner ends and nothing else.
TEST(RobotScenes, SiloCasesAreTheSiloSceneWithTheirNeck) {
  const WorldDef scene = loadScene(test::sourcePath("config/scenes/silo.yaml")).world;
  const WorldDef c = cases::silo(0.04, 0.007, 2);
  expectSameWorld(scene, c);
  ASSERT_EQ(c.blocks.size(), 4u);
  for (int i = 0; i < 4; ++i) expectSameOutline(scene.blocks[i], c.blocks[i]);
  auto neck = [](const WorldDef& w) {
    return outlineBox(w.blocks[3]).first.x() - outlineBox(w.blocks[2]).second.x();
  };
  EXPECT_NEAR(neck(scene), 0.04, 1e-12);
  const WorldDef narrow = cases::silo(0.03, 0.007, 2);
  EXPECT_NEAR(neck(narrow), 0.03, 1e-12);
  for (int i = 0; i < 2; ++i) expectSameOutline(scene.blocks[i], narrow.blocks[i]);  // the walls
  // The plates' outer ends stay inside the walls.
  EXPECT_LT(outlineBox(narrow.blocks[2]).first.x(), outlineBox(narrow.blocks[0]).second.x());
  EXPECT_GT(outlineBox(narrow.blocks[3]).second.x(), outlineBox(narrow.blocks[1]).first.x());
}

// The smooth vertical blade at the CI resolution (5 mm cells), at d = 4, 6 and 8 cm, against
// Reece's force gamma d^2 N_gamma with McKyes' N_gamma at delta = 0, where the planar wedge is
// Rankine's passive state, an exact solution (N_gamma = K_p / 2, K_p = 3.39 for the material's
// flowing in-plane angle of 33.0 deg): the force at the onset of the cut (cases::bladeForce).
// The validation report's study (docs/validation/REPORT.md, case blade: 10, 5 and 2.5 mm, nine
// runs) finds the onset force over Reece's falling with h / d as R0 + A h / d, R0 = 1.034 +-
// 0.032 (the converged ratio, Reece's within its error), A = 2.86, residuals 0.045 rms: the
// blade's edge is smeared over a cell or two, so the failing wedge is deeper by a length
// proportional to h (about 1.4 h). The band: that line at 5 mm (1.39, 1.27, 1.21 at d = 4, 6,
// 8 cm), +- three times the residuals' rms; and above Reece's value (the force converges from
// above: below it the error would have changed sign, which refinement does not do). Measured in
// the study at 5 mm: 1.442, 1.243, 1.181.
// The exponent of the onset force in d: the study's 5 mm value, 1.740 +- 0.095 (standard error
// of the fit through the three depths' noisy onsets), within three standard errors; below 2
// at a fixed cell because the shallowest cut has the fewest cells (R0 + A h / d is largest).
constexpr Real kR0 = 1.034, kA = 2.86, kResidual = 0.045;
constexpr Real kExponent = 1.740, kExponentError = 0.095;
TEST(RobotScenes, BladeForceAgainstReeceAtCiResolution) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::vector<Real> depths = {0.04, 0.06, 0.08};
  std::vector<Real> onset, error;
  auto blade = [&](std::size_t i) {
    cases::Blade c;
    c.depth = depths[i];
    c.cell_size = 0.005;
    c.friction = 0;
    return c;
  };
  // The three depths at once (test/parallel_runs.hpp).
  const std::vector<cases::BladeForce> forces =
      test::runAll<cases::BladeForce>(static_cast<int>(depths.size()), [&](int i) {
        const cases::Blade c = blade(i);
        World w(cases::excavatorBlade(c));
        return cases::bladeForce(cases::pushBlade(w, c, 0.3 * c.depth), c.depth);
      });
  for (std::size_t i = 0; i < depths.size(); ++i) {
    const cases::Blade c = blade(i);
    const cases::BladeForce& f = forces[i];
    const Real reece = cases::reeceHorizontal(c);
    std::printf("d %.2f m: onset %.1f +- %.1f N/m, Reece %.1f N/m, ratio %.3f; mean %.1f N/m\n",
                c.depth, f.onset, f.onset_error, reece, f.onset / reece, f.mean);
    onset.push_back(f.onset);
    error.push_back(f.onset_error);
    EXPECT_GT(f.onset, reece) << "d " << c.depth;
    EXPECT_NEAR(f.onset / reece, kR0 + kA * c.cell_size / c.depth, 3 * kResidual)
        << "d " << c.depth;
  }
  const cases::PowerLaw k = cases::powerLaw(depths, onset, error);
  std::printf("exponent %.3f +- %.3f, %.1f s\n", k.exponent, k.error,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  EXPECT_NEAR(k.exponent, kExponent, 3 * kExponentError);
}

// The blade in real time (docs/robots.md): the blade scene at 1 cm with ASFLIP relaxed over
// 0.03 s, the blade's springs subcycled and kappa_1 = 0.8. Its horizontal force, averaged over
// the steps from 0.12 s (after the unstressed layer's first ringing) to 1 s, at the launch
// file's cfl, its half and its quarter. Measured (blocks.csv's samples, three perturbed members
// each): 219.20, 219.14, 218.89 N/m, members within 0.08; with APIC instead the same halvings
// move it by 3.5% and 8.1% (226.0, 233.8, 244.2 N/m). The bound, 0.5% of the force, lies
// between the two: it fails if the transfer's loss per step comes back. This test's own run
// measured 219.15, 219.10, 218.87 N/m.
TEST(RobotScenes, FastBladeForceDoesNotDependOnTheStep) {
  const std::vector<std::string> set =
      launchSet(test::sourcePath("launch/excavator_blade_fast.launch"));
  ASSERT_EQ(set.size(), 6u) << "launch/excavator_blade_fast.launch's set argument";
  const auto cfl_item = std::find_if(
      set.begin(), set.end(), [](const std::string& kv) { return kv.rfind("time.cfl=", 0) == 0; });
  ASSERT_NE(cfl_item, set.end()) << "the launch file sets no time.cfl";
  const Real cfl0 = std::stod(cfl_item->substr(9));
  std::vector<Real> force;
  for (const Real cfl : {cfl0, cfl0 / 2, cfl0 / 4}) {
    std::vector<std::string> o = set;
    o.push_back("time.cfl=" + std::to_string(cfl));  // the last override of a key wins
    World w(loadScene(test::sourcePath("config/scenes/excavator_blade.yaml"), o).world);
    const Blocks& B = *w.blocks();
    Real impulse = 0, span = 0;
    long steps = 0;
    while (w.time() < 1.0 - 1e-12) {
      const StepInfo s = stepStable(w, 1.0);
      ASSERT_TRUE(s.finite);
      ++steps;
      if (w.time() <= 0.12) continue;
      impulse += -B.coupling()[0].force.x() * s.dt;
      span += s.dt;
    }
    force.push_back(impulse / span);
    std::printf("cfl %g: %ld steps, the blade's force %.2f N/m\n", cfl, steps, force.back());
  }
  EXPECT_GT(force[0], 150);  // a cut, not an empty push (McKyes' level-surface 160 N/m)
  EXPECT_NEAR(force[1] / force[0], 1, 0.005);
  EXPECT_NEAR(force[2] / force[0], 1, 0.005);
}
