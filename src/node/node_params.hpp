// The node's private parameters (~name), read once at start-up and checked: a missing or wrong
// one is an error naming it, not a silent default. Defaults and units are in docs/node.md.
#pragma once

#include <ros/node_handle.h>

#include <map>
#include <string>
#include <vector>

#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/render/render.hpp"
#include "mpm_sdem/ros/bag_recorder.hpp"
#include "mpm_sdem/scene/scene.hpp"

namespace mpm_sdem::node {

enum class EndAction { kPause, kShutdown, kContinue };

struct NodeParams {
  std::string scene;                   // scene file path (required)
  std::vector<std::string> overrides;  // "key=value" scene overrides (~set)
  std::string fixed_frame = "world";
  std::string tf_prefix = "mpm_sdem";  // block frames: <tf_prefix>/<block name>
  // Publishing, Hz of simulation time (0: off).
  double particles_rate = 30;
  int cloud_decimation = 1;  // publish every n-th material point
  double blocks_rate = 100;  // ~blocks, ~block_poses and tf
  double stats_rate = 10;
  double image_rate = 5;          // only while ~image has subscribers
  double clock_rate = 1000;       // /clock, only with /use_sim_time true
  double terrain_rate = 10;       // ~terrain
  double terrain_resolution = 0;  // m, column width of ~terrain; 0: the grid's cell size
  // ~force_arrows: metres of arrow per N/m of force; 0: the domain's larger side / 5 for the
  // weight of all the material and blocks.
  double force_arrow_scale = 0;
  // Commanded obstacles. A kinematic block's ~obstacles/<name>/cmd_vel twist lapses to zero
  // after this long without a new one (s of simulation time; 0: never), like
  // diff_drive_controller's cmd_vel_timeout.
  double cmd_vel_timeout = 0.5;
  std::map<std::string, std::string> follow_tf;  // kinematic block name -> tf frame it follows
  double follow_tf_delay = 0.1;                  // s: how far behind its frame a follower tracks it
  // m/s: the fastest a follower's points move. A frame that moves faster (a jump) is closed on
  // at this speed, with a warning naming it.
  double follow_tf_max_speed = 5;
  // A robot's links as kinematic blocks following their tf frames (robot_links.hpp): the links
  // (empty: none), the description (the parameter robot_description_param, as
  // robot_state_publisher reads it, or a URDF file), the corners' rounding (m), the blocks'
  // friction and how long to wait for the links' transforms at start (s of wall time).
  std::vector<std::string> robot_links;
  std::string robot_description_param = "robot_description";
  std::string robot_description_file;
  double robot_rounding = 0.002;
  double robot_friction = 0.5;
  double robot_tf_timeout = 10;
  render::RenderDef image;            // its scale set by chooseImageScale once the scene is read
  render::ViewRequest image_request;  // ~image/color_by and ~image/max_value, where given
  // Pacing: 0 runs as fast as possible; r > 0 keeps simulation time <= r * wall time.
  double real_time_factor = 0;
  bool start_paused = false;
  EndAction end_action = EndAction::kPause;  // at the scene's time.end
  int threads = 0;  // OpenMP threads, 0 to the cores; 0: chosen while running (ThreadTuner)
  bool allow_overlap = false;  // spawn/teleport obstacles into material or other blocks
  // Recording.
  bool record = false;
  // After ~reset: false closes the bag and the video (one recording per run of the node);
  // true starts new ones (<bag>-reset<n>.bag, ...).
  bool record_after_reset = false;
  std::string bag;       // path; default <ROS_HOME or ~/.ros>/mpm_sdem_<scene>_<date>.bag
  RecordDef record_def;  // with ~bag_checkpoint_rate (Hz; checkpoints, and one at the end)
  // Start from a checkpoint instead of the scene's initial state (mpm_sdem_run --resume's
  // forms: FILE, FOLDER or BAG[@TIME]); /clock, tf and, from a bag, the recording continue.
  std::string resume;
  std::string video;  // .avi/.mp4/.mkv path; empty: no video
  double video_fps = 30;
  // ParaView files (mpm_sdem/vtk/vtk_series.hpp) into vtk_dir every vtk_interval s of simulated
  // time; empty: none. A recording like the bag: after ~reset only with record_after_reset.
  std::string vtk_dir;
  double vtk_interval = 0.1;
};

// What is wrong with a tf frame name (names joined by '/', without a leading one; at most
// kMaxFrameLength characters), or "": the one check of ~fixed_frame, ~tf_prefix, ~follow_tf and
// the requests' reference frames.
inline constexpr std::size_t kMaxFrameLength = 256;
Problem frameProblem(const std::string& frame);

// What is wrong with the settings a user may also change while the node runs
// (dynamic_reconfigure, reconfigure.hpp): the publishing rates and decimation, the real-time
// factor and the obstacle drivers' settings; the key names the parameter. Empty when sound.
Problem runtimeProblem(const NodeParams& params);

// Fills params from the private node handle; false with a message on a bad value.
bool loadParams(const ros::NodeHandle& pnh, NodeParams& params, std::string& error);

// Sets params.image.scale from the ~image parameters, the scene's view and its default
// (render::chooseScale); false with a message when ~image/max_value cannot top that scale.
bool chooseImageScale(const Scene& scene, NodeParams& params, std::string& error);

}  // namespace mpm_sdem::node
