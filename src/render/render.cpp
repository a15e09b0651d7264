#include "mpm_sdem/render/render.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"

namespace mpm_sdem::render {

namespace {

int fourccFor(const std::string& path) {
  auto ends = [&](const char* s) {
    const std::string e(s);
    return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
  };
  if (ends(".mp4")) return cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  if (ends(".mkv")) return cv::VideoWriter::fourcc('F', 'F', 'V', '1');
  return cv::VideoWriter::fourcc('M', 'J', 'P', 'G');
}

cv::Size imageSize(const World& world, int width) {
  const Vec2 span = world.def().domain.max - world.def().domain.min;
  // Even sizes: some codecs refuse odd ones.
  const int h = 2 * std::max(1, static_cast<int>(std::lround(0.5 * width * span.y() / span.x())));
  return cv::Size(2 * std::max(1, width / 2), h);
}

}  // namespace

void renderWorld(const World& world, const RenderDef& def, cv::Mat& image) {
  const cv::Size size = imageSize(world, def.width);
  image.create(size, CV_8UC3);
  image.setTo(cv::Scalar(32, 32, 32));
  const DomainDef& dom = world.def().domain;
  const double px = size.width / (dom.max.x() - dom.min.x());  // pixels per metre
  auto toPixel = [&](const Vec2& p) {
    return cv::Point(static_cast<int>((p.x() - dom.min.x()) * px),
                     static_cast<int>((dom.max.y() - p.y()) * px));
  };
  const Particles& P = world.particles();
  const std::size_t n = P.size();
  // Value of each point mapped to 0..255 and coloured with OpenCV's turbo map.
  cv::Mat values(1, static_cast<int>(std::max<std::size_t>(n, 1)), CV_8UC1, cv::Scalar(0));
  Real top = def.color_by == ColorBy::kKind ? 1 : def.max_value;
  auto value = [&](std::size_t p) -> Real {
    if (def.color_by == ColorBy::kSpeed) return std::hypot(P.vx[p], P.vy[p]);
    if (def.color_by == ColorBy::kKind) return P.kind[p];
    return -meanStress(Stress{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]});
  };
  if (!(top > 0)) {
    for (std::size_t p = 0; p < n; ++p) top = std::max(top, value(p));
  }
  for (std::size_t p = 0; p < n && top > 0; ++p) {
    values.at<std::uint8_t>(0, static_cast<int>(p)) =
        static_cast<std::uint8_t>(std::clamp(255 * value(p) / top, 0.0, 255.0));
  }
  cv::Mat colours;
  cv::applyColorMap(values, colours, cv::COLORMAP_TURBO);
  // A point covers its share of a cell: h / sqrt(points per cell), at least one pixel.
  int ppc = 1;
  for (const BodyDef& b : world.def().bodies) ppc = std::max(ppc, b.points_per_cell);
  const int radius =
      std::max(1, static_cast<int>(std::lround(0.5 * world.def().cell_size / ppc * px)));
  for (std::size_t p = 0; p < n; ++p) {
    const cv::Vec3b c = colours.at<cv::Vec3b>(0, static_cast<int>(p));
    cv::circle(image, toPixel(Vec2(P.x[p], P.y[p])), radius, cv::Scalar(c[0], c[1], c[2]),
               cv::FILLED);
  }
  if (const Blocks* B = world.blocks()) {
    for (int s = 0; s < B->shapeCount(); ++s) {  // a cluster drawn disc by disc
      const cv::Scalar colour =
          B->movable(s) ? cv::Scalar(90, 170, 230) : cv::Scalar(170, 170, 170);
      const std::vector<Vec2> core(B->coreVertices(s), B->coreVertices(s) + B->coreVertexCount(s));
      std::vector<cv::Point> outline;
      for (const Vec2& p : roundedOutline(core, B->rounding(s), 6)) outline.push_back(toPixel(p));
      cv::fillConvexPoly(image, outline, colour, cv::LINE_AA);
    }
  }
  char label[96];
  if (def.color_by == ColorBy::kKind)
    std::snprintf(label, sizeof(label), "t = %.3f s   colour: material point (blue), SPH (red)",
                  world.time());
  else
    std::snprintf(label, sizeof(label), "t = %.3f s   colour: %s 0 - %.3g %s", world.time(),
                  def.color_by == ColorBy::kSpeed ? "speed" : "pressure", top,
                  def.color_by == ColorBy::kSpeed ? "m/s" : "Pa");
  cv::putText(image, label, cv::Point(8, 20), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

std::string videoPathProblem(const std::string& path) {
  return limits::outputFileProblem(path, {".avi", ".mp4", ".mkv"});
}

VideoRecorder::VideoRecorder(const std::string& path, double fps, const RenderDef& def,
                             const World& world)
    : def_(def), path_(path), frames_due_(fps) {
  if (const std::string problem = videoPathProblem(path); !problem.empty())
    throw std::runtime_error("cannot write the video: " + problem);
  if (!(fps > 0))
    throw std::runtime_error("video frame rate must be > 0, got " + std::to_string(fps));
  if (!writer_.open(path, fourccFor(path), fps, imageSize(world, def.width))) {
    throw std::runtime_error("OpenCV cannot write the video " + path +
                             " (use a .avi, .mp4 or .mkv name in a writable directory)");
  }
}

void VideoRecorder::record(const World& world) {
  if (!writer_.isOpened() || !frames_due_.due(world.time())) return;
  renderWorld(world, def_, frame_);
  writer_.write(frame_);
  ++frames_;
}

void VideoRecorder::close() {
  writer_.release();
}

}  // namespace mpm_sdem::render
