/// \file
/// What may not be combined: one table, one row per pair of features with its reason. The scene
/// parser and World ask it (combinationProblem), and World::placementProblem asks it for a block
/// added while running; test_exclusions walks every pair of features against it.
#pragma once

#include <vector>

#include "mpm_sdem/core/problem.hpp"

namespace mpm_sdem {

struct WorldDef;

/// The features a scene turns on, each by one key.
enum class Feature : int {
  kUsl,                ///< solver.stress_update: usl
  kSleep,              ///< solver.sleep_speed > 0
  kInertiaScale,       ///< solver.inertia_scale != 1
  kVolumeFit,          ///< solver.volume_fit: true
  kVolumetricAverage,  ///< solver.volumetric_average: true
  kPeriodic,           ///< domain.walls: left and right periodic
  kSidewalls,          ///< domain.sidewalls
  kBlocks,             ///< blocks
  kFem,                ///< fem_bodies
  kFemSubcycled,       ///< time.fem_integration: subcycled
  kSph,                ///< sph
  kImp,                ///< coupling.scheme: imp
  kImpGrid,            ///< coupling.scheme: imp_grid
  kMultiVelocity,      ///< coupling.scheme: multi_velocity
  kParticleSurface,    ///< coupling.scheme: particle_surface
  kPartitioned,        ///< coupling.scheme: partitioned
  kContactExact,       ///< coupling.normal_integration: exact
  kContactSubcycled,   ///< coupling.normal_integration: subcycled
  kSpringsPerLength,   ///< coupling.stiffness_per: length
  kCount
};

/// A feature as a scene turns it on.
struct FeatureInfo {
  Feature feature;   ///< which (the row's place in features())
  const char* name;  ///< in words ("sleeping material")
  const char* key;   ///< the scene key that turns it on ("solver.sleep_speed")
  const char* how;   ///< the value that does ("> 0")
  /// Features of one choice (the same nonzero number) are values of one key: a scene has at
  /// most one of them, so they never meet. 0: a feature of its own.
  int choice;
};

/// Every feature, indexed by Feature.
const std::vector<FeatureInfo>& features();
/// The feature's row.
const FeatureInfo& featureInfo(Feature f);

/// Two features that may not be combined, and why.
struct Exclusion {
  Feature first;       ///< the one blamed: the problem names its key
  Feature second;      ///< the one it cannot meet
  const char* reason;  ///< why they may not meet, as the refusal states it
};

/// Every exclusion: the one table.
const std::vector<Exclusion>& exclusions();

/// The features def turns on, indexed by Feature.
std::vector<bool> featuresOf(const WorldDef& def);

/// The row that refuses first and second together (in either order), or nullptr.
const Exclusion* exclusionOf(Feature first, Feature second);

/// The problem of a row: under the first feature's key, "<first> (<key> <how>) does not combine
/// with <second> (<key> <how>): <reason>", and, when the first is one value of a choice, the
/// values that would combine.
Problem exclusionProblem(const Exclusion& row);

/// The first row whose two features def turns on, as exclusionProblem; empty when none.
Problem combinationProblem(const WorldDef& def);
/// The same for features given as featuresOf gives them (a world's with a block added).
Problem combinationProblem(const std::vector<bool>& on);

}  // namespace mpm_sdem
