#include "mpm_sdem/core/step_stages.hpp"

#include <cassert>

namespace mpm_sdem {

namespace {

using M = StepMakeup;
bool always(const M&) {
  return true;
}
bool coupled(const M& m) {
  return m.contact_bodies;
}

}  // namespace

const std::vector<StageInfo>& stageTable() {
  // Seed 000 sec. 2.2 and 4.2: contact forces from the state at the start of the step, the MPM
  // step with them on the grid (eq. 48), then the bodies with the reactions (eq. 49-50).
  static const std::vector<StageInfo> table = {
      {Stage::kTimeStep, "time_step", StageOwner::kWorld, "every step, before it", always,
       "the stable step: the smallest of the CFL, contact, element, viscous and SPH terms "
       "(seed 000 eq. 51), or the fixed one"},
      {Stage::kBodiesBegin, "bodies_begin", StageOwner::kBodies, "blocks or FEM bodies", coupled,
       "FEM internal forces (seed 002 sec. 2.3), the coupling record cleared, trial velocities",
       "once per step; with time.fem_integration: subcycled, the FEM bodies' free motion in "
       "substeps of kappa_1 times their element step"},
      {Stage::kContactSearch, "contact_search", StageOwner::kCoupling,
       "the scheme searches (IMP, partitioned)",
       [](const M& m) { return m.contact_bodies && m.hooks.before_step; },
       "the contact search (Verlet list) and, explicit, the spring forces of seed 000 eq. 43 from "
       "the state at the start of the step",
       "once per step; explicit springs bound dt (contact)"},
      {Stage::kSort, "sort", StageOwner::kMpm, "no SPH", [](const M& m) { return !m.sph; },
       "the awake points binned by tiles of 3 x 3 cells"},
      {Stage::kSphSort, "sph_sort", StageOwner::kSph, "SPH", [](const M& m) { return m.sph; },
       "the particles' kinds (a point may cross a region's edge), their bins by kind and the "
       "transition band (seed 001 sec. 4)"},
      {Stage::kSleep, "sleep", StageOwner::kSleep, "solver.sleep_speed > 0",
       [](const M& m) { return m.sleep; },
       "which tiles sleep or wake (blocks and point loads keep theirs awake); on a change the "
       "sleepers' grid share rebuilt and the awake points binned again"},
      {Stage::kClearGrid, "clear_grid", StageOwner::kMpm, "always", always,
       "the nodes the last step used zeroed"},
      {Stage::kSphGradient, "sph_gradient", StageOwner::kSph, "SPH",
       [](const M& m) { return m.sph; },
       "the SPH particles' velocity gradient (seed 001 eq. 2.9) and stress, before the grid: the "
       "band lends the grid their affine velocity and stress"},
      {Stage::kP2G, "p2g", StageOwner::kMpm, "USF", [](const M& m) { return !m.usl; },
       "mass and momentum with APIC's affine part (seed 000 eq. 18-19)"},
      {Stage::kP2GForce, "p2g_force", StageOwner::kMpm, "USL", [](const M& m) { return m.usl; },
       "mass, momentum and the internal force of the stress (seed 000 eq. 13, 18-19) in one "
       "sweep"},
      {Stage::kSleepMass, "sleep_mass", StageOwner::kSleep, "solver.sleep_speed > 0",
       [](const M& m) { return m.sleep; },
       "the sleeping points' mass added to the nodes the awake points use"},
      {Stage::kSidewallLoad, "sidewall_load", StageOwner::kMpm, "USL with side walls",
       [](const M& m) { return m.usl && m.sidewalls; },
       "the side walls' friction load from the points' pressure (USF: in stress_force)"},
      {Stage::kFoldMomentum, "fold_momentum", StageOwner::kMpm, "periodic sides",
       [](const M& m) { return m.periodic; },
       "the two images of each periodic node summed: mass and momentum"},
      {Stage::kScaleInertia, "scale_inertia", StageOwner::kMpm, "solver.inertia_scale != 1",
       [](const M& m) { return m.inertia_scaled; },
       "the nodes' mass and momentum times s (their velocity unchanged)"},
      {Stage::kGridVelocity, "grid_velocity", StageOwner::kMpm, "always", always,
       "v0 = p / m (seed 000 eq. 20) and the walls"},
      {Stage::kVolumetricAverage, "volumetric_average", StageOwner::kMpm,
       "solver.volumetric_average (USF)", [](const M& m) { return m.volumetric_average && !m.usl; },
       "each point's velocity gradient (seed 000 eq. 21-22), its divergence averaged over the "
       "nodes around it (B-bar against volumetric locking, VolumetricAverage)"},
      {Stage::kStressForce, "stress_force", StageOwner::kMpm, "USF",
       [](const M& m) { return !m.usl; },
       "velocity gradient (unless volumetric_average gave it), stress update and internal force "
       "(seed 000 eq. 13, 21-25) in one sweep, with the side walls' load"},
      {Stage::kSleepForce, "sleep_force", StageOwner::kSleep, "solver.sleep_speed > 0 (USF)",
       [](const M& m) { return m.sleep && !m.usl; },
       "the sleeping points' internal force added to the awake nodes"},
      {Stage::kSphForces, "sph_forces", StageOwner::kSph, "SPH", [](const M& m) { return m.sph; },
       "the SPH particles' accelerations (seed 001 eq. 2.6-2.8), from the first pass's pairs",
       "once per step; the SPH term bounds dt (sph)"},
      {Stage::kPointLoads, "point_loads", StageOwner::kWorld, "a point load is set",
       [](const M& m) { return m.point_loads; },
       "the points' external forces spread on the grid (the f^ext of seed 000 eq. 13)"},
      {Stage::kContactForces, "contact_forces", StageOwner::kCoupling,
       "the scheme adds grid forces (IMP explicit, partitioned)",
       [](const M& m) { return m.contact_bodies && m.hooks.grid_forces; },
       "the spring forces spread on the grid (seed 000 eq. 48)"},
      {Stage::kFoldForces, "fold_forces", StageOwner::kMpm, "periodic sides",
       [](const M& m) { return m.periodic; },
       "the two images of each periodic node summed: forces and side-wall load"},
      {Stage::kKick, "kick", StageOwner::kMpm, "always", always,
       "v = v0 + dt f / m with gravity (seed 000 eq. 11, 17), local damping (unless a correction "
       "follows: corrected_walls damps then) and the walls"},
      {Stage::kSidewallFriction, "sidewall_friction", StageOwner::kMpm, "side walls",
       [](const M& m) { return m.sidewalls; },
       "Coulomb friction of the side walls on the nodes' velocities"},
      {Stage::kContactCorrect, "contact_correct", StageOwner::kCoupling,
       "the scheme corrects velocities (multi-velocity, particle-surface, subcycled IMP)",
       [](const M& m) { return m.contact_bodies && m.hooks.correct; },
       "impulses on the trial grid velocities, or the subcycled springs with the bodies' Box2D "
       "substeps within them",
       "subcycled IMP: ceil(dt / substep) substeps, each within time.contact_factor of the "
       "springs' period; else once per step"},
      {Stage::kCorrectedWalls, "corrected_walls", StageOwner::kMpm,
       "the scheme changes nodal velocities",
       [](const M& m) { return m.contact_bodies && m.corrects; },
       "local damping on the step's whole velocity change, and the walls again"},
      {Stage::kG2P, "g2p", StageOwner::kMpm, "always", always,
       "velocities, affine matrices and positions back to the material points (seed 000 eq. "
       "26-31)"},
      {Stage::kSleepNote, "sleep_note", StageOwner::kSleep, "solver.sleep_speed > 0",
       [](const M& m) { return m.sleep; },
       "the sleeping tiles that the step's moving nodes reach, to wake in the next step"},
      {Stage::kSphMove, "sph_move", StageOwner::kSph, "SPH", [](const M& m) { return m.sph; },
       "the SPH particles' kick and drift"},
      {Stage::kConstitutive, "constitutive", StageOwner::kMpm, "USL",
       [](const M& m) { return m.usl; }, "the stress update after G2P"},
      {Stage::kVolumeFit, "volume_fit", StageOwner::kMpm,
       "solver.volume_fit and a flowing material", [](const M& m) { return m.volume_fit; },
       "the shearing points of flowing materials moved down the nodes' over-fill (VolumeFit)"},
      {Stage::kContactReactions, "contact_reactions", StageOwner::kCoupling,
       "the scheme sums reactions after the points move (partitioned)",
       [](const M& m) { return m.contact_bodies && m.hooks.after_material; },
       "the reactions summed for the bodies (seed 000 eq. 49-50)"},
      {Stage::kBodies, "bodies", StageOwner::kBodies, "blocks or FEM bodies, not subcycled",
       [](const M& m) { return m.contact_bodies && !m.subcycles; },
       "blocks: Box2D with the block-block springs; FEM bodies: central differences, or the "
       "material's impulse as a kick when subcycled",
       "blocks: as many substeps as their springs need (stableStep); FEM bodies: once per step, "
       "their element step bounding dt (element)"},
      {Stage::kCheckBlocks, "check_blocks", StageOwner::kWorld, "blocks",
       [](const M& m) { return m.blocks; },
       "each moving block's state finite and its centre inside the domain"},
  };
  return table;
}

const StageInfo& stageInfo(Stage stage) {
  const StageInfo& row = stageTable()[static_cast<std::size_t>(stage)];
  assert(row.stage == stage);  // listed in the enum's order
  return row;
}

const char* stageName(Stage stage) {
  return stage == Stage::kCount ? "?" : stageInfo(stage).name;
}

const char* ownerName(StageOwner owner) {
  switch (owner) {
    case StageOwner::kWorld:
      return "World";
    case StageOwner::kMpm:
      return "MpmSolver";
    case StageOwner::kSleep:
      return "Sleep";
    case StageOwner::kCoupling:
      return "the coupling scheme";
    case StageOwner::kBodies:
      return "ContactBodies";
    case StageOwner::kSph:
      return "the SPH region";
  }
  return "?";
}

std::vector<Stage> composeStep(const StepMakeup& makeup) {
  std::vector<Stage> stages;
  for (const StageInfo& row : stageTable())
    if (row.stage != Stage::kTimeStep && row.runs(makeup)) stages.push_back(row.stage);
  return stages;
}

std::string stepTableMarkdown() {
  std::string md =
      "| # | stage (profile name) | owner of its data | runs when | what it does | its rate |\n"
      "| --- | --- | --- | --- | --- | --- |\n";
  int n = 0;
  for (const StageInfo& row : stageTable())
    md += "| " + std::to_string(n++) + " | `" + row.name + "` | " + ownerName(row.owner) + " | " +
          row.when + " | " + row.what + " | " + row.rate + " |\n";
  return md;
}

}  // namespace mpm_sdem
