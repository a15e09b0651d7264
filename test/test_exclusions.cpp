// What may not be combined (core/exclusions.hpp): one table. Every pair of features is built as
// a small world: a pair the table refuses is refused by World with that row's message, and every
// other pair builds and runs steps that stay finite. The scene parser asks the same table
// (test_scene_errors: the refusals at their keys and lines).
#include <gtest/gtest.h>

#include <set>
#include <stdexcept>
#include <string>

#include "helpers.hpp"
#include "mpm_sdem/core/exclusions.hpp"
#include "mpm_sdem/mesh/mesher.hpp"

using namespace mpm_sdem;

namespace {

WorldDef base() {
  return test::smallBed();
}

// Turns feature f on, adding only what it needs; the other features stay as they were.
void enable(Feature f, WorldDef& d) {
  switch (f) {
    case Feature::kUsl:
      d.solver.stress_update = StressUpdate::kUsl;
      break;
    case Feature::kSleep:
      d.solver.sleep.speed = 0.01;
      break;
    case Feature::kInertiaScale:
      d.solver.inertia_scale = 4;
      break;
    case Feature::kVolumeFit:
      d.solver.volume_fit = true;
      break;
    case Feature::kVolumetricAverage:
      d.solver.volumetric_average = true;
      break;
    case Feature::kPeriodic:
      d.domain.left.type = d.domain.right.type = WallType::kPeriodic;
      break;
    case Feature::kSidewalls:
      d.domain.sidewalls = {0.1, 0.3};
      break;
    case Feature::kBlocks:
      d.blocks.push_back(
          cases::boxBlock("box", Vec2(0.5, 0.2), 0.1, 0.1, 0.005, BodyType::kDynamic));
      break;
    case Feature::kFem: {
      FemBodyDef beam;
      beam.name = "beam";
      beam.mesh = meshPolygon({{0.1, 0.3}, {0.2, 0.3}, {0.2, 0.4}, {0.1, 0.4}}, 0.05);
      d.fem_bodies.push_back(beam);
      break;
    }
    case Feature::kFemSubcycled:
      d.time_step.fem_subcycled = true;
      break;
    case Feature::kSph:
      d.sph.bodies = {0};
      break;
    case Feature::kImp:
      d.coupling.scheme = CouplingScheme::kImp;
      break;
    case Feature::kImpGrid:
      d.coupling.scheme = CouplingScheme::kImpGrid;
      break;
    case Feature::kMultiVelocity:
      d.coupling.scheme = CouplingScheme::kMultiVelocity;
      break;
    case Feature::kParticleSurface:
      d.coupling.scheme = CouplingScheme::kParticleSurface;
      break;
    case Feature::kPartitioned:
      d.coupling.scheme = CouplingScheme::kPartitioned;
      break;
    case Feature::kContactExact:
      d.coupling.normal_integration = ContactIntegration::kExact;
      break;
    case Feature::kContactSubcycled:
      d.coupling.normal_integration = ContactIntegration::kSubcycled;
      break;
    case Feature::kSpringsPerLength:
      d.coupling.stiffness_per = SpringBasis::kPerLength;
      d.coupling.normal_stiffness = 1e8;  // Pa: about the point springs' 1e6 N/m at 1 cm spacing
      d.coupling.tangential_stiffness = 5e7;
      break;
    case Feature::kCount:
      break;
  }
}

constexpr int kFeatures = static_cast<int>(Feature::kCount);

std::string nameOf(int f) {
  return featureInfo(static_cast<Feature>(f)).name;
}

// "" when the world builds and 20 steps stay finite; else what went wrong.
std::string runs(const WorldDef& def) {
  try {
    World w(def);
    for (int k = 0; k < 20; ++k) {
      const StepInfo info = w.step(w.chooseTimeStep().dt);
      if (!info.finite) return "a step was not finite";
    }
  } catch (const std::exception& e) {
    return std::string("refused: ") + e.what();
  }
  return "";
}

}  // namespace

// The table's rows: each names two features of the list, not of one choice (values of one key
// never meet), once; the features' rows are in the enum's order and each enabler turns on its
// feature and no other.
TEST(Exclusions, TheTableIsWellFormed) {
  ASSERT_EQ(features().size(), static_cast<std::size_t>(kFeatures));
  for (int f = 0; f < kFeatures; ++f) {
    EXPECT_EQ(static_cast<int>(features()[f].feature), f);
    WorldDef d = base();
    const std::vector<bool> before = featuresOf(d);
    enable(static_cast<Feature>(f), d);
    const std::vector<bool> after = featuresOf(d);
    EXPECT_TRUE(after[f]) << nameOf(f);
    for (int g = 0; g < kFeatures; ++g) {
      if (g == f || featureInfo(static_cast<Feature>(g)).choice != 0) continue;
      EXPECT_EQ(after[g], before[g]) << "enabling " << nameOf(f) << " turned " << nameOf(g);
    }
  }
  std::set<std::pair<int, int>> seen;
  for (const Exclusion& row : exclusions()) {
    const int a = static_cast<int>(row.first), b = static_cast<int>(row.second);
    EXPECT_NE(a, b);
    const int choice = featureInfo(row.first).choice;
    EXPECT_TRUE(choice == 0 || choice != featureInfo(row.second).choice) << nameOf(a);
    EXPECT_TRUE(seen.insert({std::min(a, b), std::max(a, b)}).second)
        << nameOf(a) << " / " << nameOf(b) << " listed twice";
    EXPECT_GT(std::string(row.reason).size(), 20u);
  }
}

// Every feature alone runs.
TEST(Exclusions, EachFeatureAloneRuns) {
  for (int f = 0; f < kFeatures; ++f) {
    WorldDef d = base();
    enable(static_cast<Feature>(f), d);
    EXPECT_EQ(runs(d), "") << nameOf(f);
  }
}

// Every pair: refused by World with its row's message, or built and stepped.
TEST(Exclusions, EveryPairIsRefusedByItsRowOrRuns) {
  int refused = 0, ran = 0;
  for (int a = 0; a < kFeatures; ++a) {
    for (int b = a + 1; b < kFeatures; ++b) {
      const Feature fa = static_cast<Feature>(a), fb = static_cast<Feature>(b);
      const int choice = featureInfo(fa).choice;
      if (choice != 0 && choice == featureInfo(fb).choice) continue;  // one key's two values
      WorldDef d = base();
      enable(fa, d);
      enable(fb, d);
      const std::string what = nameOf(a) + " with " + nameOf(b);
      if (const Exclusion* row = exclusionOf(fa, fb)) {
        EXPECT_EQ(combinationProblem(d).text(), exclusionProblem(*row).text()) << what;
        try {
          World w(d);
          ADD_FAILURE() << what << ": World accepted it";
        } catch (const std::invalid_argument& e) {
          EXPECT_EQ(std::string(e.what()), exclusionProblem(*row).text()) << what;
        }
        ++refused;
      } else {
        EXPECT_EQ(combinationProblem(d).text(), "") << what;
        EXPECT_EQ(runs(d), "") << what;
        ++ran;
      }
    }
  }
  EXPECT_EQ(refused, static_cast<int>(exclusions().size()));
  EXPECT_GT(ran, 100);
}

// A refusal names both keys, the reason, and the values of a choice that would combine.
TEST(Exclusions, TheMessageNamesTheKeysAndWhatWouldCombine) {
  const Problem p = exclusionProblem(*exclusionOf(Feature::kMultiVelocity, Feature::kFem));
  EXPECT_EQ(p.key, "coupling.scheme");
  EXPECT_EQ(p.message,
            "the multi_velocity coupling (coupling.scheme: multi_velocity) does not combine with "
            "FEM bodies (fem_bodies: a body): it needs a block's interior lattice; "
            "coupling.scheme: imp, imp_grid, particle_surface would combine");
  const Problem q = exclusionProblem(*exclusionOf(Feature::kContactExact, Feature::kPartitioned));
  EXPECT_EQ(q.key, "coupling.normal_integration");
  EXPECT_NE(q.message.find("coupling.scheme: imp, imp_grid would combine"), std::string::npos)
      << q.message;
}

// A block may not be added while running where the scene could not have had one.
TEST(Exclusions, ABlockAddedToAPeriodicWorldIsRefused) {
  WorldDef d = base();
  enable(Feature::kPeriodic, d);
  World w(d);
  const BlockDef box = cases::boxBlock("box", Vec2(0.5, 0.3), 0.1, 0.1, 0.005, BodyType::kDynamic);
  const Problem p = w.placementProblem(box, false);
  EXPECT_EQ(p.text(), exclusionProblem(*exclusionOf(Feature::kPeriodic, Feature::kBlocks)).text());
}
