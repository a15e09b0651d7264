#include "sim_loop.hpp"

#include <omp.h>

#include <thread>

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

}  // namespace

Simulation::Simulation(ros::NodeHandle& nh, ros::NodeHandle& pnh, const NodeParams& params,
                       Scene scene, std::string scene_text)
    : params_(params),
      scene_(std::move(scene)),
      scene_text_(std::move(scene_text)),
      world_(std::make_unique<World>(scene_.world)),
      publishers_(nh, pnh, params_, scene_text_),
      paused_(params.start_paused) {
  if (params_.threads > 0) omp_set_num_threads(params_.threads);
  dt_ = world_->chooseTimeStep();
  openRecordings();
  publishers_.blocksChanged(*world_);
}

Simulation::~Simulation() {
  closeRecordings();
}

void Simulation::openRecordings() {
  conversions::StatsInput in;
  in.dt = dt_;
  if (params_.record) {
    bag_ = std::make_unique<BagRecorder>(withSuffix(params_.bag, resets_), params_.record_def,
                                         scene_text_);
    bag_->record(*world_, in);
    ROS_INFO("recording to %s(.active while open)", bag_->path().c_str());
  }
  if (!params_.video.empty()) {
    video_ = std::make_unique<render::VideoRecorder>(withSuffix(params_.video, resets_),
                                                     params_.video_fps, params_.image, *world_);
    video_->record(*world_);
    ROS_INFO("writing video to %s", video_->path().c_str());
  }
}

void Simulation::closeRecordings() {
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
}

void Simulation::restartPacing() {
  pace_wall_ = Clock::now();
  pace_sim_ = world_->time();
}

void Simulation::pace() {
  if (!(params_.real_time_factor > 0)) return;
  // Sleep until the wall clock has caught up with the simulated time (divided by the factor).
  const auto target =
      pace_wall_ + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                       (world_->time() - pace_sim_) / params_.real_time_factor));
  if (target > Clock::now()) std::this_thread::sleep_until(target);
}

void Simulation::logProgress(bool force) {
  const auto now = Clock::now();
  if (!force && now - last_log_ < std::chrono::seconds(10)) return;
  last_log_ = now;
  const double wall = std::chrono::duration<double>(now - start_wall_).count();
  ROS_INFO("t = %.4f / %.4g s, step %ld, dt %.3g s (%s), %.3g x real time", world_->time(),
           scene_.end_time, world_->stepCount(), dt_.dt, stepLimitName(dt_.limit),
           wall > 0 ? world_->time() / wall : 0.0);
}

bool Simulation::advance() {
  dt_ = world_->chooseTimeStep();
  const bool to_end = params_.end_action != EndAction::kContinue && !end_reached_;
  const Real h = to_end ? stepTowards(dt_.dt, scene_.end_time, world_->time()) : dt_.dt;
  const StepInfo info = world_->step(h);
  if (!info.finite) {
    unstable_ = true;
    paused_ = true;
    ROS_ERROR(
        "the state became non-finite at step %ld, t = %.6g s (dt = %.3g s, %s); paused. "
        "Call ~reset, and lower time.cfl or time.dt in the scene.",
        world_->stepCount(), world_->time(), h, stepLimitName(dt_.limit));
    return false;
  }
  if (bag_) {
    conversions::StatsInput in;
    in.dt = dt_;
    const double wall = std::chrono::duration<double>(Clock::now() - start_wall_).count();
    in.real_time_factor = wall > 0 ? world_->time() / wall : 0;
    in.profile = world_->profile();
    bag_->record(*world_, in);
  }
  if (video_) video_->record(*world_);
  publishers_.publish(*world_, dt_, paused_);
  if (to_end && world_->time() >= scene_.end_time * (1 - 1e-9)) {
    end_reached_ = true;
    logProgress(true);
    if (params_.end_action == EndAction::kShutdown) {
      ROS_INFO("reached the scene's end time %g s; shutting down (end_action: shutdown)",
               scene_.end_time);
      shutdown_ = true;
    } else {
      ROS_INFO("reached the scene's end time %g s; paused (~resume continues past it)",
               scene_.end_time);
      paused_ = true;
      publishers_.publish(*world_, dt_, paused_, true);
    }
  }
  return true;
}

int Simulation::run(const volatile std::sig_atomic_t& stop) {
  start_wall_ = last_log_ = Clock::now();
  restartPacing();
  publishers_.publish(*world_, dt_, paused_, true);
  ROS_INFO(
      "scene %s: %zu material points, %d blocks (coupling %s), end %g s, first dt %.3g s "
      "(%s)%s",
      scene_.name.c_str(), world_->particles().size(),
      world_->blocks() ? world_->blocks()->count() : 0,
      couplingSchemeName(world_->def().coupling.scheme), scene_.end_time, dt_.dt,
      stepLimitName(dt_.limit), paused_ ? "; paused (call ~resume)" : "");
  while (!stop && ros::ok() && !shutdown_) {
    commands_.runPending(*this);
    if (paused_) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    advance();
    pace();
    logProgress(false);
  }
  commands_.close("the node is shutting down");
  if (stop) ROS_INFO("signal received at t = %.4f s; closing the recordings", world_->time());
  closeRecordings();
  return 0;
}

Reply Simulation::pause() {
  if (paused_) return {true, "already paused at step " + std::to_string(world_->stepCount())};
  paused_ = true;
  publishers_.publish(*world_, dt_, paused_, true);
  return {true, "paused at step " + std::to_string(world_->stepCount()) +
                    ", t = " + std::to_string(world_->time()) + " s"};
}

Reply Simulation::resume() {
  if (unstable_) return {false, "the state is non-finite; call ~reset first"};
  if (!paused_) return {true, "already running"};
  paused_ = false;
  restartPacing();
  return {true, "resumed at step " + std::to_string(world_->stepCount())};
}

Reply Simulation::reset() {
  closeRecordings();
  world_ = std::make_unique<World>(scene_.world);
  ++resets_;
  unstable_ = false;
  end_reached_ = false;
  dt_ = world_->chooseTimeStep();
  openRecordings();
  publishers_.restart(*world_);
  publishers_.blocksChanged(*world_);
  publishers_.publish(*world_, dt_, paused_, true);
  restartPacing();
  return {true, "reset to t = 0 (spawned obstacles removed)" +
                    std::string(paused_ ? "; still paused" : "")};
}

Reply Simulation::step(long n) {
  if (!paused_) return {false, "~step works while paused; call ~pause first"};
  if (unstable_) return {false, "the state is non-finite; call ~reset first"};
  for (long k = 0; k < n; ++k) {
    if (!advance())
      return {false, "the state became non-finite after " + std::to_string(k + 1) + " steps"};
  }
  publishers_.publish(*world_, dt_, paused_, true);
  return {true, "took " + std::to_string(n) + " steps"};
}

void Simulation::blocksChanged() {
  dt_ = world_->chooseTimeStep();
  publishers_.blocksChanged(*world_);
  if (bag_) bag_->blocksChanged(*world_);
  publishers_.publish(*world_, dt_, paused_, true);
}

}  // namespace mpm_sdem::node
