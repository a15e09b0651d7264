// Pictures of a world with OpenCV: material points coloured by speed, pressure or kind on a
// fixed scale, blocks drawn with their rounding and named, a colour bar, a scale bar and the time.
// Used for the node's ~image topic and for videos. Not part of the core.
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <opencv2/videoio.hpp>
#include <string>
#include <vector>

#include "mpm_sdem/core/bounded_worker.hpp"
#include "mpm_sdem/core/problem.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/core/world.hpp"
#include "mpm_sdem/render/view.hpp"

namespace mpm_sdem::render {

struct RenderDef {
  int width = 800;   // px; the height follows the domain's aspect ratio
  ColorScale scale;  // chooseScale: fixed for the run
};

// What a picture shows, read from the world and already in pixels (y down, the domain's top
// left at 0, 0): taking it is a copy of the points' places and colours, cheap enough for the
// simulation's thread; drawing it needs no world, so a recorder draws on a thread of its own.
struct Snapshot {
  cv::Size size;                                 // px
  Real time = 0;                                 // s
  Vec2 top_left{0, 0};                           // m: where pixel (0, 0) is
  Real per_metre = 1;                            // px/m
  int radius = 1;                                // px, of a material point's disk
  std::vector<cv::Point> points;                 // material points
  std::vector<std::uint8_t> colours;             // their colour map indices (0-255)
  std::vector<cv::Point> triangles;              // FEM elements, three corners each
  std::vector<std::vector<cv::Point>> outlines;  // block shapes, rounding included
  std::vector<bool> movable;                     // per outline: dynamic or kinematic (else grey)
  std::vector<std::string> names;                // blocks' and FEM bodies' names
  std::vector<Vec2> name_at;                     // where to write them (m)
};
// Fills snapshot (its vectors reused) with what def draws of world now.
void takeSnapshot(const World& world, const RenderDef& def, Snapshot& snapshot);
// Draws a snapshot into image (CV_8UC3, BGR), reallocated only when its size changes. The
// overlays (time, scale bar, colour bar, names) are left out below 320 px, where they would
// cover the picture.
void drawSnapshot(const Snapshot& snapshot, const RenderDef& def, cv::Mat& image);
// Both at once.
void renderWorld(const World& world, const RenderDef& def, cv::Mat& image);

// "" or why a video cannot be written there (limits::outputFileProblem: .avi, .mp4 or .mkv).
Problem videoPathProblem(const std::string& path);

// Writes frames every 1/fps s of simulation time, played back at fps: the video runs in
// simulation time. The container follows the file name (.avi: MJPG, .mp4: mp4v, .mkv: FFV1).
// The caller's thread takes a snapshot (it reads the world); a thread of the recorder's own
// draws and encodes it, as rosbag record writes on its own thread: the simulation waits for
// neither the drawing nor the codec. At most kQueued frames wait; a full queue makes record()
// wait, so no frame is dropped.
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
  cv::VideoWriter writer_;
  RenderDef def_;
  std::string path_;
  SampleClock frames_due_;
  int frames_ = 0;
  bool open_ = false;
  cv::Mat frame_;  // the encoder's
  // Draws and encodes the snapshots taken; last: stopped before the writer is released.
  std::unique_ptr<BoundedWorker<Snapshot>> encoder_;
};

}  // namespace mpm_sdem::render
