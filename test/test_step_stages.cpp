// The step composed once (core/step_stages.hpp): a world runs the stages its makeup needs, in the
// table's order, and its profile names those alone; the makeup changes only with the bodies and
// point loads, and the stages with it; docs/architecture.md's step table is the code's.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "helpers.hpp"
#include "mpm_sdem/core/step_stages.hpp"

using namespace mpm_sdem;

namespace {

WorldDef bed() {
  return test::smallBed();
}

std::vector<std::string> names(const std::vector<Stage>& stages) {
  std::vector<std::string> out;
  for (const Stage s : stages) out.push_back(stageName(s));
  return out;
}

using Names = std::vector<std::string>;

}  // namespace

// Rows in the enum's order, names distinct, every stage reachable by some makeup.
TEST(StepStages, OneRowPerStageInStepOrder) {
  const std::vector<StageInfo>& table = stageTable();
  ASSERT_EQ(table.size(), static_cast<std::size_t>(Stage::kCount));
  std::vector<std::string> seen;
  for (std::size_t k = 0; k < table.size(); ++k) {
    EXPECT_EQ(static_cast<std::size_t>(table[k].stage), k);
    for (const std::string& s : seen) EXPECT_NE(s, table[k].name);
    seen.push_back(table[k].name);
  }
  StepMakeup all;  // every optional stage's condition, two makeups for the exclusive ones
  all.sph = all.sleep = all.periodic = all.sidewalls = all.inertia_scaled = all.volume_fit =
      all.volumetric_average = all.point_loads = all.contact_bodies = all.corrects = all.blocks =
          true;
  all.hooks = {true, true, true, true};
  StepMakeup usl = all;
  usl.usl = true;
  usl.sph = usl.subcycles = false;
  std::vector<bool> reached(table.size(), false);
  reached[static_cast<int>(Stage::kTimeStep)] = true;  // World::chooseTimeStep's
  for (const StepMakeup& m : {all, usl})
    for (const Stage s : composeStep(m)) reached[static_cast<int>(s)] = true;
  for (std::size_t k = 0; k < table.size(); ++k) EXPECT_TRUE(reached[k]) << table[k].name;
}

// Material alone (USF, no walls to fold, no bodies): the MPM step and nothing else, and its
// profile lists those stages with time_step.
TEST(StepStages, MaterialAloneRunsTheMpmStepOnly) {
  World w(bed());
  const Names mpm = {"sort", "clear_grid", "p2g", "grid_velocity", "stress_force", "kick", "g2p"};
  EXPECT_EQ(names(w.stages()), mpm);
  for (int k = 0; k < 5; ++k) w.step(w.chooseTimeStep().dt);
  Names listed = {"time_step"};
  listed.insert(listed.end(), mpm.begin(), mpm.end());
  EXPECT_EQ(names(w.profile().usedStages()), listed);
  EXPECT_EQ(w.profile().steps, 5);
}

// A block spawned into a world of material alone brings the coupling's stages (IMP, explicit);
// removed, they go (its record stays: check_blocks runs while the world has block storage). The
// profile keeps listing what ran.
TEST(StepStages, StagesFollowTheBodiesAndPointLoads) {
  World w(bed());
  w.step(w.chooseTimeStep().dt);
  BlockDef box = cases::boxBlock("box", Vec2(0.5, 0.3), 0.1, 0.1, 0.005, BodyType::kDynamic);
  ASSERT_EQ(w.placementProblem(box, false).text(), "");
  const BlockId id = w.addBlock(box);
  EXPECT_EQ(names(w.stages()),
            (Names{"bodies_begin", "contact_search", "sort", "clear_grid", "p2g", "grid_velocity",
                   "stress_force", "contact_forces", "kick", "g2p", "bodies", "check_blocks"}));
  w.step(w.chooseTimeStep().dt);
  w.removeBlock(id);
  EXPECT_EQ(names(w.stages()), (Names{"sort", "clear_grid", "p2g", "grid_velocity", "stress_force",
                                      "kick", "g2p", "check_blocks"}));
  w.setPointLoad(0, Vec2(0, -1));
  EXPECT_EQ(names(w.stages())[5], "point_loads");
  w.setPointLoad(0, Vec2(0, 0));
  EXPECT_EQ(std::count(w.stages().begin(), w.stages().end(), Stage::kPointLoads), 0);
  const std::vector<Stage> used = w.profile().usedStages();
  EXPECT_EQ(std::count(used.begin(), used.end(), Stage::kContactSearch), 1);
}

// Each scheme's hooks become its stages, and USL, periodic sides, side walls and scaled inertia
// theirs, in the table's order.
TEST(StepStages, SchemesAndSolverOptionsComposeTheirStages) {
  WorldDef d = bed();
  d.blocks.push_back(cases::boxBlock("box", Vec2(0.5, 0.3), 0.1, 0.1, 0.005, BodyType::kDynamic));
  d.coupling.scheme = CouplingScheme::kMultiVelocity;
  EXPECT_EQ(names(World(d).stages()),
            (Names{"bodies_begin", "sort", "clear_grid", "p2g", "grid_velocity", "stress_force",
                   "kick", "contact_correct", "corrected_walls", "g2p", "bodies", "check_blocks"}));
  d.coupling.scheme = CouplingScheme::kImp;
  d.coupling.normal_integration = ContactIntegration::kSubcycled;
  EXPECT_EQ(
      names(World(d).stages()),
      (Names{"bodies_begin", "contact_search", "sort", "clear_grid", "p2g", "grid_velocity",
             "stress_force", "kick", "contact_correct", "corrected_walls", "g2p", "check_blocks"}));
  WorldDef flume = bed();
  flume.domain.left.type = flume.domain.right.type = WallType::kPeriodic;
  flume.domain.sidewalls = {0.1, 0.3};
  flume.solver.stress_update = StressUpdate::kUsl;
  flume.solver.inertia_scale = 2;
  EXPECT_EQ(
      names(World(flume).stages()),
      (Names{"sort", "clear_grid", "p2g_force", "sidewall_load", "fold_momentum", "scale_inertia",
             "grid_velocity", "fold_forces", "kick", "sidewall_friction", "g2p", "constitutive"}));
}

// docs/architecture.md shows the table the code composes from; on a change, paste the printed
// table between the markers.
TEST(StepStages, TheArchitecturePageShowsTheCodesTable) {
  std::ifstream in(test::sourcePath("docs/architecture.md"));
  ASSERT_TRUE(in) << "docs/architecture.md";
  std::stringstream text;
  text << in.rdbuf();
  const std::string page = text.str();
  const std::string begin = "<!-- step table: generated from src/core/step_stages.cpp -->\n";
  const std::string end = "<!-- end of the step table -->";
  const std::size_t a = page.find(begin), b = page.find(end);
  ASSERT_NE(a, std::string::npos) << "no marker: " << begin;
  ASSERT_NE(b, std::string::npos) << "no marker: " << end;
  EXPECT_EQ(page.substr(a + begin.size(), b - a - begin.size()), stepTableMarkdown())
      << "the table as the code has it:\n"
      << stepTableMarkdown();
}
