// Test 8: bad scene input is refused with one message naming the file, line, key and a valid
// value, and the runner exits non-zero before simulating (no output written). The shipped scenes
// parse.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>

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

// One case per kind of bad input; every bad_*.yaml differs from valid.yaml in one line.
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
                               "must be > 0 kg/m^3"},
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
                               "must be > 0 Pa"},
                      BadScene{"NonPositiveCellSize",
                               "bad_cell_size.yaml",
                               {},
                               "bad_cell_size.yaml:10:14",
                               "grid.cell_size",
                               "must be > 0 m"},
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
                               "applies to the imp and imp_grid schemes only"},
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
                               "must be a finite number >= 0 Pa"},
                      BadScene{"AdhesionWithBox2DContacts",
                               "valid_blocks.yaml",
                               {"blocks.wedge.adhesion=30", "block_contact.model=box2d"},
                               "--set blocks.wedge.adhesion=30",
                               "blocks[1].adhesion",
                               "needs block_contact.model: penalty"},
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
                               "must be > 0 m"},
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
                               "must be > 0 kg/m^3"}),
    [](const ::testing::TestParamInfo<BadScene>& info) { return std::string(info.param.test); });

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

TEST(SceneErrors, ShippedScenesParse) {
  namespace fs = std::filesystem;
  int n = 0;
  for (const auto& e : fs::directory_iterator(test::sourcePath("config/scenes"))) {
    if (e.path().extension() != ".yaml") continue;
    ++n;
    EXPECT_NO_THROW(loadScene(e.path().string())) << e.path();
  }
  EXPECT_GE(n, 1);
}
