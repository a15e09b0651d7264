// What makes a picture readable on its own: the time, a scale bar, the colour bar and the names
// of blocks and FEM bodies. Everything is sized in proportion to the image width (text of about
// 11 px at 800 px) and drawn white with a dark outline, so that it reads over material, bodies
// and background alike.
// Internal to the render library; its test reads the layout.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "mpm_sdem/render/view.hpp"

namespace mpm_sdem::render::detail {

inline const cv::Scalar kBackground(32, 32, 32);  // BGR
// Below this width the overlays would cover most of the picture: renderWorld leaves them out.
inline constexpr int kMinOverlayWidth = 320;  // px

// The colour map, index 0 (bottom of the scale, blue) to 255 (top, red): OpenCV's turbo without
// its darkest ends; one table for the points and the colour bar, so that the bar shows exactly
// the points' colours.
const cv::Mat& colourMap();  // 1 x 256, CV_8UC3 (BGR)
// The index of value on a scale topped by max_value (> 0); at or below 0: 0, at or above: 255.
int colourIndex(Real value, Real max_value);

// From the domain (m, y up) to pixels (y down), the domain's top-left corner at (0, 0).
struct PixelFrame {
  Vec2 top_left;   // m
  Real per_metre;  // px/m
  cv::Point operator()(const Vec2& p) const {
    return cv::Point(static_cast<int>((p.x() - top_left.x()) * per_metre),
                     static_cast<int>((top_left.y() - p.y()) * per_metre));
  }
};

// Where the overlays go in an image of this size (px).
struct Layout {
  double font = 0.5;  // cv::FONT_HERSHEY_SIMPLEX scale
  int thickness = 1;  // of text and lines
  int margin = 8;     // from the image's edges and between items
  int text_height = 11;
  cv::Rect time_label;    // top left
  cv::Rect scale_bar;     // under the time: the bar and its end ticks, without its label
  Real scale_length = 0;  // m, a round length of 1/10 to 1/4 of the domain's width
  cv::Rect color_bar;     // top right: the gradient (or the kinds' two swatches) alone
};
Layout layoutFor(const cv::Size& image, const PixelFrame& frame);

void drawTime(cv::Mat& image, const Layout& layout, Real time);
void drawScaleBar(cv::Mat& image, const Layout& layout);
void drawColorBar(cv::Mat& image, const Layout& layout, const ColorScale& scale);
// A body's name and where to write it (m): a block's centre of mass, an FEM body's mean node.
struct NameTag {
  std::string name;
  Vec2 at;
};
// Each name centred on its place, kept inside the image.
void drawNames(cv::Mat& image, const Layout& layout, const std::vector<NameTag>& names,
               const PixelFrame& frame);

}  // namespace mpm_sdem::render::detail
