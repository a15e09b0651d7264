#include "overlays.hpp"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace mpm_sdem::render::detail {

namespace {

constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kText(255, 255, 255);
const cv::Scalar kOutline(0, 0, 0);

// The largest 1, 2 or 5 times a power of ten not above v.
Real roundDown125(Real v) {
  const Real decade = std::pow(10.0, std::floor(std::log10(v)));
  for (const Real m : {5.0, 2.0, 1.0}) {
    if (m * decade <= v * (1 + 1e-12)) return m * decade;
  }
  return decade;
}

// The smallest 1, 2 or 5 times a power of ten not below v.
Real roundUp125(Real v) {
  const Real decade = std::pow(10.0, std::floor(std::log10(v)));
  for (const Real m : {1.0, 2.0, 5.0}) {
    if (m * decade >= v * (1 - 1e-12)) return m * decade;
  }
  return 10 * decade;
}

cv::Size textSize(const std::string& text, const Layout& l, double scale = 1) {
  int baseline = 0;
  return cv::getTextSize(text, kFont, l.font * scale, l.thickness, &baseline);
}

// White text with a dark outline; org is the left end of the baseline.
void label(cv::Mat& image, const std::string& text, cv::Point org, const Layout& l,
           double scale = 1) {
  cv::putText(image, text, org, kFont, l.font * scale, kOutline, l.thickness + 2, cv::LINE_AA);
  cv::putText(image, text, org, kFont, l.font * scale, kText, l.thickness, cv::LINE_AA);
}

// A label centred on x, its baseline at y.
void centred(cv::Mat& image, const std::string& text, int x, int y, const Layout& l,
             double scale = 1) {
  label(image, text, cv::Point(x - textSize(text, l, scale).width / 2, y), l, scale);
}

// Darkens a panel behind overlays: they stay readable over bright material, and the picture
// still shows through.
void darken(cv::Mat& image, cv::Rect r) {
  r &= cv::Rect(0, 0, image.cols, image.rows);
  if (r.area() > 0) image(r).convertTo(image(r), -1, 0.35);
}

std::string lengthText(Real metres) {
  char text[32];
  if (metres >= 1000)
    std::snprintf(text, sizeof(text), "%g km", metres / 1000);
  else if (metres >= 0.1)
    std::snprintf(text, sizeof(text), "%g m", metres);
  else if (metres >= 0.01)
    std::snprintf(text, sizeof(text), "%g cm", metres * 100);
  else
    std::snprintf(text, sizeof(text), "%g mm", metres * 1000);
  return text;
}

// The unit the colour bar's numbers are written in, for short tick labels of at most three
// digits: kPa rather than "4000" Pa, mm/s rather than "0.005" m/s.
struct DisplayUnit {
  Real factor;
  const char* name;
};
DisplayUnit displayUnit(const ColorScale& s) {
  if (s.color_by == ColorBy::kSpeed)
    return s.max_value < 0.1 ? DisplayUnit{1e3, "mm/s"} : DisplayUnit{1, "m/s"};
  if (s.max_value >= 1e9) return {1e-9, "GPa"};
  if (s.max_value >= 1e6) return {1e-6, "MPa"};
  if (s.max_value >= 1e3) return {1e-3, "kPa"};
  return {1, "Pa"};
}

}  // namespace

const cv::Mat& colourMap() {
  // Turbo's own ends are nearly black (a dark purple, a dark red) and vanish on the dark
  // background: material at rest could not be seen. Its span 24..232 goes from a clear blue to
  // a clear red.
  static const cv::Mat map = [] {
    cv::Mat ramp(1, 256, CV_8UC1), colours;
    for (int i = 0; i < 256; ++i)
      ramp.at<std::uint8_t>(0, i) = static_cast<std::uint8_t>(24 + i * 208 / 255);
    cv::applyColorMap(ramp, colours, cv::COLORMAP_TURBO);
    return colours;
  }();
  return map;
}

int colourIndex(Real value, Real max_value) {
  // Truncated, not rounded: only values at the top reach 255, and 1 mm/s on a 2 m/s scale is
  // the bottom colour, as at rest. NaN (a state about to be refused) at the bottom too.
  if (!(value > 0)) return 0;
  return static_cast<int>(std::min(255 * value / max_value, Real(255)));
}

Layout layoutFor(const cv::Size& image, const PixelFrame& frame) {
  Layout l;
  const double s = image.width / 800.0;
  // Not below 0.38 (text about 8 px high), the smallest that still reads; narrower pictures
  // give the overlays a larger share of their width instead.
  l.font = std::max(0.38, 0.5 * s);
  l.thickness = std::max(1, static_cast<int>(std::lround(s)));
  l.margin = std::max(4, static_cast<int>(std::lround(8 * s)));
  l.text_height = textSize("0123456789", l).height;
  l.time_label = cv::Rect(l.margin, l.margin, textSize("t = 0.000 s", l).width, l.text_height);
  const Real width_m = image.width / frame.per_metre;
  l.scale_length = roundDown125(width_m / 4);
  l.scale_bar =
      cv::Rect(l.margin, l.time_label.br().y + l.margin,
               std::max(1, static_cast<int>(std::lround(l.scale_length * frame.per_metre))),
               std::max(4, static_cast<int>(std::lround(8 * s))));
  const int bar_width = static_cast<int>(std::lround(std::max(150.0, 200 * s)));
  const int bar_height = std::max(4, static_cast<int>(std::lround(10 * s)));
  // Room right of the bar for half of its last label, which is centred on the bar's end.
  const int x = image.width - l.margin - bar_width - static_cast<int>(std::lround(16 * s));
  l.color_bar = cv::Rect(x, l.margin + l.text_height + l.margin / 2 + 2, bar_width, bar_height);
  return l;
}

void drawTime(cv::Mat& image, const Layout& l, Real time) {
  char text[48];
  std::snprintf(text, sizeof(text), "t = %.3f s", time);
  label(image, text, cv::Point(l.time_label.x, l.time_label.br().y), l);
}

void drawScaleBar(cv::Mat& image, const Layout& l) {
  const std::string text = lengthText(l.scale_length);
  const cv::Rect& r = l.scale_bar;
  const int text_right = r.br().x + l.margin / 2 + textSize(text, l).width;
  darken(image, cv::Rect(cv::Point(l.margin / 2, l.margin / 2),
                         cv::Point(std::max(text_right, l.time_label.br().x) + l.margin / 2,
                                   r.br().y + l.margin / 2)));
  const int mid = r.y + r.height / 2;
  const int bar = std::max(2, r.height / 3);
  cv::rectangle(image, cv::Rect(r.x, mid - bar / 2, r.width, bar), kText, cv::FILLED);
  cv::line(image, cv::Point(r.x, r.y), cv::Point(r.x, r.br().y - 1), kText, l.thickness);
  cv::line(image, cv::Point(r.br().x - 1, r.y), cv::Point(r.br().x - 1, r.br().y - 1), kText,
           l.thickness);
  label(image, text, cv::Point(r.br().x + l.margin / 2, mid + l.text_height / 2), l);
}

void drawColorBar(cv::Mat& image, const Layout& l, const ColorScale& scale) {
  const cv::Rect& r = l.color_bar;
  const int tick = std::max(2, r.height / 2);
  const int labels_y = r.br().y + tick + l.text_height + 2;  // baseline of the tick labels
  darken(image, cv::Rect(cv::Point(r.x - l.margin - l.text_height, l.margin / 2),
                         cv::Point(image.cols - l.margin / 2, labels_y + l.margin / 2 + 2)));
  const cv::Mat& map = colourMap();
  if (scale.color_by == ColorBy::kKind) {
    const cv::Rect left(r.x, r.y, r.width / 2, r.height),
        right(left.br().x, r.y, r.width / 2, r.height);
    cv::rectangle(image, left, cv::Scalar(map.at<cv::Vec3b>(0, 0)), cv::FILLED);
    cv::rectangle(image, right, cv::Scalar(map.at<cv::Vec3b>(0, 255)), cv::FILLED);
    label(image, "kind", cv::Point(r.x, r.y - l.margin / 2 - 2), l);
    centred(image, "material point", left.x + left.width / 2, labels_y, l, 0.85);
    centred(image, "SPH particle", right.x + right.width / 2, labels_y, l, 0.85);
    return;
  }
  for (int x = 0; x < r.width; ++x) {
    const int index = x * 255 / std::max(1, r.width - 1);
    cv::line(image, cv::Point(r.x + x, r.y), cv::Point(r.x + x, r.br().y - 1),
             cv::Scalar(map.at<cv::Vec3b>(0, index)));
  }
  const DisplayUnit unit = displayUnit(scale);
  label(image, std::string(colorByName(scale.color_by)) + " [" + unit.name + "]",
        cv::Point(r.x, r.y - l.margin / 2 - 2), l);
  // Ticks at round steps, 2 to 5 intervals, and one at the top; a round tick closer than 0.6
  // of a step to the top is left out, or their labels would overlap.
  const Real top = scale.max_value * unit.factor;
  const Real step = roundUp125(top / 5);
  std::vector<Real> ticks;
  for (int k = 0; k * step < top - 0.6 * step; ++k) ticks.push_back(k * step);
  ticks.push_back(top);
  // Every tick marked; a label that would touch its left neighbour's or the top's is left out
  // (long numbers on a narrow bar), the top's always kept.
  auto text = [](Real v) {
    char t[32];
    std::snprintf(t, sizeof(t), "%g", v);
    return std::string(t);
  };
  const double size = 0.9;
  const int gap = l.margin / 2;
  auto at = [&](Real v) { return r.x + static_cast<int>(std::lround(v / top * (r.width - 1))); };
  const int top_left = at(top) - textSize(text(top), l, size).width / 2;
  int free_from = r.x - l.margin;
  for (const Real v : ticks) {
    const int x = at(v);
    cv::line(image, cv::Point(x, r.br().y), cv::Point(x, r.br().y + tick), kText, l.thickness);
    const int half = textSize(text(v), l, size).width / 2;
    const bool last = v == ticks.back();
    if (!last && (x - half < free_from || x + half + gap > top_left)) continue;
    centred(image, text(v), x, labels_y, l, size);
    free_from = x + half + gap;
  }
}

void drawNames(cv::Mat& image, const Layout& l, const std::vector<NameTag>& names,
               const PixelFrame& frame) {
  const double scale = 0.85;
  for (const NameTag& tag : names) {
    const cv::Size size = textSize(tag.name, l, scale);
    const cv::Point c = frame(tag.at);
    const int x = std::clamp(c.x - size.width / 2, 0, std::max(0, image.cols - size.width));
    const int y = std::clamp(c.y + size.height / 2, size.height, image.rows - 1);
    label(image, tag.name, cv::Point(x, y), l, scale);
  }
}

}  // namespace mpm_sdem::render::detail
