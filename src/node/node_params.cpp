#include "node_params.hpp"

#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/vtk/vtk_series.hpp"

namespace mpm_sdem::node {

namespace {

// Reads ~key into value when set; false (and error) when it is set with the wrong type.
template <class T>
bool read(const ros::NodeHandle& pnh, const std::string& key, T& value, const char* expected,
          std::string& error) {
  if (!pnh.hasParam(key)) return true;
  if (pnh.getParam(key, value)) return true;
  error = "parameter ~" + key + " must be " + expected;
  return false;
}

// Its type only: the bound is checked once every parameter is read (runtimeProblem for the
// publishing rates, loadParams for the bag's).
bool readRate(const ros::NodeHandle& pnh, const std::string& key, double& value,
              std::string& error) {
  return read(pnh, key, value, "a number (Hz)", error);
}

std::string defaultBagPath(const std::string& scene) {
  const char* home = std::getenv("ROS_HOME");
  std::filesystem::path dir =
      home ? home : std::string(std::getenv("HOME") ? std::getenv("HOME") : ".") + "/.ros";
  char stamp[32];
  const std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof(stamp), "%Y-%m-%d-%H-%M-%S", std::localtime(&now));
  return (dir / ("mpm_sdem_" + std::filesystem::path(scene).stem().string() + "_" + stamp + ".bag"))
      .string();
}

}  // namespace

Problem frameProblem(const std::string& frame) {
  if (frame.empty()) return "must not be empty";
  if (frame.size() > kMaxFrameLength)
    return "must be at most " + std::to_string(kMaxFrameLength) + " characters, got " +
           std::to_string(frame.size());
  std::size_t start = 0;
  while (true) {
    const std::size_t end = frame.find('/', start);
    if (const Problem p = limits::nameProblem(frame.substr(start, end - start)); !p.empty())
      return "must be names joined by '/': " + p.message;
    if (end == std::string::npos) return "";
    start = end + 1;
  }
}

Problem runtimeProblem(const NodeParams& p) {
  // The one place of these bounds: the parameters at start and dynamic_reconfigure's changes
  // (whose cfg gives none, so that a value out of them is refused, not clamped) are held to them.
  // Every message says the value it got, as asked ("got -5", not a value made of it).
  auto finite = [](double v, double lo, bool open) {
    return std::isfinite(v) && (open ? v > lo : v >= lo);
  };
  auto got = [](const char* rule, double v) {
    char m[160];
    std::snprintf(m, sizeof m, "%s, got %g", rule, v);
    return std::string(m);
  };
  const std::pair<const char*, double> rates[] = {
      {"rates/particles", p.particles_rate}, {"rates/blocks", p.blocks_rate},
      {"rates/stats", p.stats_rate},         {"rates/image", p.image_rate},
      {"rates/clock", p.clock_rate},         {"rates/terrain", p.terrain_rate}};
  for (const auto& [key, v] : rates)
    if (!finite(v, 0, false))
      return {std::string("~") + key, got("must be a finite number >= 0 Hz (0: off)", v)};
  if (p.cloud_decimation < 1)
    return {"~cloud_decimation", "must be >= 1, got " + std::to_string(p.cloud_decimation)};
  if (!finite(p.real_time_factor, 0, false))
    return {"~real_time_factor",
            got("must be a finite number >= 0 (0: as fast as possible)", p.real_time_factor)};
  if (!finite(p.cmd_vel_timeout, 0, false))
    return {"~cmd_vel_timeout",
            got("must be a finite number >= 0 s (0: never)", p.cmd_vel_timeout)};
  // tf's buffer keeps 10 s: a follower looks up its frame that far back.
  if (!finite(p.follow_tf_delay, 0, true) || !(p.follow_tf_delay <= 5))
    return {"~follow_tf_delay", got("must be in (0, 5] s", p.follow_tf_delay)};
  if (!(p.follow_tf_max_speed > 0) || !(p.follow_tf_max_speed <= limits::kSpeed.max)) {
    char m[160];
    std::snprintf(m, sizeof m, "must be in (0, %g] m/s (the speed cap of every block), got %g",
                  limits::kSpeed.max, p.follow_tf_max_speed);
    return {"~follow_tf_max_speed", m};
  }
  return {};
}

bool loadParams(const ros::NodeHandle& pnh, NodeParams& p, std::string& error) {
  // A renamed parameter is refused by its old name, not ignored.
  if (pnh.hasParam("follow_tf_time_constant")) {
    error =
        "parameter ~follow_tf_time_constant is now ~follow_tf_delay: how far behind its tf frame "
        "a follower tracks it (s, default 0.1; docs/node.md)";
    return false;
  }
  if (!pnh.getParam("scene", p.scene) || p.scene.empty()) {
    error =
        "parameter ~scene (the scene file path) is required, e.g. _scene:=$(rospack find "
        "mpm_sdem)/config/scenes/debris_impact_granular.yaml";
    return false;
  }
  std::string end = "pause", color;
  double max_value = 0;
  int decimation = p.cloud_decimation, bag_decimation = p.record_def.cloud_decimation;
  const bool ok =
      read(pnh, "set", p.overrides, "a list of \"key=value\" strings", error) &&
      read(pnh, "fixed_frame", p.fixed_frame, "a frame name", error) &&
      read(pnh, "tf_prefix", p.tf_prefix, "a string", error) &&
      readRate(pnh, "rates/particles", p.particles_rate, error) &&
      readRate(pnh, "rates/blocks", p.blocks_rate, error) &&
      readRate(pnh, "rates/stats", p.stats_rate, error) &&
      readRate(pnh, "rates/image", p.image_rate, error) &&
      readRate(pnh, "rates/clock", p.clock_rate, error) &&
      readRate(pnh, "rates/terrain", p.terrain_rate, error) &&
      read(pnh, "terrain/resolution", p.terrain_resolution, "a number (m; 0: the cell size)",
           error) &&
      read(pnh, "force_arrow_scale", p.force_arrow_scale, "a number (m per N/m; 0: automatic)",
           error) &&
      read(pnh, "cmd_vel_timeout", p.cmd_vel_timeout, "a number (s; 0: never)", error) &&
      read(pnh, "follow_tf", p.follow_tf,
           "a dictionary {block name: tf frame}, e.g. {blade: excavator/blade_link}", error) &&
      read(pnh, "follow_tf_delay", p.follow_tf_delay, "a number (s)", error) &&
      read(pnh, "follow_tf_max_speed", p.follow_tf_max_speed, "a number (m/s)", error) &&
      read(pnh, "robot_links", p.robot_links, "a list of link names, e.g. [boom, stick, bucket]",
           error) &&
      read(pnh, "robot_description_param", p.robot_description_param, "a parameter name", error) &&
      read(pnh, "robot_description_file", p.robot_description_file, "a URDF file path", error) &&
      read(pnh, "robot_rounding", p.robot_rounding, "a number (m)", error) &&
      read(pnh, "robot_friction", p.robot_friction, "a number", error) &&
      read(pnh, "robot_tf_timeout", p.robot_tf_timeout, "a number (s)", error) &&
      read(pnh, "cloud_decimation", decimation, "a whole number >= 1", error) &&
      read(pnh, "image/width", p.image.width, "a whole number of pixels", error) &&
      read(pnh, "image/color_by", color, "speed, pressure or kind", error) &&
      read(pnh, "image/max_value", max_value, "a number (m/s or Pa)", error) &&
      read(pnh, "real_time_factor", p.real_time_factor, "a number (0: as fast as possible)",
           error) &&
      read(pnh, "start_paused", p.start_paused, "true or false", error) &&
      read(pnh, "end_action", end, "pause, shutdown or continue", error) &&
      read(pnh, "threads", p.threads, "a whole number >= 0", error) &&
      read(pnh, "allow_overlap", p.allow_overlap, "true or false", error) &&
      read(pnh, "record", p.record, "true or false", error) &&
      read(pnh, "record_after_reset", p.record_after_reset, "true or false", error) &&
      read(pnh, "bag", p.bag, "a file path", error) &&
      readRate(pnh, "bag_cloud_rate", p.record_def.cloud_rate, error) &&
      readRate(pnh, "bag_state_rate", p.record_def.state_rate, error) &&
      readRate(pnh, "bag_checkpoint_rate", p.record_def.checkpoint_rate, error) &&
      read(pnh, "resume", p.resume, "a checkpoint file, a folder of them, or BAG[@TIME]", error) &&
      read(pnh, "bag_cloud_decimation", bag_decimation, "a whole number >= 1", error) &&
      read(pnh, "video", p.video, "a .avi, .mp4 or .mkv path", error) &&
      read(pnh, "video_fps", p.video_fps, "a number of frames per simulated second", error) &&
      read(pnh, "vtk/dir", p.vtk_dir, "a directory path (empty: no ParaView files)", error) &&
      read(pnh, "vtk/interval", p.vtk_interval, "a number (s of simulated time)", error);
  if (!ok) return false;
  auto fail = [&](const std::string& m) {
    error = m;
    return false;
  };
  if (const Problem f = frameProblem(p.fixed_frame); !f.empty())
    return fail("parameter ~fixed_frame " + f.message);
  if (const Problem f = frameProblem(p.tf_prefix); !f.empty())
    return fail("parameter ~tf_prefix " + f.message);
  auto nonNegative = [&](const char* key, double v, const char* unit) {
    if (v >= 0 && std::isfinite(v)) return true;
    error = std::string("parameter ~") + key + " must be a finite number >= 0 " + unit + ", got " +
            std::to_string(v);
    return false;
  };
  // The bag's rates are fixed for the run; the rates dynamic_reconfigure changes are
  // runtimeProblem's, below.
  if (!nonNegative("terrain/resolution", p.terrain_resolution, "m (0: the cell size)") ||
      !nonNegative("force_arrow_scale", p.force_arrow_scale, "m per N/m (0: automatic)") ||
      !nonNegative("bag_cloud_rate", p.record_def.cloud_rate, "Hz (0: off)") ||
      !nonNegative("bag_state_rate", p.record_def.state_rate, "Hz (0: off)") ||
      !nonNegative("bag_checkpoint_rate", p.record_def.checkpoint_rate, "Hz (0: off)"))
    return false;
  if (!(p.robot_rounding > 0 && p.robot_rounding <= 0.1))
    return fail("parameter ~robot_rounding must be in (0, 0.1] m, got " +
                std::to_string(p.robot_rounding));
  if (!(p.robot_friction >= 0 && p.robot_friction <= 10))
    return fail("parameter ~robot_friction must be in [0, 10], got " +
                std::to_string(p.robot_friction));
  if (!(p.robot_tf_timeout >= 0 && p.robot_tf_timeout <= 3600))
    return fail("parameter ~robot_tf_timeout must be in [0, 3600] s, got " +
                std::to_string(p.robot_tf_timeout));
  for (const std::string& link : p.robot_links)
    if (const Problem f = frameProblem(link); !f.empty())
      return fail("parameter ~robot_links: link " + f.message);
  for (const auto& [block, frame] : p.follow_tf) {
    if (const Problem n = limits::nameProblem(block); !n.empty())
      return fail("parameter ~follow_tf: block name " + n.message);
    if (const Problem f = frameProblem(frame); !f.empty())
      return fail("parameter ~follow_tf/" + block + ": frame " + f.message);
  }
  if (bag_decimation < 1) return fail("parameter ~bag_cloud_decimation must be >= 1");
  p.cloud_decimation = decimation;  // checked with the run-time settings below
  p.record_def.cloud_decimation = bag_decimation;
  if (p.image.width < 16 || p.image.width > 8192)
    return fail("parameter ~image/width must be 16 to 8192 px");
  if (pnh.hasParam("image/color_by")) {
    if (color == "speed") {
      p.image_request.color_by = render::ColorBy::kSpeed;
    } else if (color == "pressure") {
      p.image_request.color_by = render::ColorBy::kPressure;
    } else if (color == "kind") {
      p.image_request.color_by = render::ColorBy::kKind;
    } else {
      return fail("parameter ~image/color_by must be speed, pressure or kind, got '" + color + "'");
    }
  }
  // Its range depends on the quantity, which the scene may choose: checked in chooseImageScale.
  if (pnh.hasParam("image/max_value")) p.image_request.max_value = max_value;
  if (const Problem r = runtimeProblem(p); !r.empty()) return fail("parameter " + r.text());
  if (end == "pause") {
    p.end_action = EndAction::kPause;
  } else if (end == "shutdown") {
    p.end_action = EndAction::kShutdown;
  } else if (end == "continue") {
    p.end_action = EndAction::kContinue;
  } else {
    return fail("parameter ~end_action must be pause, shutdown or continue, got '" + end + "'");
  }
  if (const Problem t = limits::threadsProblem(p.threads); !t.empty())
    return fail("parameter ~threads " + t.message);
  if (!(p.video_fps > 0) || p.video_fps > 1000)
    return fail("parameter ~video_fps must be in (0, 1000] frames per simulated second");
  if (p.record && p.bag.empty()) p.bag = defaultBagPath(p.scene);
  // Checked now, so that a bad path stops the node before it simulates anything.
  if (p.record) {
    if (const Problem b = bagPathProblem(p.bag); !b.empty())
      return fail("parameter ~bag: " + b.message);
  }
  if (!p.video.empty()) {
    if (const Problem v = render::videoPathProblem(p.video); !v.empty())
      return fail("parameter ~video: " + v.message);
  }
  if (!(p.vtk_interval > 0) || !std::isfinite(p.vtk_interval))
    return fail("parameter ~vtk/interval must be a finite number > 0 s of simulated time, got " +
                std::to_string(p.vtk_interval));
  // Trailing slashes off, so that a reset's series is <dir>-reset<n>, not <dir>/-reset<n>.
  while (p.vtk_dir.size() > 1 && p.vtk_dir.back() == '/') p.vtk_dir.pop_back();
  if (!p.vtk_dir.empty()) {
    if (const Problem v = vtkDirProblem(p.vtk_dir); !v.empty())
      return fail("parameter ~vtk/dir: " + v.message);
  }
  p.record_def.fixed_frame = p.fixed_frame;
  p.record_def.tf_prefix = p.tf_prefix;
  p.record_def.ns = pnh.getNamespace();
  return true;
}

bool chooseImageScale(const Scene& scene, NodeParams& p, std::string& error) {
  p.image.scale = render::chooseScale(p.image_request, scene.view, scene.world);
  const render::ColorBy c = p.image.scale.color_by;
  if (!p.image_request.max_value) return true;
  if (c == render::ColorBy::kKind) {
    error =
        "parameter ~image/max_value applies only to color_by speed or pressure; the pictures "
        "show kinds (" +
        std::string(p.image_request.color_by ? "~image/color_by" : "the scene's view.color_by") +
        "): leave ~image/max_value out or set ~image/color_by";
    return false;
  }
  if (const Problem r = render::maxValueProblem(c, *p.image_request.max_value); !r.empty()) {
    error = "parameter ~image/max_value " + r.message + " (the top of the " +
            render::colorByName(c) +
            " colours; leave it out for the scene's view.max_value or its default)";
    return false;
  }
  return true;
}

}  // namespace mpm_sdem::node
