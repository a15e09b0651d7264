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

void takeSnapshot(const World& world, const RenderDef& def, Snapshot& snap) {
  const ColorScale& scale = def.scale;
  if (!(scale.max_value > 0))
    throw std::invalid_argument("renderWorld: the colour scale's top must be > 0 (chooseScale)");
  snap.size = imageSize(world, def.width);
  snap.time = world.time();
  const DomainDef& dom = world.def().domain;
  snap.top_left = Vec2(dom.min.x(), dom.max.y());
  snap.per_metre = snap.size.width / (dom.max.x() - dom.min.x());
  const detail::PixelFrame frame{snap.top_left, snap.per_metre};
  const Particles& P = world.particles();
  auto value = [&](std::size_t p) -> Real {
    if (scale.color_by == ColorBy::kSpeed) return std::hypot(P.vx[p], P.vy[p]);
    if (scale.color_by == ColorBy::kKind) return P.kind[p];
    return pressure(Stress{P.sxx[p], P.syy[p], P.sxy[p], P.szz[p]});
  };
  // A point covers its share of a cell: h / sqrt(points per cell), at least one pixel.
  int ppc = 1;
  for (const BodyDef& b : world.def().bodies) ppc = std::max(ppc, b.points_per_cell);
  snap.radius = std::max(
      1, static_cast<int>(std::lround(0.5 * world.def().cell_size / ppc * frame.per_metre)));
  snap.points.resize(P.size());
  snap.colours.resize(P.size());
  for (std::size_t p = 0; p < P.size(); ++p) {
    snap.points[p] = frame(Vec2(P.x[p], P.y[p]));
    snap.colours[p] = static_cast<std::uint8_t>(detail::colourIndex(value(p), scale.max_value));
  }
  snap.triangles.clear();
  snap.outlines.clear();
  snap.movable.clear();
  snap.names.clear();
  snap.name_at.clear();
  if (const FemBodies* fem = world.femBodies()) {
    for (int e = 0; e < fem->totalElements(); ++e)
      for (const int n : fem->elementNodes(e)) snap.triangles.push_back(frame(fem->position(n)));
    for (int b = 0; b < fem->count(); ++b) {
      Vec2 sum(0, 0);
      for (int k = 0; k < fem->nodeCount(b); ++k) sum += fem->position(fem->firstNode(b) + k);
      snap.names.push_back(fem->def(b).name);
      snap.name_at.push_back(sum / std::max(1, fem->nodeCount(b)));
    }
  }
  if (const Blocks* blocks = world.blocks()) {
    for (int s = 0; s < blocks->shapeCount(); ++s) {  // a cluster drawn disc by disc
      const std::vector<Vec2> core(blocks->coreVertices(s),
                                   blocks->coreVertices(s) + blocks->coreVertexCount(s));
      std::vector<cv::Point>& outline = snap.outlines.emplace_back();
      for (const Vec2& p : roundedOutline(core, blocks->rounding(s), 6))
        outline.push_back(frame(p));
      snap.movable.push_back(blocks->movable(s));
    }
    for (int b = 0; b < blocks->count(); ++b) {
      snap.names.push_back(blocks->def(b).name);
      snap.name_at.push_back(blocks->state(b).position);
    }
  }
}

void drawSnapshot(const Snapshot& snap, const RenderDef& def, cv::Mat& image) {
  image.create(snap.size, CV_8UC3);
  image.setTo(detail::kBackground);
  const cv::Mat& map = detail::colourMap();
  for (std::size_t p = 0; p < snap.points.size(); ++p)
    cv::circle(image, snap.points[p], snap.radius,
               cv::Scalar(map.at<cv::Vec3b>(0, snap.colours[p])), cv::FILLED);
  for (std::size_t t = 0; t + 2 < snap.triangles.size(); t += 3)
    cv::fillConvexPoly(image, &snap.triangles[t], 3, cv::Scalar(150, 190, 150), cv::LINE_AA);
  for (std::size_t s = 0; s < snap.outlines.size(); ++s) {
    const cv::Scalar colour =
        snap.movable[s] ? cv::Scalar(90, 170, 230) : cv::Scalar(170, 170, 170);
    cv::fillConvexPoly(image, snap.outlines[s], colour, cv::LINE_AA);
  }
  if (snap.size.width < detail::kMinOverlayWidth) return;
  const detail::PixelFrame frame{snap.top_left, snap.per_metre};
  std::vector<detail::NameTag> names;
  for (std::size_t k = 0; k < snap.names.size(); ++k)
    names.push_back({snap.names[k], snap.name_at[k]});
  const detail::Layout layout = detail::layoutFor(snap.size, frame);
  detail::drawNames(image, layout, names, frame);
  detail::drawScaleBar(image, layout);
  detail::drawTime(image, layout, snap.time);
  detail::drawColorBar(image, layout, def.scale);
}

void renderWorld(const World& world, const RenderDef& def, cv::Mat& image) {
  Snapshot snap;
  takeSnapshot(world, def, snap);
  drawSnapshot(snap, def, image);
}

Problem videoPathProblem(const std::string& path) {
  return limits::outputFileProblem(path, {".avi", ".mp4", ".mkv"});
}

VideoRecorder::VideoRecorder(const std::string& path, double fps, const RenderDef& def,
                             const World& world)
    : def_(def), path_(path), frames_due_(fps) {
  if (const Problem problem = videoPathProblem(path); !problem.empty())
    throw std::runtime_error("cannot write the video: " + problem.message);
  if (!(fps > 0))
    throw std::runtime_error("video frame rate must be > 0, got " + std::to_string(fps));
  if (!writer_.open(path, fourccFor(path), fps, imageSize(world, def.width))) {
    throw std::runtime_error("OpenCV cannot write the video " + path +
                             " (use a .avi, .mp4 or .mkv name in a writable directory)");
  }
  encoder_ = std::make_unique<BoundedWorker<Snapshot>>(kQueued, [this](Snapshot& snap) {
    drawSnapshot(snap, def_, frame_);
    writer_.write(frame_);
  });
  open_ = true;
}

VideoRecorder::~VideoRecorder() {
  close();
}

void VideoRecorder::record(const World& world) {
  if (!open_ || !frames_due_.due(world.time())) return;
  Snapshot snap;
  takeSnapshot(world, def_, snap);
  // The codec's error reaches the caller, as it did when frames were encoded here.
  if (!encoder_->push(std::move(snap)))
    throw std::runtime_error("video " + path_ + ": " + encoder_->failure());
  ++frames_;
}

void VideoRecorder::close() {
  if (!open_) return;
  open_ = false;
  encoder_->finish();  // the frames still queued are encoded first
  writer_.release();
}

}  // namespace mpm_sdem::render
