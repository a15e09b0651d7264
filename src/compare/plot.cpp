#include "plot.hpp"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace mpm_sdem::compare {

namespace {

struct Series {
  const std::vector<double>* x;
  const std::vector<double>* y;
  cv::Scalar colour;
  std::string label;
};

const cv::Scalar kPalette[] = {{200, 80, 30},  {30, 120, 230}, {40, 160, 40},
                               {160, 40, 160}, {30, 30, 200},  {120, 120, 0}};

std::string fmt(double v) {
  char s[32];
  std::snprintf(s, sizeof(s), "%.3g", v);
  return s;
}

// One panel: axes with their ranges printed at the ends, a polyline per series, a legend.
void panel(cv::Mat& img, const cv::Rect& area, const std::string& title,
           const std::vector<Series>& series) {
  const cv::Rect box(area.x + 70, area.y + 25, area.width - 90, area.height - 55);
  double x0 = 1e300, x1 = -1e300, y0 = 1e300, y1 = -1e300;
  for (const Series& s : series) {
    for (std::size_t k = 0; k < s.x->size(); ++k) {
      if (!std::isfinite((*s.y)[k])) continue;
      x0 = std::min(x0, (*s.x)[k]);
      x1 = std::max(x1, (*s.x)[k]);
      y0 = std::min(y0, (*s.y)[k]);
      y1 = std::max(y1, (*s.y)[k]);
    }
  }
  if (x0 > x1) x0 = 0, x1 = 1, y0 = 0, y1 = 1;
  if (y1 - y0 < 1e-12 * std::max(1.0, std::abs(y1))) y0 -= 0.5, y1 += 0.5;
  if (x1 <= x0) x1 = x0 + 1;
  const cv::Scalar ink(40, 40, 40);
  cv::rectangle(img, box, ink, 1);
  cv::putText(img, title, cv::Point(box.x, area.y + 18), cv::FONT_HERSHEY_SIMPLEX, 0.5, ink, 1,
              cv::LINE_AA);
  auto text = [&](const std::string& s, cv::Point p) {
    cv::putText(img, s, p, cv::FONT_HERSHEY_SIMPLEX, 0.4, ink, 1, cv::LINE_AA);
  };
  text(fmt(y1), cv::Point(area.x + 2, box.y + 10));
  text(fmt(y0), cv::Point(area.x + 2, box.y + box.height));
  text(fmt(x0) + " s", cv::Point(box.x, box.y + box.height + 16));
  text(fmt(x1) + " s", cv::Point(box.x + box.width - 50, box.y + box.height + 16));
  auto px = [&](double x, double y) {
    return cv::Point(box.x + static_cast<int>((x - x0) / (x1 - x0) * box.width),
                     box.y + box.height - static_cast<int>((y - y0) / (y1 - y0) * box.height));
  };
  int legend_y = box.y + 14;
  for (const Series& s : series) {
    std::vector<cv::Point> pts;
    for (std::size_t k = 0; k < s.x->size(); ++k)
      if (std::isfinite((*s.y)[k])) pts.push_back(px((*s.x)[k], (*s.y)[k]));
    if (pts.size() > 1) cv::polylines(img, pts, false, s.colour, 1, cv::LINE_AA);
    cv::putText(img, s.label, cv::Point(box.x + box.width - 220, legend_y),
                cv::FONT_HERSHEY_SIMPLEX, 0.4, s.colour, 1, cv::LINE_AA);
    legend_y += 14;
  }
}

}  // namespace

void plotComparison(const Comparison& c, const std::string& label_a, const std::string& label_b,
                    const std::string& png_path) {
  const int w = 900, h = 260;
  cv::Mat img(3 * h, w, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<Series> blocks;
  for (std::size_t i = 0; i < c.blocks.size(); ++i) {
    blocks.push_back({&c.blocks[i].time, &c.blocks[i].position, kPalette[i % 6], c.blocks[i].name});
  }
  panel(img, cv::Rect(0, 0, w, h), "block position error |p_a - p_b| (m)", blocks);
  panel(img, cv::Rect(0, h, w, h), "particle cloud: symmetric mean nearest-neighbour distance (m)",
        {{&c.clouds.time, &c.clouds.distance, kPalette[0], "distance"}});
  panel(img, cv::Rect(0, 2 * h, w, h), "total energy (J/m)",
        {{&c.energy.time, &c.energy.total_a, kPalette[0], "a: " + label_a},
         {&c.energy.time, &c.energy.total_b, kPalette[1], "b: " + label_b}});
  if (!cv::imwrite(png_path, img)) throw std::runtime_error("cannot write " + png_path);
}

}  // namespace mpm_sdem::compare
