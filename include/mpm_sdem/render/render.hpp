// Pictures of a world with OpenCV: material points coloured by speed or pressure, blocks drawn
// with their rounding. Used for the node's ~image topic and for videos. Not part of the core.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/world.hpp"

namespace mpm_sdem::render {

// kKind: material points blue, SPH particles (seed 001) red.
enum class ColorBy { kSpeed, kPressure, kKind };

struct RenderDef {
  int width = 800;  // px; the height follows the domain's aspect ratio
  ColorBy color_by = ColorBy::kSpeed;
  Real max_value = 0;  // m/s or Pa at the top of the colour map; 0: the frame's largest value
};

// Draws the world into image (CV_8UC3, BGR), reallocated only when its size changes.
void renderWorld(const World& world, const RenderDef& def, cv::Mat& image);

// "" or why a video cannot be written there (limits::outputFileProblem: .avi, .mp4 or .mkv).
std::string videoPathProblem(const std::string& path);

// Writes frames every 1/fps s of simulation time, played back at fps: the video runs in
// simulation time. The container follows the file name (.avi: MJPG, .mp4: mp4v, .mkv: FFV1).

class VideoRecorder {
 public:
  // Throws std::runtime_error when OpenCV cannot open a writer for path.
  VideoRecorder(const std::string& path, double fps, const RenderDef& def, const World& world);
  // Adds a frame if one is due at the world's current time.
  void record(const World& world);
  void close();
  int frames() const { return frames_; }
  const std::string& path() const { return path_; }

 private:
  cv::VideoWriter writer_;
  RenderDef def_;
  std::string path_;
  SampleClock frames_due_;
  int frames_ = 0;
  cv::Mat frame_;
};

}  // namespace mpm_sdem::render
