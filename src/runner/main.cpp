// mpm_sdem_run: runs a scene without ROS and writes CSV outputs. See usage() for the interface.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

#include "checkpoint_files.hpp"
#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/core/diagnostics.hpp"
#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/stepper.hpp"
#include "mpm_sdem/core/thread_tuner.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/ros/checkpoint_source.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"
#include "options.hpp"
#include "output.hpp"
#include "progress.hpp"
#include "replay.hpp"

namespace fs = std::filesystem;
using namespace mpm_sdem;

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
void onSignal(int) {
  g_interrupted = 1;
}

void printSummary(const Scene& s, World& w) {
  const WorldDef& d = w.def();
  std::fprintf(
      stderr, "scene %s (%s): %zu material points, grid %d x %d cells of %g m, %s dt, end %g s\n",
      s.name.c_str(), s.source.c_str(), w.particles().size(), w.grid().cells_x, w.grid().cells_y,
      d.cell_size, d.time_step.automatic ? "automatic" : "fixed", s.end_time);
  const Blocks* b = w.blocks();
  if (const Coupling* c = w.coupling(); b && c)
    std::fprintf(stderr, "%d blocks (Box2D scale %.4g units/m), coupling %s: %s\n", b->count(),
                 b->lengthScale(), couplingSchemeName(c->scheme()), c->settings().c_str());
  const TimeStepChoice dt = w.chooseTimeStep();
  std::fprintf(stderr, "time step %.4g s, set by the %s term\n", dt.dt, stepLimitName(dt.limit));
}

// --resume: the checkpoint into world, after checking it continues this scene with this build.
// Returns false after saying why not.
bool resume(const std::string& spec, const Scene& scene, World& world, CheckpointSource& from) {
  try {
    from = loadCheckpointSource(spec);
    resumeWorld(world, scene, from.bytes, from.description);
  } catch (const std::exception& e) {  // a missing source, or a CheckpointError
    std::cerr << "error: --resume " << spec << ": " << e.what() << "\n";
    return false;
  }
  std::fprintf(stderr, "resuming from %s\n", from.description.c_str());
  if (const std::string w = resumeGapWarning(from, world.chooseTimeStep().dt); !w.empty())
    std::fprintf(stderr, "warning: %s\n", w.c_str());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  const auto started = std::chrono::steady_clock::now();
  runner::Options opt;
  std::string error;
  bool help = false;
  if (!runner::parseOptions(argc, argv, opt, error, help)) {
    std::cerr << "mpm_sdem_run: " << error << "\n" << runner::usage();
    return 2;
  }
  if (help) {
    std::cout << runner::usage();
    return 0;
  }
  if (opt.threads > 0) omp_set_num_threads(opt.threads);
  std::unique_ptr<ThreadTuner> tuner;
  if (opt.threads == 0)
    tuner = std::make_unique<ThreadTuner>(std::min(omp_get_max_threads(), limits::logicalCores()));

  Scene scene;
  try {
    scene = loadScene(opt.scene, opt.overrides);
  } catch (const SceneError& e) {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
  std::unique_ptr<World> world_ptr;
  try {
    world_ptr = std::make_unique<World>(scene.world);
  } catch (const std::invalid_argument& e) {
    std::cerr << "error: " << opt.scene << ": " << e.what() << "\n";
    return 1;
  }
  World& world = *world_ptr;
  if (opt.perturb > 0) perturbPositions(world.particles(), opt.perturb, opt.seed);
  // Energy scale for the growth limit: the initial total, which with potential energy measured
  // from the domain floor is the sum of non-negative terms (measured before a resume, so that a
  // resumed run keeps the limit of the run it continues).
  const Diagnostics initial = measure(world);
  const Real energy_limit = initial.total() * (1 + scene.limits.energy_growth);
  CheckpointSource resumed;
  if (!opt.resume.empty() && !resume(opt.resume, scene, world, resumed)) return 1;
  const Real resume_after = opt.resume.empty() ? -1 : world.time();
  std::unique_ptr<runner::CommandReplay> replay;
  if (!opt.replay.empty()) {
    try {
      replay = std::make_unique<runner::CommandReplay>(opt.replay, world.time());
    } catch (const std::exception& e) {
      std::cerr << "error: --replay-commands: " << e.what() << "\n";
      return 1;
    }
    std::fprintf(stderr, "replaying %zu commands from %s\n", replay->count(), opt.replay.c_str());
  }
  const fs::path out =
      opt.out_dir.empty() ? fs::path("out") / fs::path(opt.scene).stem() : fs::path(opt.out_dir);
  std::error_code ec;
  fs::create_directories(out, ec);
  if (ec) {
    std::cerr << "error: cannot create output directory " << out << ": " << ec.message() << "\n";
    return 1;
  }
  printSummary(scene, world);
  std::signal(SIGINT, onSignal);
  std::signal(SIGTERM, onSignal);

  // A resumed run continues the files of the run it resumes (their rows up to the checkpoint).
  const bool fresh = resume_after < 0;
  runner::TimeSeriesWriter series((out / "timeseries.csv").string(), resume_after,
                                  scene.output.gauges);
  std::unique_ptr<runner::BlockSeriesWriter> block_series;
  if (world.blocks()) {
    block_series =
        std::make_unique<runner::BlockSeriesWriter>((out / "blocks.csv").string(), resume_after);
    if (fresh) block_series->write(world);
  }
  std::unique_ptr<runner::FemSeriesWriter> fem_series;
  if (world.femBodies()) {
    fem_series = std::make_unique<runner::FemSeriesWriter>(
        (out / "fem_nodes.csv").string(), (out / "fem_elements.csv").string(), resume_after);
    if (fresh) fem_series->write(world);
  }
  TimeStepChoice dt = world.chooseTimeStep();
  if (fresh) series.write(world, initial, dt);
  std::unique_ptr<runner::CheckpointFiles> checkpoints;
  if (opt.checkpoint_every > 0) {
    try {
      checkpoints = std::make_unique<runner::CheckpointFiles>(
          (out / "checkpoints").string(), opt.checkpoint_every, scene.state_text);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
    if (!fresh) checkpoints->resumeAfter(world.time());
  }
  std::unique_ptr<BagRecorder> bag;
  conversions::StatsInput bag_stats;
  if (!opt.bag.empty()) {
    RecordDef rec;
    rec.cloud_rate = opt.bag_cloud_rate;
    rec.state_rate = opt.bag_state_rate;
    rec.checkpoint_rate = opt.bag_checkpoint_rate;
    std::ostringstream text;
    text << std::ifstream(opt.scene).rdbuf();
    try {
      bag = std::make_unique<BagRecorder>(opt.bag, rec, text.str(), scene.state_text);
      if (!resumed.bag.empty()) bag->continueFrom(resumed.bag, world.time());
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
    // The commands this run applies (a replay's), recorded as the node records its own.
    world.setCommandLog([&bag](const WorldCommand& c) { bag->command(c); });
    bag_stats.dt = dt;
    if (fresh || resumed.bag.empty()) bag->record(world, bag_stats);
  }
  const Real eps = 1e-9 * scene.end_time;
  // The next multiple of the interval (a sum of intervals would stall below round-off); a
  // resumed run's continues the schedule of the run it resumes.
  auto nextSample = [&](Real t) {
    return (std::floor((t + eps) / scene.output.interval) + 1) * scene.output.interval;
  };
  Real next_sample = fresh ? scene.output.interval : nextSample(world.time());
  // ParaView frames at the start, at each multiple of --vtk-every and at the end; a frame that
  // cannot be written stops the run (exit 1) rather than leave a series with a gap.
  std::unique_ptr<VtkSeries> vtk_series;
  SampleClock vtk_clock(opt.vtk_every > 0 ? 1 / opt.vtk_every : 0);
  auto writeVtk = [&] {
    try {
      if (vtk_series) vtk_series->write(world);
      return true;
    } catch (const std::exception& e) {
      std::cerr << "\nerror: " << e.what() << "\n";
      vtk_series.reset();
      return false;
    }
  };
  if (opt.vtk_every > 0) {
    try {
      vtk_series = std::make_unique<VtkSeries>((out / "vtk").string(), resume_after);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      return 1;
    }
    // The schedule starts with this frame; a resumed run's continues the run it resumes.
    vtk_clock.due(world.time(), !fresh);
    if (fresh && !writeVtk()) return 1;
  }
  runner::Progress progress(scene.end_time, !opt.quiet);
  int status = 0;
  bool mach_warned = false, outside_warned = false;
  Stepper stepper(world, scene.limits.step_collapse);
  while (!reachedEnd(world.time(), scene.end_time) && !g_interrupted) {
    const auto start = std::chrono::steady_clock::now();
    if (tuner) tuner->beforeStep();
    // Where the node applies them: between steps, before the next step is chosen (a block
    // added changes it).
    if (replay && replay->applyDue(world) && bag) bag->blocksChanged(world);
    const PlannedStep step = stepper.plan(scene.end_time);
    dt = step.stable;
    std::string problem = step.problem;
    StepInfo info;
    if (problem.empty()) {
      info = stepper.take(step, problem);
      if (tuner)
        tuner->afterStep(
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    }
    if (!problem.empty()) {
      std::cerr << "\nerror: at step " << world.stepCount() << ", t = " << world.time() << " s, "
                << problem << ". Lower time.cfl or time.dt, or refine the grid.\n";
      status = 3;
      break;
    }
    // A block outside the domain leaves the material's grid: said once, the run goes on (the
    // node pauses instead, as it does for the requests that push blocks out).
    if (!info.block_problem.empty() && !outside_warned) {
      std::cerr << "\nwarning: at t = " << world.time() << " s, " << info.block_problem << "\n";
      outside_warned = true;
    }
    if (bag) {
      bag_stats.dt = dt;
      bag_stats.profile = world.profile();
      bag->record(world, bag_stats);
    }
    if (vtk_series && vtk_clock.due(world.time()) && !writeVtk()) {
      status = 1;
      break;
    }
    if (world.time() >= next_sample - eps || reachedEnd(world.time(), scene.end_time)) {
      const Diagnostics d = measure(world);
      if (!d.finite) {
        std::cerr << "\nerror: energy or momentum became non-finite at t = " << world.time()
                  << " s; stopped before writing it.\n";
        status = 3;
        break;
      }
      if (d.total() > energy_limit && d.total() - initial.total() > 1e-12) {
        std::cerr << "\nerror: total energy grew from " << initial.total() << " to " << d.total()
                  << " J/m (limit: +" << scene.limits.energy_growth * 100
                  << "% of the initial energy, limits.energy_growth) at t = " << world.time()
                  << " s. The step is likely unstable: lower time.cfl or time.dt.\n";
        series.write(world, d, dt);
        status = 3;
        break;
      }
      if (const std::string w = machWarning(d, world.time()); !w.empty() && !mach_warned) {
        std::cerr << "\nwarning: " << w << "\n";
        mach_warned = true;
      }
      series.write(world, d, dt);
      if (block_series) block_series->write(world);
      if (fem_series) fem_series->write(world);
      next_sample = nextSample(world.time());
    }
    // Last, after every output of this step: a run killed after a checkpoint has written
    // everything up to it, and its resumed run writes everything after.
    if (checkpoints) {
      try {
        checkpoints->write(world);
      } catch (const std::exception& e) {
        std::cerr << "\nerror: " << e.what() << "\n";
        status = 1;
        break;
      }
    }
    progress.update(world.stepCount(), world.time(), step.dt,
                    static_cast<long>(world.particles().size()));
  }
  progress.finish(world.stepCount(), world.time(), static_cast<long>(world.particles().size()));
  if (g_interrupted) {
    std::cerr << "interrupted at t = " << world.time() << " s; writing the state reached\n";
    status = 130;
  }
  if (vtk_series && status != 3 && !writeVtk()) status = 1;
  if (scene.output.particles && status != 3)
    runner::writeParticles(world, (out / "particles.csv").string());
  // The state reached, to continue from (a longer run, or a killed one); not a failed state.
  if (status == 0 || status == 130) {
    try {
      if (checkpoints) checkpoints->write(world, true);
    } catch (const std::exception& e) {
      std::cerr << "error: " << e.what() << "\n";
      status = 1;
    }
    if (bag) bag->checkpoint(world);
  }
  if (replay && replay->skipped() > 0)
    std::fprintf(stderr, "replay: %zu of %zu commands could not be applied\n", replay->skipped(),
                 replay->count());
  runner::writeProfile(world, (out / "profile.csv").string());
  runner::writeSummary(
      world, status,
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
      (out / "summary.csv").string());
  const Profile& prof = world.profile();
  std::fprintf(stderr, "per-stage time (ms/step):");
  for (int s = 0; s < static_cast<int>(Stage::kCount); ++s) {
    std::fprintf(stderr, " %s %.3f", stageName(static_cast<Stage>(s)),
                 prof.steps ? 1e3 * prof.seconds[s] / prof.steps : 0.0);
  }
  std::fprintf(stderr, "\noutputs in %s\n", out.string().c_str());
  if (bag) {
    bag->close();
    std::fprintf(stderr, "bag: %s (%ld messages)\n", bag->path().c_str(), bag->messageCount());
  }
  if (vtk_series)
    std::fprintf(stderr, "ParaView: %s/points.pvd (%d frames)\n", vtk_series->dir().c_str(),
                 vtk_series->frames());
  return status;
}
