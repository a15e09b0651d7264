#include "sim_loop.hpp"

#include <cstdio>
#include <limits>
#include <thread>
#include <tuple>

#include "mpm_sdem/core/checkpoint.hpp"
#include "mpm_sdem/ros/checkpoint_source.hpp"

namespace mpm_sdem::node {

namespace {

std::string withSuffix(const std::string& path, int n) {
  if (n == 0) return path;
  const std::size_t dot = path.find_last_of('.');
  const std::string tag = "-reset" + std::to_string(n);
  return dot == std::string::npos || dot < path.find_last_of('/') + 1
             ? path + tag
             : path.substr(0, dot) + tag + path.substr(dot);
}

// The video as one of the run's outputs: a frame of the first state and after every step (the
// recorder keeps its own frame rate).
class VideoOutput : public RunOutput {
 public:
  explicit VideoOutput(render::VideoRecorder& video) : video_(video) {}
  void start(World& world, bool) override { video_.record(world); }
  void step(World& world) override { video_.record(world); }

 private:
  render::VideoRecorder& video_;
};

}  // namespace

SimLoop::SimLoop(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params, Scene scene,
                 std::string scene_text)
    : params_(params),
      scene_(std::move(scene)),
      scene_text_(std::move(scene_text)),
      world_(std::make_unique<World>(scene_.world)),
      drivers_(pnh, commands_, params_),
      robot_links_(nh, params_),
      publishers_(nh, pnh, params_, scene_text_, *world_),
      paused_(params.start_paused) {
  if (!params_.resume.empty()) resumeFromCheckpoint();
  drivers_.checkFollowers(*world_);
  if (const Problem p = publishers_.terrainProblem(*world_); !p.empty())
    throw std::runtime_error(p.text());
  drivers_.sync(*world_, true);
  startRun();
  publishers_.blocksChanged(*world_);
  reconfigure_ = std::make_unique<Reconfigure>(pnh, commands_, settings());
}

SimLoop::~SimLoop() {
  closeRecordings();
}

void SimLoop::resumeFromCheckpoint() {
  CheckpointSource from;
  CatchUp caught_up;
  try {
    from = loadCheckpointSource(params_.resume);
    resumeWorld(*world_, scene_, from.bytes, from.description);
    // The steps as the recorded node took them: landed on the scene's end time until it was
    // reached (end_action pause or shutdown), past it with no end.
    const bool to_end = params_.end_action != EndAction::kContinue && from.time < scene_.end_time;
    caught_up = catchUpToAsked(*world_, from,
                               to_end ? scene_.end_time : std::numeric_limits<Time>::infinity(),
                               scene_.limits.step_collapse);
  } catch (const std::exception& e) {
    throw std::runtime_error("~resume " + params_.resume + ": " + e.what());
  }
  resumed_bag_ = from.bag;
  ROS_INFO("%s: t = %.6g s, step %ld", resumeDescription(from, caught_up, world_->time()).c_str(),
           world_->time(), world_->stepCount());
  if (const std::string w = resumeGapWarning(from, world_->time(), world_->chooseTimeStep().dt);
      !w.empty())
    ROS_WARN("~resume: %s", w.c_str());
}

void SimLoop::startRun() {
  RunDef def;
  if (params_.end_action != EndAction::kContinue) def.end_time = scene_.end_time;
  def.sample_interval = scene_.output.interval;  // for the Mach number's warning
  def.step_collapse = scene_.limits.step_collapse;
  // No energy guard (RunDef's infinite default): the obstacles users command do work on the
  // material, and a run whose energy they raised is not unstable.
  def.threads = params_.threads;
  sim_ = std::make_unique<Simulation>(*world_, def);
  openRecordings();
  // A resumed run's first recordings continue those of the run it resumes.
  if (const std::string p = sim_->start(!params_.resume.empty() && resets_ == 0); !p.empty())
    ROS_ERROR("%s; that recording stops, the run goes on", p.c_str());
}

conversions::StatsInput SimLoop::status() const {
  conversions::StatsInput in;
  in.dt = sim_->stableStep();
  in.paused = paused_ && pending_steps_ == 0;
  in.real_time_factor = real_time_.factor();
  in.profile = world_->profile();
  return in;
}

void SimLoop::openRecordings() {
  if (!recording_) return;
  // A resumed run's first recordings continue those of the run it resumes.
  const bool resumed = !params_.resume.empty() && resets_ == 0;
  if (params_.record) {
    bag_ = std::make_unique<BagRecorder>(withSuffix(params_.bag, resets_), params_.record_def,
                                         scene_text_, scene_.state_text);
    // The bag starts with the resumed bag's run up to the checkpoint.
    const bool continued = resumed && !resumed_bag_.empty();
    if (continued) bag_->continueFrom(resumed_bag_, world_->time());
    outputs_.push_back(std::make_unique<BagOutput>(
        *bag_, [this] { return status(); }, continued));
    ROS_INFO("recording to %s(.active while open)", bag_->path().c_str());
  }
  if (!params_.video.empty()) {
    video_ = std::make_unique<render::VideoRecorder>(withSuffix(params_.video, resets_),
                                                     params_.video_fps, params_.image, *world_);
    outputs_.push_back(std::make_unique<VideoOutput>(*video_));
    ROS_INFO("writing video to %s", video_->path().c_str());
  }
  if (!params_.vtk_dir.empty()) {
    try {
      vtk_ = std::make_unique<VtkSeries>(withSuffix(params_.vtk_dir, resets_),
                                         resumed ? world_->time() : -1);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string("parameter ~vtk/dir: ") + e.what());
    }
    outputs_.push_back(std::make_unique<VtkOutput>(*vtk_, 1 / params_.vtk_interval));
    ROS_INFO("writing ParaView files to %s (points.pvd, every %g s)", vtk_->dir().c_str(),
             params_.vtk_interval);
  }
  for (const auto& o : outputs_) sim_->attach(*o);
}

void SimLoop::closeRecordings() {
  // Their ends: the bag's checkpoint of the state reached, to continue from, and the last
  // ParaView frame, unless the state is not finite (as the runner).
  if (sim_) {
    if (const std::string p = sim_->finish(!unstable_); !p.empty())
      ROS_ERROR("at t = %.6g s: %s", world_->time(), p.c_str());
  }
  outputs_.clear();
  if (bag_) {
    bag_->close();
    ROS_INFO("bag closed: %s (%ld messages, up to t = %.4f s)", bag_->path().c_str(),
             bag_->messageCount(), world_->time());
    bag_.reset();
  }
  if (video_) {
    video_->close();
    ROS_INFO("video closed: %s (%d frames at %g fps)", video_->path().c_str(), video_->frames(),
             params_.video_fps);
    video_.reset();
  }
  if (vtk_) {
    ROS_INFO("ParaView files: %s/points.pvd (%d frames, up to t = %.4f s)", vtk_->dir().c_str(),
             vtk_->frames(), vtk_->lastTime());
    vtk_.reset();
  }
}

void SimLoop::restartPacing() {
  pace_wall_ = Clock::now();
  pace_sim_ = world_->time();
}

void SimLoop::pace() {
  if (!(params_.real_time_factor > 0)) return;
  // Sleep until the wall clock has caught up with the simulated time (divided by the factor).
  const auto target =
      pace_wall_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                       (world_->time() - pace_sim_) / params_.real_time_factor));
  if (target > Clock::now()) std::this_thread::sleep_until(target);
}

void SimLoop::logProgress(bool force) {
  const auto now = Clock::now();
  if (!force && now - last_log_ < std::chrono::seconds(10)) return;
  last_log_ = now;
  ROS_INFO(
      "t = %.4f / %.4g s, step %ld, dt %.3g s (%s), %.3g x real time over the last %g s "
      "run, %d threads",
      world_->time(), scene_.end_time, world_->stepCount(), sim_->stableStep().dt,
      stepLimitName(sim_->stableStep().limit), real_time_.factor(), RealTimeMeter::kWindow,
      sim_->threads());
}

void SimLoop::noteRequest(const std::string& what) {
  char at[96];
  std::snprintf(at, sizeof at, " at step %ld, t = %.6g s", world_->stepCount(), world_->time());
  last_request_ = what + at;
}

void SimLoop::fail(const std::string& what, Real dt) {
  unstable_ = true;
  paused_ = true;
  pending_steps_ = 0;
  const std::string cause = last_request_.empty()
                                ? "Call ~reset, and lower time.cfl or time.dt in the scene."
                                : "The last request before it was " + last_request_ +
                                      "; call ~reset (a request like it will do the same).";
  char at[160];
  std::snprintf(at, sizeof at, " at step %ld, t = %.6g s (dt = %.3g s, %s)", world_->stepCount(),
                world_->time(), dt, stepLimitName(sim_->stableStep().limit));
  publishers_.publish(*world_, status(), true);
  if (endInsteadOfPausing(what + at)) return;
  ROS_ERROR("%s%s; paused. %s", what.c_str(), at, cause.c_str());
}

void SimLoop::pauseOutside(const std::string& what) {
  paused_ = true;
  pending_steps_ = 0;
  const std::string cause =
      last_request_.empty() ? "" : " The last request before it was " + last_request_ + ".";
  publishers_.publish(*world_, status(), true);
  char at[96];
  std::snprintf(at, sizeof at, " at step %ld, t = %.6g s", world_->stepCount(), world_->time());
  if (endInsteadOfPausing(what + at + cause)) return;
  ROS_ERROR(
      "%s%s; paused.%s Move it back (~set_obstacle_state), remove it (~remove_obstacle) or call "
      "~reset, then ~resume.",
      what.c_str(), at, cause.c_str());
}

bool SimLoop::endInsteadOfPausing(const std::string& why) {
  if (params_.end_action != EndAction::kShutdown) return false;
  // The runner's status for a run that cannot go on (docs/running.md); the recordings close
  // properly on the way out, up to this state.
  exit_status_ = 3;
  shutdown_ = true;
  ROS_ERROR(
      "%s; the run cannot go on without a request, and with end_action shutdown none is awaited: "
      "shutting down with status %d (end_action pause waits for ~reset or ~resume instead)",
      why.c_str(), exit_status_);
  return true;
}

void SimLoop::publishWhilePaused() {
  // /clock holds its time and ~stats (latched) stays fresh for late listeners.
  const auto now = Clock::now();
  if (now - last_idle_ < std::chrono::milliseconds(500)) return;
  last_idle_ = now;
  // A robot's links appear while paused too, as their transforms arrive.
  if (robot_links_.spawnArrived(*world_, drivers_)) blocksChanged();
  publishers_.publishIdle(*world_, status());
}

bool SimLoop::advance() {
  if (robot_links_.spawnArrived(*world_, drivers_)) blocksChanged();
  const RunStep step = sim_->advance([this](Real dt) { drivers_.beforeStep(*world_, dt); });
  if (!step.problem.empty()) {
    fail(step.problem, step.dt > 0 ? step.dt : sim_->stableStep().dt);
    return false;
  }
  if (!step.output_problem.empty())
    ROS_ERROR("%s at t = %.6g s; that recording stops here, the run goes on",
              step.output_problem.c_str(), world_->time());
  if (!step.warning.empty()) ROS_WARN("%s", step.warning.c_str());
  real_time_.sample(world_->time());
  publishers_.publish(*world_, status());
  if (!step.info.block_problem.empty()) {
    // A dynamic block pushed or thrown out of the domain (kinematic ones stop at its walls):
    // the step is sound and recorded, but the block has left the material's grid.
    pauseOutside(step.info.block_problem);
    return false;
  }
  if (params_.end_action != EndAction::kContinue && !end_reached_ && sim_->ended()) {
    end_reached_ = true;
    sim_->setEndTime(std::numeric_limits<Time>::infinity());  // ~resume runs on past it
    logProgress(true);
    if (params_.end_action == EndAction::kShutdown) {
      ROS_INFO("reached the scene's end time %g s; shutting down (end_action: shutdown)",
               scene_.end_time);
      shutdown_ = true;
    } else {
      ROS_INFO("reached the scene's end time %g s; paused (~resume continues past it)",
               scene_.end_time);
      paused_ = true;
      pending_steps_ = 0;
      publishers_.publish(*world_, status(), true);
    }
  }
  return true;
}

int SimLoop::run(const volatile std::sig_atomic_t& stop) {
  last_log_ = Clock::now();
  restartPacing();
  publishers_.publish(*world_, status(), true);
  ROS_INFO(
      "scene %s: %zu material points, %d blocks (coupling %s), end %g s, first dt %.3g s "
      "(%s)%s",
      scene_.name.c_str(), world_->particles().size(),
      world_->blocks() ? world_->blocks()->count() : 0,
      couplingSchemeName(world_->def().coupling.scheme), scene_.end_time, sim_->stableStep().dt,
      stepLimitName(sim_->stableStep().limit), paused_ ? "; paused (call ~resume)" : "");
  while (!stop && ros::ok() && !shutdown_) {
    commands_.runPending(*this);
    const bool stepping = pending_steps_ > 0;
    real_time_.setRunning(!paused_ || stepping);
    if (paused_ && !stepping) {
      publishWhilePaused();
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    // ~step's steps run unpaced, one per pass, so that commands (~pause) come in between.
    // (Reaching the scene's end, or failing, has already cleared pending_steps_.)
    if (advance() && pending_steps_ > 0 && --pending_steps_ == 0) {
      ROS_INFO("took the %ld steps asked for; at step %ld, t = %.6g s", asked_steps_,
               world_->stepCount(), world_->time());
      publishers_.publish(*world_, status(), true);
    }
    if (!stepping) pace();
    logProgress(false);
  }
  commands_.close("the node is shutting down");
  if (stop) ROS_INFO("signal received at t = %.4f s; closing the recordings", world_->time());
  closeRecordings();
  return exit_status_;
}

Reply SimLoop::pause() {
  if (pending_steps_ > 0) {
    const long left = pending_steps_;
    pending_steps_ = 0;
    publishers_.publish(*world_, status(), true);
    return {true, "cancelled the last " + std::to_string(left) + " of " +
                      std::to_string(asked_steps_) + " steps; paused at step " +
                      std::to_string(world_->stepCount())};
  }
  if (paused_) return {true, "already paused at step " + std::to_string(world_->stepCount())};
  paused_ = true;
  publishers_.publish(*world_, status(), true);
  return {true, "paused at step " + std::to_string(world_->stepCount()) +
                    ", t = " + std::to_string(world_->time()) + " s"};
}

Reply SimLoop::resume() {
  if (unstable_) return {false, "the state is non-finite; call ~reset first"};
  if (!paused_) return {true, "already running"};
  paused_ = false;
  pending_steps_ = 0;
  restartPacing();
  return {true, "resumed at step " + std::to_string(world_->stepCount())};
}

Reply SimLoop::reset() {
  const bool was_recording = bag_ || video_;
  closeRecordings();
  sim_.reset();
  world_ = std::make_unique<World>(scene_.world);
  ++resets_;
  unstable_ = false;
  end_reached_ = false;
  pending_steps_ = 0;
  last_request_.clear();
  real_time_.clear();
  drivers_.sync(*world_, true);  // held loads and commands end with the run they were for
  recording_ = params_.record_after_reset;
  startRun();
  publishers_.restart(*world_);
  publishers_.blocksChanged(*world_);
  publishers_.publish(*world_, status(), true);
  restartPacing();
  reconfigure_->publish(settings());  // the scene's gravity again
  std::string note = paused_ ? "; still paused" : "";
  if (was_recording && !recording_)
    note +=
        "; the recording of the run before it is closed (~record_after_reset: true records "
        "each run)";
  return {
      true,
      "reset to t = 0 (spawned obstacles removed, held loads and velocity commands ended)" + note};
}

RuntimeSettings SimLoop::settings() const {
  return {params_, world_->def().solver.gravity};
}

Reply SimLoop::applySettings(const RuntimeSettings& s) {
  NodeParams& p = params_;
  const NodeParams& q = s.params;
  std::string changed;
  auto note = [&changed](const char* name, double from, double to) {
    if (from == to) return false;
    char text[128];
    std::snprintf(text, sizeof text, "%s%s %g -> %g", changed.empty() ? "" : ", ", name, from, to);
    changed += text;
    return true;
  };
  if (note("real_time_factor", p.real_time_factor, q.real_time_factor)) {
    p.real_time_factor = q.real_time_factor;
    restartPacing();
  }
  bool rates = false;
  for (auto [name, from, to] : {std::tuple{"particles_rate", &p.particles_rate, q.particles_rate},
                                std::tuple{"blocks_rate", &p.blocks_rate, q.blocks_rate},
                                std::tuple{"stats_rate", &p.stats_rate, q.stats_rate},
                                std::tuple{"image_rate", &p.image_rate, q.image_rate},
                                std::tuple{"terrain_rate", &p.terrain_rate, q.terrain_rate},
                                std::tuple{"clock_rate", &p.clock_rate, q.clock_rate}})
    if (note(name, *from, to)) *from = to, rates = true;
  if (rates) publishers_.setRates();
  if (note("cloud_decimation", p.cloud_decimation, q.cloud_decimation))
    p.cloud_decimation = q.cloud_decimation;
  // The drivers read these before every step; the velocities they give are recorded commands.
  for (auto [name, from, to] :
       {std::tuple{"cmd_vel_timeout", &p.cmd_vel_timeout, q.cmd_vel_timeout},
        std::tuple{"follow_tf_delay", &p.follow_tf_delay, q.follow_tf_delay},
        std::tuple{"follow_tf_max_speed", &p.follow_tf_max_speed, q.follow_tf_max_speed}})
    if (note(name, *from, to)) *from = to;
  const Vec2 g = world_->def().solver.gravity;
  if (note("gravity_x", g.x(), s.gravity.x()) | note("gravity_y", g.y(), s.gravity.y())) {
    world_->setGravity(s.gravity);  // checked by the callback; a command in the bag
    noteRequest("gravity set to (" + std::to_string(s.gravity.x()) + ", " +
                std::to_string(s.gravity.y()) + ") m/s^2");
  }
  if (changed.empty()) return {true, "nothing changed"};
  ROS_INFO("dynamic_reconfigure at t = %.6g s: %s", world_->time(), changed.c_str());
  publishers_.publish(*world_, status(), true);
  return {true, changed};
}

Reply SimLoop::step(long n) {
  if (!paused_) return {false, "~step works while paused; call ~pause first"};
  if (unstable_) return {false, "the state is non-finite; call ~reset first"};
  if (pending_steps_ > 0)
    return {false, "still taking " + std::to_string(pending_steps_) + " of " +
                       std::to_string(asked_steps_) + " steps; ~pause cancels them"};
  pending_steps_ = asked_steps_ = n;
  return {true, "taking " + std::to_string(n) + " steps from step " +
                    std::to_string(world_->stepCount()) +
                    " between commands; ~pause cancels them, ~stats shows the progress"};
}

void SimLoop::blocksChanged() {
  sim_->blocksChanged();  // the step chosen again, the bag's static frames
  drivers_.sync(*world_);
  publishers_.blocksChanged(*world_);
  publishers_.publish(*world_, status(), true);
}

}  // namespace mpm_sdem::node
