#include "run.hpp"

#include <cstdio>
#include <fstream>
#include <iostream>
#include <sstream>

#include "mpm_sdem/core/checkpoint.hpp"

namespace fs = std::filesystem;

namespace mpm_sdem::runner {

namespace {

void printSummary(const Run& run) {
  const Scene& s = run.scene;
  const World& w = *run.world;
  std::fprintf(
      stderr, "scene %s (%s): %zu material points, grid %d x %d cells of %g m, %s dt, end %g s\n",
      s.name.c_str(), s.source.c_str(), w.particles().size(), w.grid().cells_x, w.grid().cells_y,
      w.def().cell_size, w.def().time_step.automatic ? "automatic" : "fixed", s.end_time);
  const Blocks* b = w.blocks();
  if (const Coupling* c = w.coupling(); b && c)
    std::fprintf(stderr, "%d blocks (Box2D scale %.4g units/m), coupling %s: %s\n", b->count(),
                 b->lengthScale(), couplingSchemeName(c->scheme()), c->settings().c_str());
  const TimeStepChoice& dt = run.sim->stableStep();
  std::fprintf(stderr, "time step %.4g s, set by the %s term\n", dt.dt, stepLimitName(dt.limit));
}

RunDef runDef(const Scene& scene, int threads) {
  RunDef def;
  def.end_time = scene.end_time;
  def.sample_interval = scene.output.interval;
  def.step_collapse = scene.limits.step_collapse;
  def.energy_growth = scene.limits.energy_growth;
  def.threads = threads;
  return def;
}

// --resume: the checkpoint into the world, after checking it continues this scene with this
// build; BAG@TIME then steps on to TIME as the bag's run did. Throws std::runtime_error saying
// why it cannot.
void resume(const std::string& spec, Run& run) {
  CatchUp caught_up;
  try {
    run.resumed = loadCheckpointSource(spec);
    resumeWorld(*run.world, run.scene, run.resumed.bytes, run.resumed.description);
    caught_up =
        catchUpToAsked(*run.world, run.resumed, run.scene.end_time, run.scene.limits.step_collapse);
  } catch (const std::exception& e) {  // a missing source, a CheckpointError, a failed step
    throw std::runtime_error("--resume " + spec + ": " + e.what());
  }
  std::fprintf(stderr, "%s\n",
               resumeDescription(run.resumed, caught_up, run.world->time()).c_str());
  if (const std::string w =
          resumeGapWarning(run.resumed, run.world->time(), run.world->chooseTimeStep().dt);
      !w.empty())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
}

// Opens the files the options ask for; throws std::runtime_error naming the one that cannot be.
void openFiles(const Options& opt, Run& run) {
  RunFiles& f = run.files;
  World& world = *run.world;
  const Real after = run.fresh() ? -1 : world.time();
  f.series = std::make_unique<TimeSeriesWriter>((run.out / "timeseries.csv").string(), *run.sim,
                                                after, run.scene.output.gauges);
  if (world.blocks())
    f.blocks = std::make_unique<BlockSeriesWriter>((run.out / "blocks.csv").string(), after);
  if (world.femBodies())
    f.fem = std::make_unique<FemSeriesWriter>((run.out / "fem_nodes.csv").string(),
                                              (run.out / "fem_elements.csv").string(), after);
  if (!opt.bag.empty()) {
    RecordDef rec;
    rec.cloud_rate = opt.bag_cloud_rate;
    rec.state_rate = opt.bag_state_rate;
    rec.checkpoint_rate = opt.bag_checkpoint_rate;
    std::ostringstream text;
    text << std::ifstream(opt.scene).rdbuf();
    f.bag = std::make_unique<BagRecorder>(opt.bag, rec, text.str(), run.scene.state_text);
    const bool continued = !run.resumed.bag.empty();
    if (continued) f.bag->continueFrom(run.resumed.bag, world.time());
    f.bag_output = std::make_unique<BagOutput>(
        *f.bag,
        [&run] {
          conversions::StatsInput in;
          in.dt = run.sim->stableStep();
          in.profile = run.world->profile();
          return in;
        },
        continued);
  }
  if (opt.vtk_every > 0) {
    f.vtk = std::make_unique<VtkSeries>((run.out / "vtk").string(), after);
    f.vtk_output = std::make_unique<VtkOutput>(*f.vtk, 1 / opt.vtk_every);
  }
  if (opt.checkpoint_every > 0)
    f.checkpoints = std::make_unique<CheckpointFiles>((run.out / "checkpoints").string(),
                                                      opt.checkpoint_every, run.scene.state_text);
  for (RunOutput* o : std::initializer_list<RunOutput*>{f.series.get(), f.blocks.get(), f.fem.get(),
                                                        f.bag_output.get(), f.vtk_output.get(),
                                                        f.checkpoints.get()})
    if (o) run.sim->attach(*o);
}

}  // namespace

bool prepare(const Options& opt, Run& run) {
  try {
    run.scene = loadScene(opt.scene, opt.overrides);
  } catch (const SceneError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return false;
  }
  try {
    run.world = std::make_unique<World>(run.scene.world);
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << opt.scene << ": " << e.what() << "\n";
    return false;
  }
  if (opt.perturb > 0) perturbPositions(run.world->particles(), opt.perturb, opt.seed);
  // Made before a resume: the energy guard's reference is the first state of the run resumed.
  run.sim = std::make_unique<Simulation>(*run.world, runDef(run.scene, opt.threads));
  run.out =
      opt.out_dir.empty() ? fs::path("out") / fs::path(opt.scene).stem() : fs::path(opt.out_dir);
  try {
    if (!opt.resume.empty()) resume(opt.resume, run);
    if (!opt.replay.empty()) {
      try {
        run.replay = std::make_unique<CommandReplay>(opt.replay, run.world->time());
      } catch (const std::exception& e) {
        throw std::runtime_error(std::string("--replay-commands: ") + e.what());
      }
      std::fprintf(stderr, "replaying %zu commands from %s\n", run.replay->count(),
                   opt.replay.c_str());
    }
    std::error_code ec;
    fs::create_directories(run.out, ec);
    if (ec)
      throw std::runtime_error("cannot create output directory " + run.out.string() + ": " +
                               ec.message());
    openFiles(opt, run);
    if (const std::string p = run.sim->start(!run.fresh()); !p.empty()) throw std::runtime_error(p);
    printSummary(run);
  } catch (const std::exception& e) {
    std::cerr << "error: " << e.what() << "\n";
    return false;
  }
  return true;
}

int finish(Run& run, int status, double wall_seconds) {
  World& world = *run.world;
  if (const std::string p = run.sim->finish(status != 3); !p.empty()) {
    std::cerr << "error: " << p << "\n";
    if (status == 0) status = 1;
  }
  if (run.scene.output.particles && status != 3)
    writeParticles(world, (run.out / "particles.csv").string());
  if (run.replay && run.replay->skipped() > 0)
    std::fprintf(stderr, "replay: %zu of %zu commands could not be applied\n",
                 run.replay->skipped(), run.replay->count());
  writeProfile(world, (run.out / "profile.csv").string());
  writeSummary(world, status, wall_seconds, (run.out / "summary.csv").string());
  const Profile& prof = world.profile();
  std::fprintf(stderr, "per-stage time (ms/step):");
  for (const Stage s : prof.usedStages())
    std::fprintf(stderr, " %s %.3f", stageName(s),
                 prof.steps ? 1e3 * prof.seconds[static_cast<int>(s)] / prof.steps : 0.0);
  std::fprintf(stderr, "\noutputs in %s\n", run.out.string().c_str());
  if (run.files.bag) {
    run.files.bag->close();
    std::fprintf(stderr, "bag: %s (%ld messages)\n", run.files.bag->path().c_str(),
                 run.files.bag->messageCount());
  }
  if (run.files.vtk)
    std::fprintf(stderr, "ParaView: %s/points.pvd (%d frames)\n", run.files.vtk->dir().c_str(),
                 run.files.vtk->frames());
  return status;
}

}  // namespace mpm_sdem::runner
