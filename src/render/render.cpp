#include "mpm_sdem/render/render.hpp"

#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "mpm_sdem/core/limits.hpp"
#include "mpm_sdem/core/mpm/constitutive.hpp"
#include "overlays.hpp"

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
  const ColorScale& scale = def.scale;
  if (!(scale.max_value > 0))
    throw std::invalid_argument("renderWorld: the colour scale's top must be > 0 (chooseScale)");
  const cv::Size size = imageSize(world, def.width);
  image.create(size, CV_8UC3);
  image.setTo(detail::kBackground);
  const DomainDef& dom = world.def().domain;
  const detail::PixelFrame frame{Vec2(dom.min.x(), dom.max.y()),
                                 size.width / (dom.max.x() - dom.min.x())};
  const Particles& P = world.particles();
  auto value = [&](std::size_t p) -> Real {
    if (scale.color_by == ColorBy::kSpeed) return std::hypot(P.vx[p], P.vy[p]);
    if (scale.color_by == ColorBy::kKind) return P.kind[p];
    return pressure(Stress{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]});
  };
  // A point covers its share of a cell: h / sqrt(points per cell), at least one pixel.
  int ppc = 1;
  for (const BodyDef& b : world.def().bodies) ppc = std::max(ppc, b.points_per_cell);
  const int radius = std::max(
      1, static_cast<int>(std::lround(0.5 * world.def().cell_size / ppc * frame.per_metre)));
  const cv::Mat& map = detail::colourMap();
  for (std::size_t p = 0; p < P.size(); ++p) {
    const cv::Vec3b c = map.at<cv::Vec3b>(0, detail::colourIndex(value(p), scale.max_value));
    cv::circle(image, frame(Vec2(P.x[p], P.y[p])), radius, cv::Scalar(c), cv::FILLED);
  }
  std::vector<detail::NameTag> names;
  if (const FemBodies* fem = world.femBodies()) {
    for (int e = 0; e < fem->totalElements(); ++e) {
      const std::array<int, 3>& n = fem->elementNodes(e);
      const cv::Point corners[3] = {frame(fem->position(n[0])), frame(fem->position(n[1])),
                                    frame(fem->position(n[2]))};
      cv::fillConvexPoly(image, corners, 3, cv::Scalar(150, 190, 150), cv::LINE_AA);
    }
    for (int b = 0; b < fem->count(); ++b) {
      Vec2 sum(0, 0);
      for (int k = 0; k < fem->nodeCount(b); ++k) sum += fem->position(fem->firstNode(b) + k);
      names.push_back({fem->def(b).name, sum / std::max(1, fem->nodeCount(b))});
    }
  }
  if (const Blocks* blocks = world.blocks()) {
    for (int s = 0; s < blocks->shapeCount(); ++s) {  // a cluster drawn disc by disc
      const cv::Scalar colour =
          blocks->movable(s) ? cv::Scalar(90, 170, 230) : cv::Scalar(170, 170, 170);
      const std::vector<Vec2> core(blocks->coreVertices(s),
                                   blocks->coreVertices(s) + blocks->coreVertexCount(s));
      std::vector<cv::Point> outline;
      for (const Vec2& p : roundedOutline(core, blocks->rounding(s), 6))
        outline.push_back(frame(p));
      cv::fillConvexPoly(image, outline, colour, cv::LINE_AA);
    }
    for (int b = 0; b < blocks->count(); ++b)
      names.push_back({blocks->def(b).name, blocks->state(b).position});
  }
  if (size.width < detail::kMinOverlayWidth) return;
  const detail::Layout layout = detail::layoutFor(size, frame);
  detail::drawNames(image, layout, names, frame);
  detail::drawScaleBar(image, layout);
  detail::drawTime(image, layout, world.time());
  detail::drawColorBar(image, layout, scale);
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
  encoder_ = std::thread([this] { encode(); });
}

VideoRecorder::~VideoRecorder() {
  close();
}

void VideoRecorder::record(const World& world) {
  if (!encoder_.joinable() || !frames_due_.due(world.time())) return;
  renderWorld(world, def_, frame_);
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return queue_.size() < kQueued || !failure_.empty(); });
  // The codec's error reaches the caller, as it did when frames were encoded here.
  if (!failure_.empty()) throw std::runtime_error("video " + path_ + ": " + failure_);
  queue_.push_back(frame_.clone());
  changed_.notify_all();
  ++frames_;
}

void VideoRecorder::encode() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return closing_ || !queue_.empty(); });
    if (queue_.empty()) return;  // closing, and every frame written
    const cv::Mat frame = std::move(queue_.front());
    queue_.pop_front();
    changed_.notify_all();
    lock.unlock();
    try {
      writer_.write(frame);
    } catch (const std::exception& e) {  // not past the thread (std::terminate, no bag closed)
      lock.lock();
      failure_ = e.what();
      queue_.clear();
      changed_.notify_all();
      return;
    }
    lock.lock();
  }
}

void VideoRecorder::close() {
  if (encoder_.joinable()) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      closing_ = true;
    }
    changed_.notify_all();
    encoder_.join();
  }
  writer_.release();
}

}  // namespace mpm_sdem::render
