// Pictures of a world with OpenCV: material points coloured by speed, pressure or kind on a
// fixed scale, blocks drawn with their rounding and named, a colour bar, a scale bar and the time.
// Used for the node's ~image topic and for videos. Not part of the core.
#pragma once

#include <condition_variable>
#include <deque>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <thread>

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
// Frames are drawn on the caller's thread (they read the world) and encoded on a thread of the
// recorder's own, as rosbag record writes on its own thread: the simulation does not wait for the
// codec. At most kQueued frames wait; a full queue makes record() wait, so no frame is dropped.
class VideoRecorder {
 public:
  // Throws std::runtime_error when OpenCV cannot open a writer for path.
  VideoRecorder(const std::string& path, double fps, const RenderDef& def, const World& world);
  ~VideoRecorder();
  VideoRecorder(const VideoRecorder&) = delete;
  VideoRecorder& operator=(const VideoRecorder&) = delete;
  // Adds a frame if one is due at the world's current time. Throws std::runtime_error when the
  // codec failed on an earlier frame.
  void record(const World& world);
  // Encodes the frames still queued and closes the file; idempotent.
  void close();
  int frames() const { return frames_; }
  const std::string& path() const { return path_; }

  static constexpr std::size_t kQueued = 4;

 private:
  void encode();  // the encoder thread

  cv::VideoWriter writer_;
  RenderDef def_;
  std::string path_;
  SampleClock frames_due_;
  int frames_ = 0;
  cv::Mat frame_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<cv::Mat> queue_;  // drawn, not yet encoded
  bool closing_ = false;
  std::string failure_;  // the codec's error; no frame is encoded after it
  std::thread encoder_;  // last: started once the rest is in place
};

}  // namespace mpm_sdem::render
