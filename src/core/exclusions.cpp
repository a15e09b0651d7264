#include "mpm_sdem/core/exclusions.hpp"

#include <cassert>
#include <string>

#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem {

namespace {

constexpr int kScheme = 1;       // coupling.scheme's values
constexpr int kIntegration = 2;  // coupling.normal_integration's

using F = Feature;

}  // namespace

const std::vector<FeatureInfo>& features() {
  static const std::vector<FeatureInfo> table = {
      {F::kUsl, "USL", "solver.stress_update", "usl", 0},
      {F::kSleep, "sleeping material", "solver.sleep_speed", "> 0", 0},
      {F::kInertiaScale, "scaled inertia", "solver.inertia_scale", "!= 1", 0},
      {F::kVolumeFit, "the volume fit", "solver.volume_fit", "true", 0},
      {F::kVolumetricAverage, "the volumetric average", "solver.volumetric_average", "true", 0},
      {F::kPeriodic, "periodic sides", "domain.walls", "periodic", 0},
      {F::kSidewalls, "side walls", "domain.sidewalls", "width > 0", 0},
      {F::kBlocks, "blocks", "blocks", "a block", 0},
      {F::kFem, "FEM bodies", "fem_bodies", "a body", 0},
      {F::kFemSubcycled, "subcycled FEM bodies", "time.fem_integration", "subcycled", 0},
      {F::kSph, "SPH particles", "sph", "a region or body", 0},
      {F::kImp, "the imp coupling", "coupling.scheme", "imp", kScheme},
      {F::kImpGrid, "the imp_grid coupling", "coupling.scheme", "imp_grid", kScheme},
      {F::kMultiVelocity, "the multi_velocity coupling", "coupling.scheme", "multi_velocity",
       kScheme},
      {F::kParticleSurface, "the particle_surface coupling", "coupling.scheme", "particle_surface",
       kScheme},
      {F::kPartitioned, "the partitioned coupling", "coupling.scheme", "partitioned", kScheme},
      {F::kContactExact, "exact normal springs", "coupling.normal_integration", "exact",
       kIntegration},
      {F::kContactSubcycled, "subcycled contact springs", "coupling.normal_integration",
       "subcycled", kIntegration},
      {F::kSpringsPerLength, "springs per length", "coupling.stiffness_per", "length", 0},
  };
  return table;
}

const FeatureInfo& featureInfo(Feature f) {
  const FeatureInfo& row = features()[static_cast<std::size_t>(f)];
  assert(row.feature == f);  // listed in the enum's order
  return row;
}

const std::vector<Exclusion>& exclusions() {
  static const char* kImpOnly =
      "it acts on the IMPs' springs (seed 000 sec. 4), which this scheme does not have";
  static const char* kPeriodicAlone =
      "the periodic fold wraps the grid alone; the contact search, the bodies and the SPH "
      "neighbours do not wrap around";
  static const char* kPointsOnly =
      "sleeping tiles are material points' alone (only they are binned by tile and their "
      "sleepers' share rebuilt)";
  static const char* kInertiaPointsOnly =
      "it scales the material points' inertia only, and these would keep theirs";
  static const std::vector<Exclusion> table = {
      {F::kSleep, F::kUsl,
       "in USL, awake material resting on sleepers drifts at a steady fraction of the sleep speed"},
      {F::kSleep, F::kSph, kPointsOnly},
      {F::kSleep, F::kFem, kPointsOnly},
      {F::kSleep, F::kSidewalls, "the side walls' friction acts on every node"},
      {F::kSleep, F::kPeriodic,
       "the sleepers' share of the grid and the tiles' waking know nothing of sides that wrap"},
      {F::kPeriodic, F::kBlocks, kPeriodicAlone},
      {F::kPeriodic, F::kFem, kPeriodicAlone},
      {F::kPeriodic, F::kSph, kPeriodicAlone},
      {F::kVolumetricAverage, F::kUsl,
       "it averages the gradient of the USF stress update; USL takes G2P's gradient after the "
       "kick"},
      {F::kVolumetricAverage, F::kSleep,
       "the sleepers' volumes are not in the nodes' sums, so their awake neighbours would average "
       "without them"},
      {F::kVolumetricAverage, F::kPeriodic, "the nodes' sums are not folded across the sides"},
      {F::kInertiaScale, F::kFem, kInertiaPointsOnly},
      {F::kInertiaScale, F::kSph, kInertiaPointsOnly},
      {F::kSph, F::kUsl,
       "the SPH particles' stress is updated with the material points' before the forces (USF)"},
      {F::kContactSubcycled, F::kFemSubcycled,
       "the contact substeps step the FEM bodies themselves; choose one of the two"},
      {F::kMultiVelocity, F::kFem, "it needs a block's interior lattice"},
      {F::kPartitioned, F::kFem, "it builds its wall from the material's outline"},
      {F::kMultiVelocity, F::kSph,
       "it meets bodies on the grid, which does not move SPH particles"},
      {F::kPartitioned, F::kSph, "it meets bodies on the grid, which does not move SPH particles"},
      {F::kContactExact, F::kMultiVelocity, kImpOnly},
      {F::kContactExact, F::kParticleSurface, kImpOnly},
      {F::kContactExact, F::kPartitioned, kImpOnly},
      {F::kContactSubcycled, F::kMultiVelocity, kImpOnly},
      {F::kContactSubcycled, F::kParticleSurface, kImpOnly},
      {F::kContactSubcycled, F::kPartitioned, kImpOnly},
      {F::kSpringsPerLength, F::kMultiVelocity, kImpOnly},
      {F::kSpringsPerLength, F::kParticleSurface, kImpOnly},
      {F::kSpringsPerLength, F::kPartitioned, kImpOnly},
  };
  return table;
}

std::vector<bool> featuresOf(const WorldDef& def) {
  std::vector<bool> on(static_cast<std::size_t>(F::kCount), false);
  auto set = [&on](Feature f, bool v) { on[static_cast<std::size_t>(f)] = v; };
  set(F::kUsl, def.solver.stress_update == StressUpdate::kUsl);
  set(F::kSleep, def.solver.sleep.on());
  set(F::kInertiaScale, def.solver.inertia_scale != 1);
  set(F::kVolumeFit, def.solver.volume_fit);
  set(F::kVolumetricAverage, def.solver.volumetric_average);
  set(F::kPeriodic,
      def.domain.left.type == WallType::kPeriodic || def.domain.right.type == WallType::kPeriodic);
  set(F::kSidewalls, def.domain.sidewalls.width > 0);
  set(F::kBlocks, !def.blocks.empty());
  set(F::kFem, !def.fem_bodies.empty());
  set(F::kFemSubcycled, def.time_step.fem_subcycled);
  set(F::kSph, def.sph.enabled());
  const CouplingScheme s = def.coupling.scheme;
  set(F::kImp, s == CouplingScheme::kImp);
  set(F::kImpGrid, s == CouplingScheme::kImpGrid);
  set(F::kMultiVelocity, s == CouplingScheme::kMultiVelocity);
  set(F::kParticleSurface, s == CouplingScheme::kParticleSurface);
  set(F::kPartitioned, s == CouplingScheme::kPartitioned);
  set(F::kContactExact, def.coupling.normal_integration == ContactIntegration::kExact);
  set(F::kContactSubcycled, def.coupling.normal_integration == ContactIntegration::kSubcycled);
  set(F::kSpringsPerLength, def.coupling.stiffness_per == SpringBasis::kPerLength);
  return on;
}

const Exclusion* exclusionOf(Feature a, Feature b) {
  for (const Exclusion& row : exclusions())
    if ((row.first == a && row.second == b) || (row.first == b && row.second == a)) return &row;
  return nullptr;
}

namespace {

// The values of f's choice that would meet other: "" when f is no choice's or none would.
std::string otherValues(Feature f, Feature other) {
  const FeatureInfo& info = featureInfo(f);
  if (info.choice == 0) return "";
  std::string values;
  for (const FeatureInfo& o : features())
    if (o.choice == info.choice && o.feature != f && !exclusionOf(o.feature, other))
      values += std::string(values.empty() ? "" : ", ") + o.how;
  return values.empty() ? "" : std::string(info.key) + ": " + values + " would combine";
}

std::string named(const FeatureInfo& f) {
  return std::string(f.name) + " (" + f.key + ": " + f.how + ")";
}

}  // namespace

Problem exclusionProblem(const Exclusion& row) {
  const FeatureInfo &a = featureInfo(row.first), &b = featureInfo(row.second);
  std::string message = named(a) + " does not combine with " + named(b) + ": " + row.reason;
  std::string hint = otherValues(row.first, row.second);
  if (hint.empty()) hint = otherValues(row.second, row.first);
  if (!hint.empty()) message += "; " + hint;
  return {a.key, message};
}

Problem combinationProblem(const WorldDef& def) {
  return combinationProblem(featuresOf(def));
}

Problem combinationProblem(const std::vector<bool>& on) {
  for (const Exclusion& row : exclusions())
    if (on[static_cast<std::size_t>(row.first)] && on[static_cast<std::size_t>(row.second)])
      return exclusionProblem(row);
  return {};
}

}  // namespace mpm_sdem
