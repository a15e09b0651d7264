/// \file
/// The stages of a step, one table: each row's name (the profile's), the owner of its data, when
/// it runs and what it does. World composes its step from the rows whose condition its makeup
/// meets (composeStep), once when it is built and again only when its makeup changes (a block
/// added to a world of material alone, the first point load); the step then runs that list with
/// no branch per feature. docs/architecture.md's step table is this table (stepTableMarkdown,
/// compared by test_step_stages).
#pragma once

#include <string>
#include <vector>

namespace mpm_sdem {

/// The stages, in the order a step runs them (time_step first: World::chooseTimeStep, before it).
enum class Stage : int {
  kTimeStep,
  kBodiesBegin,
  kContactSearch,
  kSort,
  kSphSort,
  kSleep,
  kClearGrid,
  kSphGradient,
  kP2G,
  kP2GForce,
  kSleepMass,
  kSidewallLoad,
  kFoldMomentum,
  kScaleInertia,
  kGridVelocity,
  kVolumetricAverage,
  kStressForce,
  kSleepForce,
  kSphForces,
  kPointLoads,
  kContactForces,
  kFoldForces,
  kKick,
  kSidewallFriction,
  kContactCorrect,
  kCorrectedWalls,
  kG2P,
  kSleepNote,
  kSphMove,
  kConstitutive,
  kVolumeFit,
  kContactReactions,
  kBodies,
  kCheckBlocks,
  kCount  ///< how many stages
};

/// The hooks a coupling scheme fills (Coupling::hooks): only those become stages.
struct CouplingHooks {
  bool before_step = false;     ///< Coupling::beforeStep
  bool grid_forces = false;     ///< Coupling::addGridForces
  bool correct = false;         ///< Coupling::correctGridVelocity
  bool after_material = false;  ///< Coupling::afterMaterialStep
};

/// What a world is made of, as far as its step's stages go.
struct StepMakeup {
  bool usl = false;                 ///< SolverDef::stress_update is USL (else USF)
  bool sph = false;                 ///< an SPH region or SPH bodies
  bool sleep = false;               ///< SolverDef::sleep on
  bool periodic = false;            ///< the left and right sides are one
  bool sidewalls = false;           ///< the flume's side walls (DomainDef::sidewalls)
  bool inertia_scaled = false;      ///< SolverDef::inertia_scale != 1
  bool volume_fit = false;          ///< SolverDef::volume_fit and some material flows
  bool volumetric_average = false;  ///< SolverDef::volumetric_average
  bool point_loads = false;         ///< World::setPointLoad holds a load
  bool contact_bodies = false;      ///< blocks or FEM bodies with a shape
  CouplingHooks hooks;              ///< the coupling's (with contact bodies)
  bool corrects = false;            ///< the coupling changes nodal velocities after the kick
  bool subcycles = false;           ///< the coupling steps the bodies in its substeps
  bool blocks = false;              ///< rigid blocks (their state checked after the step)
};

/// Where a stage's data lives.
enum class StageOwner { kWorld, kMpm, kSleep, kCoupling, kBodies, kSph };

/// One row of the table.
struct StageInfo {
  Stage stage;                         ///< which (the row's place in stageTable())
  const char* name;                    ///< as profiles and outputs name it
  StageOwner owner;                    ///< who holds the data it works on
  const char* when;                    ///< the condition of runs, in words
  bool (*runs)(const StepMakeup&);     ///< whether a world of this makeup runs it
  const char* what;                    ///< what it does, citing the seeds' equations
  const char* rate = "once per step";  ///< how often it runs within a step
};

/// Every stage, in step order (rows indexed by Stage).
const std::vector<StageInfo>& stageTable();
/// The stage's row.
const StageInfo& stageInfo(Stage stage);
/// The stage's name in outputs ("p2g", "contact_search", ...).
const char* stageName(Stage stage);
/// The owner's name in the docs ("MpmSolver", ...).
const char* ownerName(StageOwner owner);
/// The stages a world of this makeup runs in a step, in order (time_step not among them).
std::vector<Stage> composeStep(const StepMakeup& makeup);
/// The table as docs/architecture.md shows it (a Markdown table, one row per stage).
std::string stepTableMarkdown();

}  // namespace mpm_sdem
