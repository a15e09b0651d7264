// Pictures of a world with OpenCV: material points coloured by speed, pressure or kind on a
// fixed scale, blocks drawn with their rounding and named, a colour bar, a scale bar and the time.
// Used for the node's ~image topic and for videos. Not part of the core.
#pragma once

#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>

#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/render/view.hpp"

namespace mpm_sdem::render {

struct RenderDef {
  int width = 800;   // px; the height follows the domain's aspect ratio
  ColorScale scale;  // chooseScale: fixed for the run
};

// Draws the world into image (CV_8UC3, BGR), reallocated only when its size changes. The
// overlays (time, scale bar, colour bar, block names) are left out below 320 px, where they
// would cover the picture.
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
