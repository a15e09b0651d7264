// Test 8: bad scene input is refused with one message naming the file, line, key and a valid
// value, and the runner exits non-zero before simulating (no output written). The shipped scenes
// parse and take steps.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <cstdlib>

#include <algorithm>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "helpers.hpp"
#include "mpm_sdem/scene/scene.hpp"

using namespace mpm_sdem;

namespace {

std::string errorOf(const std::string& file, const std::vector<std::string>& overrides = {}) {
  try {
    loadScene(test::sourcePath("test/data/" + file), overrides);
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

void expectError(const std::string& msg, const std::string& where, const std::string& key,
                 const std::string& hint) {
  ASSERT_FALSE(msg.empty()) << "the scene was accepted";
  EXPECT_NE(msg.find(where), std::string::npos) << msg;
  EXPECT_NE(msg.find(key), std::string::npos) << msg;
  EXPECT_NE(msg.find(hint), std::string::npos) << msg;
}

}  // namespace

TEST(SceneErrors, ValidBaseSceneParses) {
  EXPECT_EQ(errorOf("valid.yaml"), "");
  EXPECT_EQ(errorOf("valid_blocks.yaml"), "");
  EXPECT_EQ(errorOf("valid_fem.yaml"), "");
  EXPECT_EQ(errorOf("valid_cluster.yaml"), "");
  EXPECT_EQ(errorOf("valid_fluid.yaml"), "");
}

// Multi-rate FEM and subcycled IMP springs do not nest (the contact substeps step the FEM
// bodies): asked together, the coupling's key is refused, naming the other (the exclusions'
// table, test_exclusions).
TEST(SceneErrors, TwoMultiRateSplitsAreRefused) {
  const std::vector<std::string> both = {"time.fem_integration=subcycled",
                                         "coupling.normal_integration=subcycled"};
  expectError(errorOf("valid.yaml", both), "--set coupling.normal_integration=subcycled",
              "coupling.normal_integration",
              "does not combine with subcycled FEM bodies (time.fem_integration: subcycled)");
}

// The table of models (material.hpp) lists each row at its enum's place, and the scene refuses
// every model's key on a material of another model, naming the models that have it: the sand of
// valid.yaml (Drucker-Prager) and the water of valid_fluid.yaml (fluid) take each foreign key.
TEST(SceneErrors, EachModelsKeysAreItsOwn) {
  const std::vector<MaterialTraits>& models = materialModels();
  for (std::size_t i = 0; i < models.size(); ++i)
    EXPECT_EQ(static_cast<std::size_t>(models[i].model), i) << models[i].name;
  const std::pair<const char*, MaterialModel> scenes[] = {
      {"valid.yaml", MaterialModel::kDruckerPrager}, {"valid_fluid.yaml", MaterialModel::kFluid}};
  int refused = 0;
  for (const auto& [file, model] : scenes) {
    const std::string material = model == MaterialModel::kFluid ? "water" : "sand";
    for (const MaterialTraits& t : models) {
      for (const MaterialKey& k : t.keys) {
        const std::vector<MaterialKey>& own = materialTraits(model).keys;
        if (std::any_of(own.begin(), own.end(),
                        [&](const MaterialKey& o) { return std::string(o.key) == k.key; }))
          continue;
        const std::string set = "materials." + material + "." + k.key + "=0.5";
        expectError(errorOf(file, {set}), "--set " + set, std::string("materials[0].") + k.key,
                    "applies only to model: ");
        EXPECT_NE(errorOf(file, {set}).find(t.name), std::string::npos) << set;
        ++refused;
      }
    }
  }
  EXPECT_GE(refused, 12);  // every key of the four models, from one scene or the other
}

// Scaled inertia scales the material points' only: FEM bodies and SPH particles, which would keep
// theirs, are refused with it at its key; out of range at its own.
TEST(SceneErrors, InertiaScaleOnlyForMaterialPoints) {
  expectError(errorOf("valid_fem.yaml", {"solver.inertia_scale=4"}), "--set solver.inertia_scale=4",
              "solver.inertia_scale", "does not combine with FEM bodies (fem_bodies: a body)");
  expectError(errorOf("valid_sph.yaml", {"solver.inertia_scale=4"}), "--set solver.inertia_scale=4",
              "solver.inertia_scale", "does not combine with SPH particles");
  expectError(errorOf("valid.yaml", {"solver.inertia_scale=0.5"}), "--set solver.inertia_scale=0.5",
              "solver.inertia_scale", "must be in [1, 10000]");
  EXPECT_EQ(errorOf("valid.yaml", {"solver.inertia_scale=4"}), "");
}

// Sleeping material: USF and material points only (refused at solver.sleep_speed with the
// reason), its other keys only with a sleep speed, each in its range.
TEST(SceneErrors, SleepingMaterialWhereItIsWellPosed) {
  expectError(errorOf("valid.yaml", {"solver.sleep_speed=0.01", "solver.stress_update=usl"}),
              "--set solver.sleep_speed=0.01", "solver.sleep_speed",
              "does not combine with USL (solver.stress_update: usl): in USL, awake material");
  expectError(errorOf("valid_sph.yaml", {"solver.sleep_speed=0.01"}), "--set solver.sleep_speed",
              "solver.sleep_speed", "does not combine with SPH particles");
  expectError(errorOf("valid_fem.yaml", {"solver.sleep_speed=0.01"}), "--set solver.sleep_speed",
              "solver.sleep_speed", "does not combine with FEM bodies");
  expectError(errorOf("valid.yaml", {"solver.sleep_time=0.1"}), "--set solver.sleep_time=0.1",
              "solver.sleep_time", "applies only with sleep_speed > 0");
  expectError(errorOf("valid.yaml", {"solver.sleep_speed=2"}), "--set solver.sleep_speed=2",
              "solver.sleep_speed", "must be in [0, 1]");
  EXPECT_EQ(errorOf("valid.yaml", {"solver.sleep_speed=0.01", "solver.sleep_time=0.1",
                                   "solver.sleep_margin=0.02"}),
            "");
  // A bed at rest from the start: not a fluid, whose pressure follows from its density.
  expectError(errorOf("valid_fluid.yaml", {"bodies.column.initial_stress=geostatic"}),
              "valid_fluid.yaml", "initial_stress", "a fluid's pressure follows from its density");
  expectError(errorOf("valid.yaml", {"bodies.column.initial_stress=weight"}), "valid.yaml",
              "initial_stress", "geostatic");
  EXPECT_EQ(errorOf("valid.yaml", {"bodies.column.initial_stress=geostatic"}), "");
}

// A cluster of discs listed, or a shape filled with discs (the wedge's 2.2 cm outline takes
// 2 x 2 discs of 4 mm at the default pitch of 8 mm).
TEST(SceneErrors, ClustersParse) {
  const Scene listed = loadScene(test::sourcePath("test/data/valid_cluster.yaml"));
  ASSERT_EQ(listed.world.blocks[1].discs.size(), 3u);
  EXPECT_DOUBLE_EQ(listed.world.blocks[1].discs[2].centre.y(), 0.007);
  const Scene filled = loadScene(test::sourcePath("test/data/valid_blocks.yaml"),
                                 {"blocks.wedge.disc_radius=0.004"});
  EXPECT_EQ(filled.world.blocks[1].discs.size(), 4u);
  EXPECT_TRUE(filled.world.blocks[1].core.empty());
}

struct BadScene {
  const char* test;  // test name
  const char* file;  // under test/data/
  std::vector<std::string> overrides;
  const char *where, *key, *hint;  // expected in the message
};

class BadSceneInput : public ::testing::TestWithParam<BadScene> {};

TEST_P(BadSceneInput, IsRefusedWithItsMessage) {
  const BadScene& c = GetParam();
  expectError(errorOf(c.file, c.overrides), c.where, c.key, c.hint);
}

// One case per kind of bad input; every bad_*.yaml differs from valid.yaml in one line. The FEM
// element size refused is one that would make 44 million triangles.
INSTANTIATE_TEST_SUITE_P(
    EachBadInput, BadSceneInput,
    ::testing::Values(BadScene{"UnknownKey",
                               "unknown_key.yaml",
                               {},
                               "unknown_key.yaml:21:5",
                               "materials[0].densty",
                               "did you mean 'density'?"},
                      BadScene{"MissingRequiredKey",
                               "missing_key.yaml",
                               {},
                               "missing_key.yaml:15:3",
                               "time",
                               "missing required key 'end'"},
                      BadScene{"WrongType",
                               "wrong_type.yaml",
                               {},
                               "wrong_type.yaml:15:8",
                               "time.end",
                               "expected a finite number in s, got 'soon'"},
                      BadScene{"NonPositiveDensity",
                               "bad_density.yaml",
                               {},
                               "bad_density.yaml:21:14",
                               "materials[0].density",
                               "must be in [0.1, 100000] kg/m^3, got -1300"},
                      BadScene{"PoissonRatioOutOfRange",
                               "bad_poisson.yaml",
                               {},
                               "bad_poisson.yaml:23:20",
                               "materials[0].poisson_ratio",
                               "must be in (-1, 0.5)"},
                      BadScene{"NonPositiveYoungsModulus",
                               "bad_youngs.yaml",
                               {},
                               "bad_youngs.yaml:22:21",
                               "materials[0].youngs_modulus",
                               "must be in [1, 1e+13] Pa, got 0"},
                      BadScene{"NonPositiveCellSize",
                               "bad_cell_size.yaml",
                               {},
                               "bad_cell_size.yaml:10:14",
                               "grid.cell_size",
                               "must be in [1e-05, 1000] m, got 0"},
                      BadScene{"BodyOutsideDomain",
                               "body_outside.yaml",
                               {},
                               "body_outside.yaml:27:5",
                               "bodies[0]",
                               "reaches outside the domain"},
                      BadScene{"UnknownMaterialName",
                               "unknown_material.yaml",
                               {},
                               "unknown_material.yaml:28:15",
                               "bodies[0].material",
                               "no material named 'sandd'; defined: sand"},
                      BadScene{"DomainNotWholeCells",
                               "valid.yaml",
                               {"grid.cell_size=0.03"},
                               "--set grid.cell_size=0.03",
                               "grid.cell_size",
                               "not a whole number of cells"},
                      BadScene{"FrictionAngleAboveTheConesLimit",
                               "valid.yaml",
                               {"materials.sand.friction_angle=61"},
                               "--set materials.sand.friction_angle=61",
                               "materials[0].friction_angle",
                               "holds no flowing slope steeper than 60 deg"},
                      BadScene{"StiffnessPerLengthWithoutImp",
                               "valid.yaml",
                               {"coupling.scheme=partitioned", "coupling.stiffness_per=length"},
                               "--set coupling.stiffness_per=length",
                               "coupling.stiffness_per",
                               "coupling.scheme: imp, imp_grid would combine"},
                      BadScene{
                          "ExactIntegrationWithoutImp",
                          "valid.yaml",
                          {"coupling.scheme=particle_surface", "coupling.normal_integration=exact"},
                          "--set coupling.normal_integration=exact",
                          "coupling.normal_integration",
                          "coupling.scheme: imp, imp_grid would combine"},
                      BadScene{"UnknownFemIntegration",
                               "valid.yaml",
                               {"time.fem_integration=implicit"},
                               "--set time.fem_integration=implicit",
                               "time.fem_integration",
                               "use one of: explicit | subcycled"},
                      BadScene{"UnknownNormalIntegration",
                               "valid.yaml",
                               {"coupling.normal_integration=implicit"},
                               "--set coupling.normal_integration=implicit",
                               "coupling.normal_integration",
                               "explicit"},
                      BadScene{"GaugeWithTwoSides",
                               "valid.yaml",
                               {"output.gauges={g: {below: 0.1, right_of: 0.2}}"},
                               "--set output.gauges={g: {below: 0.1, right_of: 0.2}}",
                               "output.gauges.g.below",
                               "give one of below (y, m) or right_of (x, m)"},
                      BadScene{"GaugeAtInfinity",
                               "valid.yaml",
                               {"output.gauges={g: {below: .inf}}"},
                               "--set output.gauges={g: {below: .inf}}",
                               "output.gauges.g.below",
                               "finite"},
                      BadScene{"ElasticModulusOnAFluid",
                               "valid_fluid.yaml",
                               {"materials.water.youngs_modulus=1e6"},
                               "--set materials.water.youngs_modulus=1e6",
                               "materials[0].youngs_modulus",
                               "a fluid's stiffness is its sound_speed"},
                      BadScene{"SoundSpeedOnASolid",
                               "valid.yaml",
                               {"materials.sand.sound_speed=30"},
                               "--set materials.sand.sound_speed=30",
                               "materials[0].sound_speed",
                               "applies only to model: fluid"},
                      BadScene{"SoundSpeedOutOfRange",
                               "valid_fluid.yaml",
                               {"materials.water.sound_speed=0"},
                               "--set materials.water.sound_speed=0",
                               "materials[0].sound_speed",
                               "must be in [0.1, 10000] m/s"},
                      BadScene{"TaitExponentOfOne",
                               "valid_fluid.yaml",
                               {"materials.water.tait_exponent=1"},
                               "--set materials.water.tait_exponent=1",
                               "materials[0].tait_exponent",
                               "must be in (1, 15]"},
                      BadScene{"FrictionAngleOnAFluid",
                               "valid_fluid.yaml",
                               {"materials.water.friction_angle=30"},
                               "--set materials.water.friction_angle=30",
                               "materials[0].friction_angle",
                               "applies only to model: drucker_prager"},
                      BadScene{"SeparationVolumeRatioBelowOne",
                               "valid.yaml",
                               {"materials.sand.separation_volume_ratio=0.9"},
                               "--set materials.sand.separation_volume_ratio=0.9",
                               "materials[0].separation_volume_ratio",
                               "must be > 1"},
                      BadScene{"UnknownCouplingScheme",
                               "valid_blocks.yaml",
                               {"coupling.scheme=partitoned"},
                               "--set coupling.scheme=partitoned",
                               "coupling.scheme",
                               "use one of: imp | imp_grid | multi_velocity | "
                               "particle_surface | partitioned"},
                      BadScene{"NegativeAdhesion",
                               "valid_blocks.yaml",
                               {"blocks.wedge.adhesion=-1"},
                               "--set blocks.wedge.adhesion=-1",
                               "blocks[1].adhesion",
                               "must be in [0, 1e+12] Pa, got -1"},
                      BadScene{"DriveOnAStaticBlock",
                               "valid_blocks.yaml",
                               {"blocks.floor.drive.angular_velocity=1"},
                               "valid_blocks.yaml",
                               "blocks[0].drive",
                               "only a dynamic block has a drive"},
                      BadScene{"DriveTooFast",
                               "valid_blocks.yaml",
                               {"blocks.wedge.drive.velocity_x=2000"},
                               "valid_blocks.yaml",
                               "blocks[1].drive",
                               "at most 1000 m/s"},
                      BadScene{"AdhesionWithBox2DContacts",
                               "valid_blocks.yaml",
                               {"blocks.wedge.adhesion=30", "block_contact.model=box2d"},
                               "--set blocks.wedge.adhesion=30",
                               "blocks[1].adhesion",
                               "needs block_contact.model: penalty"},
                      BadScene{"ClusterDiscsApart",
                               "valid_blocks.yaml",
                               {"blocks.wedge.disc_radius=0.004", "blocks.wedge.disc_pitch=0.009"},
                               "--set blocks.wedge.disc_pitch=0.009",
                               "blocks[1].disc_pitch",
                               "must lie in (0, 2 disc_radius]"},
                      BadScene{"ClusterDiscTooLarge",
                               "valid_blocks.yaml",
                               {"blocks.wedge.disc_radius=0.05"},
                               "--set blocks.wedge.disc_radius=0.05",
                               "blocks[1].disc_radius",
                               "not one disc of radius 0.05 m fits"},
                      BadScene{"ClusterDiscRadiusNotPositive",
                               "valid_cluster.yaml",
                               {"blocks.wedge.discs=[[0, 0, -0.005]]"},
                               "--set blocks.wedge.discs",
                               "blocks[1].discs",
                               "disc 0: its radius must be positive"},
                      BadScene{"SphSmoothingLengthTooLong",
                               "valid_sph.yaml",
                               {"sph.smoothing_length=0.05"},
                               "--set sph.smoothing_length=0.05",
                               "sph.smoothing_length",
                               "(0.5 to 1.5 cells: the kernel reaches twice it"},
                      BadScene{"SphUnknownBody",
                               "valid_sph.yaml",
                               {"sph.bodies=[nothing]"},
                               "--set sph.bodies=[nothing]",
                               "sph.bodies[0]",
                               "no body named 'nothing'"},
                      BadScene{"FemElementSizeTooSmall",
                               "valid_fem.yaml",
                               {"fem_bodies.barrier.element_size=0.00001"},
                               "--set fem_bodies.barrier.element_size=0.00001",
                               "fem_bodies[0].element_size",
                               "use a larger element_size"},
                      BadScene{"FemPoissonRatioOutOfRange",
                               "valid_fem.yaml",
                               {"fem_bodies.barrier.poisson_ratio=0.5"},
                               "--set fem_bodies.barrier.poisson_ratio=0.5",
                               "fem_bodies[0].poisson_ratio",
                               "must be in [0, 0.49]"},
                      BadScene{"FemHeldBoxHoldsNoNode",
                               "valid_fem.yaml",
                               {"fem_bodies.barrier.held=[[0.5, 0.2, 0.51, 0.21]]"},
                               "--set fem_bodies.barrier.held",
                               "fem_bodies[0].held[0]",
                               "holds no node of the mesh"},
                      BadScene{"FemWithGridBasedScheme",
                               "valid_fem.yaml",
                               {"coupling.scheme=multi_velocity"},
                               "--set coupling.scheme=multi_velocity",
                               "coupling.scheme",
                               "does not combine with FEM bodies"},
                      BadScene{"BlockPointsPerCellOutOfRange",
                               "valid_blocks.yaml",
                               {"coupling.block_points_per_cell=0"},
                               "--set coupling.block_points_per_cell=0",
                               "coupling.block_points_per_cell",
                               "must be 1 to 8 points per cell side"},
                      BadScene{"OverrideOfUnknownKey",
                               "valid.yaml",
                               {"time.ends=1"},
                               "--set time.ends=1",
                               "time.ends",
                               "did you mean 'end'?"},
                      BadScene{"BlockConcave",
                               "bad_block_concave.yaml",
                               {},
                               "bad_block_concave.yaml:45:15",
                               "blocks[1].vertices",
                               "not convex"},
                      BadScene{"BlockEdgesCross",
                               "bad_block_crossing.yaml",
                               {},
                               "bad_block_crossing.yaml:45:15",
                               "blocks[1].vertices",
                               "edges cross"},
                      BadScene{"BlockNineVertices",
                               "bad_block_nine_vertices.yaml",
                               {},
                               "bad_block_nine_vertices.yaml:45:15",
                               "blocks[1].vertices",
                               "at most 8 vertices"},
                      BadScene{"BlockZeroArea",
                               "bad_block_zero_area.yaml",
                               {},
                               "bad_block_zero_area.yaml:45:15",
                               "blocks[1].vertices",
                               "zero area"},
                      BadScene{"BlockRounding",
                               "bad_block_rounding.yaml",
                               {},
                               "bad_block_rounding.yaml:46:15",
                               "blocks[1].rounding",
                               "must be in [1e-05, 1000] m, got 0"},
                      BadScene{"BlocksOverlap",
                               "bad_block_overlap.yaml",
                               {},
                               "bad_block_overlap.yaml:42:5",
                               "blocks[1]",
                               "block 'wedge' overlaps block 'floor' by 0.011 m"},
                      BadScene{"BlockInMaterial",
                               "bad_block_in_material.yaml",
                               {},
                               "bad_block_in_material.yaml:42:5",
                               "blocks[1]",
                               "overlaps the material of body 'column'"},
                      BadScene{"OverrideOutOfRange",
                               "valid.yaml",
                               {"materials.sand.density=-3"},
                               "--set materials.sand.density=-3",
                               "materials[0].density",
                               "must be in [0.1, 100000] kg/m^3, got -3"},
                      BadScene{"StepCollapseNotAFraction",
                               "valid.yaml",
                               {"limits.step_collapse=1"},
                               "--set limits.step_collapse=1",
                               "limits.step_collapse",
                               "must lie in (0, 1), got 1"},
                      // Ranges that keep the arithmetic sound and time moving (limits.hpp).
                      BadScene{"BlockDensityOverflowsBox2D",
                               "valid_blocks.yaml",
                               {"blocks.wedge.density=1e300"},
                               "--set blocks.wedge.density=1e300",
                               "blocks[1].density",
                               "must be in [0.1, 100000] kg/m^3, got 1e+300"},
                      BadScene{"BlockDensityFreezesTime",
                               "valid_blocks.yaml",
                               {"blocks.wedge.density=1e-300"},
                               "--set blocks.wedge.density=1e-300",
                               "blocks[1].density",
                               "got 1e-300"},
                      BadScene{"BlockNameNotARosName",
                               "valid_blocks.yaml",
                               {"blocks.wedge.name=block 1"},
                               "--set blocks.wedge.name=block 1",
                               "blocks[1].name",
                               "only letters, digits and '_' (a ROS name and tf frame)"},
                      BadScene{"BlockNameAPath",
                               "valid_blocks.yaml",
                               {"blocks.wedge.name=../../etc/passwd"},
                               "blocks.wedge.name=../../etc/passwd",
                               "blocks[1].name",
                               "got '../../etc/passwd'"},
                      BadScene{"MaterialNameEmpty",
                               "valid.yaml",
                               {"materials.sand.name=\"\""},
                               "--set materials.sand.name",
                               "materials[0].name",
                               "must not be empty"},
                      BadScene{"StaticBlockWithVelocity",
                               "valid_blocks.yaml",
                               {"blocks.floor.velocity=[1, 0]"},
                               "--set blocks.floor.velocity=[1, 0]",
                               "blocks[0].velocity",
                               "a static block does not move"},
                      BadScene{"BlockFasterThanTheStepAllows",
                               "valid_blocks.yaml",
                               {"blocks.wedge.velocity=[1e15, 0]"},
                               "--set blocks.wedge.velocity=[1e15, 0]",
                               "blocks[1].velocity",
                               "at most 1000 m/s"},
                      BadScene{"BlockSpinFasterThanTheStepAllows",
                               "valid_blocks.yaml",
                               {"blocks.wedge.angular_velocity=1e6"},
                               "--set blocks.wedge.angular_velocity=1e6",
                               "blocks[1].angular_velocity",
                               "at most 1000 m/s"},
                      BadScene{"MovingBlockOutsideTheDomain",
                               "valid_blocks.yaml",
                               {"blocks.wedge.position=[0.5, 0.05]"},
                               "--set blocks.wedge.position=[0.5, 0.05]",
                               "blocks[1].position",
                               "reaches outside the domain"},
                      BadScene{"StaticBlockAwayFromTheDomain",
                               "valid_blocks.yaml",
                               {"blocks.floor.position=[0.2, 5]"},
                               "--set blocks.floor.position=[0.2, 5]",
                               "blocks[0].position",
                               "does not touch the domain"},
                      BadScene{"StiffnessFreezesTime",
                               "valid_blocks.yaml",
                               {"coupling.normal_stiffness=1e300"},
                               "--set coupling.normal_stiffness=1e300",
                               "coupling.normal_stiffness",
                               "must be in [1, 1e+13] N/m per m"},
                      BadScene{"ModulusFreezesTime",
                               "valid.yaml",
                               {"materials.sand.youngs_modulus=1e300"},
                               "--set materials.sand.youngs_modulus=1e300",
                               "materials[0].youngs_modulus",
                               "must be in [1, 1e+13] Pa"},
                      BadScene{"GravityBeyondAnyCentrifuge",
                               "valid.yaml",
                               {"solver.gravity=[0, -1e30]"},
                               "--set solver.gravity=[0, -1e30]",
                               "solver.gravity",
                               "its magnitude must be in [0, 10000] m/s^2"},
                      BadScene{"PicFractionWithAsflip",
                               "valid.yaml",
                               {"solver.transfer=asflip", "solver.pic_fraction=0.1"},
                               "--set solver.pic_fraction=0.1",
                               "solver.pic_fraction",
                               "applies only to transfer: flip"},
                      BadScene{"RelaxationWithApic",
                               "valid.yaml",
                               {"solver.asflip_relaxation_time=0.03"},
                               "--set solver.asflip_relaxation_time=0.03",
                               "solver.asflip_relaxation_time",
                               "applies only to transfer: asflip"},
                      BadScene{"NegativeRelaxationTime",
                               "valid.yaml",
                               {"solver.transfer=asflip", "solver.asflip_relaxation_time=-1"},
                               "--set solver.asflip_relaxation_time=-1",
                               "solver.asflip_relaxation_time",
                               "must be in [0, 1000] s"},
                      BadScene{"UnknownTransfer",
                               "valid.yaml",
                               {"solver.transfer=aflip"},
                               "--set solver.transfer=aflip",
                               "solver.transfer",
                               "use one of: apic | pic | flip | asflip"},
                      BadScene{"PeriodicOnOneSideOnly",
                               "valid.yaml",
                               {"domain.walls.left=periodic"},
                               "valid.yaml:7:5",
                               "domain.walls",
                               "left and right must both be periodic, or neither"},
                      BadScene{"GranularKeyOnDruckerPrager",
                               "valid.yaml",
                               {"materials.sand.mu_s=0.4"},
                               "--set materials.sand.mu_s=0.4",
                               "materials[0].mu_s",
                               "applies only to model: granular"},
                      BadScene{"SidewallsOfNoWidth",
                               "valid.yaml",
                               {"domain.sidewalls={width: 0, friction: 0.3}"},
                               "--set domain.sidewalls={width: 0, friction: 0.3}",
                               "domain.sidewalls.width",
                               "must be in (0, 100] m"},
                      BadScene{"TimeStepFreezesTime",
                               "valid.yaml",
                               {"time.dt=1e-300"},
                               "--set time.dt=1e-300",
                               "time.dt",
                               "must be in [1e-09, 1000] s"},
                      BadScene{"DomainBeyondFloatPrecision",
                               "valid.yaml",
                               {"domain.max=[2147483648, 0.2]"},
                               "--set domain.max=[2147483648, 0.2]",
                               "domain.max",
                               "must be in [-100000, 100000] m"},
                      // 1e10 nodes: beyond half the memory of any machine this runs on.
                      BadScene{"DomainBeyondMemory",
                               "valid.yaml",
                               {"domain.max=[1000, 1000]"},
                               "valid.yaml",
                               "grid.cell_size",
                               "more than half this machine's"},
                      BadScene{"CellsBeyondMemory",
                               "valid.yaml",
                               {"grid.cell_size=1e-5", "domain.max=[10, 10]"},
                               "--set grid.cell_size=1e-5",
                               "grid.cell_size",
                               "use larger cells or a smaller domain"},
                      BadScene{"OutputIntervalBelowRoundOff",
                               "valid.yaml",
                               {"output.interval=1e-300"},
                               "--set output.interval=1e-300",
                               "output.interval",
                               "must be in [1e-09, 1000] s"},
                      BadScene{"SceneNameNotAName",
                               "valid.yaml",
                               {"name=../../etc/passwd"},
                               "--set name=../../etc/passwd",
                               "name",
                               "must start with a letter"},
                      // The pictures' colour scale (view): its top must be above 0, in the
                      // range of its quantity, and only for quantities with a scale.
                      BadScene{"ViewMaxValueZero",
                               "bad_view_max_value.yaml",
                               {},
                               "bad_view_max_value.yaml:32:36",
                               "view.max_value",
                               "must be in (0, 1000] m/s, got 0 (the top of the speed colours"},
                      BadScene{"ViewPressureBeyondAnyModulus",
                               "valid.yaml",
                               {"view.color_by=pressure", "view.max_value=1e300"},
                               "--set view.max_value=1e300",
                               "view.max_value",
                               "must be in (0, 1e+13] Pa"},
                      BadScene{"ViewMaxValueForKinds",
                               "valid.yaml",
                               {"view.color_by=kind", "view.max_value=2"},
                               "--set view.max_value=2",
                               "view.max_value",
                               "applies only to color_by speed or pressure"},
                      BadScene{"ViewUnknownQuantity",
                               "valid.yaml",
                               {"view.color_by=velocity"},
                               "--set view.color_by=velocity",
                               "view.color_by",
                               "use one of: speed | pressure | kind"},
                      BadScene{"VerletDistanceListsEverything",
                               "valid_blocks.yaml",
                               {"coupling.verlet_distance=1e300"},
                               "--set coupling.verlet_distance=1e300",
                               "coupling.verlet_distance",
                               "must be in (0, 5 cell sizes"}),
    [](const ::testing::TestParamInfo<BadScene>& info) { return std::string(info.param.test); });

// Only a regular file of bounded size is read: a FIFO would block for ever, /dev/zero never end.
TEST(SceneErrors, OnlyARegularFileIsRead) {
  namespace fs = std::filesystem;
  const auto refused = [](const std::string& path) {
    try {
      loadScene(path);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_NE(refused("/dev/zero").find("not a regular file"), std::string::npos);
  EXPECT_NE(refused(fs::temp_directory_path().string()).find("not a regular file"),
            std::string::npos);
  EXPECT_NE(refused("/no/such/scene.yaml").find("no such scene file"), std::string::npos);
  const fs::path fifo = fs::temp_directory_path() / "mpm_sdem_test_fifo.yaml";
  fs::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_NE(refused(fifo.string()).find("not a regular file"), std::string::npos);
  fs::remove(fifo);
  const fs::path big = fs::temp_directory_path() / "mpm_sdem_test_big.yaml";
  {
    std::ofstream out(big);
    out << "# " << std::string(2 << 20, 'x') << "\n";
  }
  EXPECT_NE(refused(big.string()).find("more than a scene file's"), std::string::npos);
  fs::remove(big);
}

// A scene whose values each lie in range can still ask for a step that would stop the clock:
// World refuses it (a first step below 1e-9 s), naming the term (here a 10 um block with the
// stiffest springs allowed).
TEST(SceneErrors, AStepBelowTheFloorIsRefusedByTheWorld) {
  Scene s = loadScene(test::sourcePath("test/data/valid_blocks.yaml"),
                      {"coupling.normal_stiffness=1e13", "materials.sand.youngs_modulus=1e13",
                       "materials.sand.density=0.1"});
  try {
    World world(s.world);
    FAIL() << "accepted a first step of " << world.chooseTimeStep().dt << " s";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("a simulated second would take over"), std::string::npos)
        << e.what();
  }
}

// A message never echoes a huge value back (a pasted file as an override, a 100 kB key).
TEST(SceneErrors, MessagesCutHugeValues) {
  const std::string huge(100000, 'x');
  for (const std::vector<std::string>& set :
       {std::vector<std::string>{huge}, {"time.end=" + huge}, {huge + "=1"}}) {
    const std::string msg = errorOf("valid.yaml", set);
    ASSERT_FALSE(msg.empty());
    EXPECT_LT(msg.size(), 600u) << msg.substr(0, 300);
  }
}

TEST(SceneErrors, OverrideByMaterialNameIsApplied) {
  const Scene s =
      loadScene(test::sourcePath("test/data/valid.yaml"), {"materials.sand.density=1500"});
  EXPECT_EQ(s.world.materials[0].density, 1500);
}

TEST(SceneErrors, RunnerExitsNonZeroBeforeSimulating) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / "mpm_sdem_test_bad_scene";
  fs::remove_all(out);
  const std::string cmd = std::string(MPM_SDEM_RUNNER) + " " +
                          test::sourcePath("test/data/bad_density.yaml") + " --quiet --out " +
                          out.string() + " 2>/dev/null";
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  EXPECT_FALSE(fs::exists(out / "timeseries.csv"));
}

// The runner asks the step guard before every step: with the stop at 0.9 of the first step the
// default scene's flow (its CFL step falls by about a tenth as it speeds up) stops the run
// with status 3 and the key in the message; the default fraction lets it run (every test
// that runs the scene). Measured: stopped at t = 0.126 s, where the flow has shortened the CFL
// step to 0.793 ms (0.881 ms at rest).
TEST(SceneErrors, RunnerStopsWhenTheStepFallsBelowTheGuard) {
  namespace fs = std::filesystem;
  const fs::path out = fs::temp_directory_path() / "mpm_sdem_test_step_guard";
  fs::remove_all(out);
  const std::string cmd =
      std::string(MPM_SDEM_RUNNER) + " " +
      test::sourcePath("config/scenes/debris_impact_granular.yaml") +
      " --quiet --threads 1 --set limits.step_collapse=0.9 --set time.end=0.3 --out " +
      out.string() + " 2>" + (out.string() + ".err");
  const int status = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 3);
  std::ifstream in(out.string() + ".err");
  const std::string log((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(log.find("below 0.9 of the reference step"), std::string::npos) << log;
  EXPECT_NE(log.find("limits.step_collapse"), std::string::npos) << log;
}

// Every shipped scene parses, builds its world and steps: a few steps, all positions finite.
TEST(SceneErrors, ShippedScenesStep) {
  namespace fs = std::filesystem;
  int n = 0;
  for (const auto& e : fs::directory_iterator(test::sourcePath("config/scenes"))) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    World w(loadScene(e.path().string()).world);
    for (int i = 0; i < 5; ++i) {
      const StepInfo info = stepStable(w);
      ASSERT_TRUE(info.finite) << e.path() << " step " << i;
    }
    EXPECT_GT(w.time(), 0) << e.path();
  }
  EXPECT_GE(n, 8);
}
