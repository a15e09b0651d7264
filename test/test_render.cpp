// Pictures of a world (issue 20): the colour scale is fixed, so material creeping at 1 mm/s is
// drawn in the scale's bottom colour, not red as when every frame was scaled to its own fastest
// point; the colour bar shows exactly the points' colours; the colour bar, the scale bar and the
// block names are drawn where the layout puts them; the scale is chosen parameter first, then
// scene, then the scene's default.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include <filesystem>
#include <set>

#include "helpers.hpp"
#include "mpm_sdem/core/sample_clock.hpp"
#include "mpm_sdem/render/render.hpp"
#include "mpm_sdem/scene/scene.hpp"
#include "overlays.hpp"

using namespace mpm_sdem;
using namespace mpm_sdem::render;
namespace overlay = mpm_sdem::render::detail;

namespace {

// 0.4 m x 0.2 m: 800 x 400 px at the default width, 2000 px/m. A 10 cm x 5 cm body of material
// moving at `speed` in the lower left, a static box named "plate" in the lower right.
WorldDef smallWorld(Real speed) {
  WorldDef def = test::box(Vec2(0, 0), Vec2(0.4, 0.2), 0.01);
  def.materials.push_back(test::elastic(1000, 1e5, 0.3));
  def.bodies.push_back(test::rectangle(Vec2(0.05, 0.0), Vec2(0.15, 0.05), 2));
  def.bodies.back().velocity = Vec2(speed, 0);
  def.blocks.push_back(
      cases::boxBlock("plate", Vec2(0.3, 0.03), 0.06, 0.04, 0.002, BodyType::kStatic, 500));
  return def;
}

cv::Vec3b bottomColour() {
  return overlay::colourMap().at<cv::Vec3b>(0, 0);
}
cv::Vec3b topColour() {
  return overlay::colourMap().at<cv::Vec3b>(0, 255);
}

struct Picture {
  cv::Mat image;
  overlay::PixelFrame frame;
  overlay::Layout layout;
};

Picture draw(const World& world, const ColorScale& scale) {
  Picture p;
  RenderDef def;
  def.scale = scale;
  renderWorld(world, def, p.image);
  const DomainDef& dom = world.def().domain;
  p.frame = {Vec2(dom.min.x(), dom.max.y()), p.image.cols / (dom.max.x() - dom.min.x())};
  p.layout = overlay::layoutFor(p.image.size(), p.frame);
  return p;
}

ColorScale speedUpTo(Real max_value) {
  ViewRequest parameter;
  parameter.color_by = ColorBy::kSpeed;
  parameter.max_value = max_value;
  return chooseScale(parameter, {}, WorldDef{});
}

cv::Vec3b pixel(const cv::Mat& image, const cv::Point& p) {
  return image.at<cv::Vec3b>(p.y, p.x);
}

// Text is white, anti-aliased: its strokes' cores at least this bright in every channel.
int countBright(const cv::Mat& image, const cv::Rect& r) {
  int n = 0;
  for (int y = r.y; y < r.br().y; ++y)
    for (int x = r.x; x < r.br().x; ++x) {
      const cv::Vec3b c = image.at<cv::Vec3b>(y, x);
      n += c[0] > 200 && c[1] > 200 && c[2] > 200;
    }
  return n;
}

int countDifferent(const cv::Mat& image, const cv::Rect& r, const cv::Vec3b& from) {
  int n = 0;
  for (int y = r.y; y < r.br().y; ++y)
    for (int x = r.x; x < r.br().x; ++x) n += image.at<cv::Vec3b>(y, x) != from;
  return n;
}

const cv::Vec3b kBackground(32, 32, 32);

}  // namespace

TEST(Render, CreepingMaterialIsTheBottomColourNotRed) {
  const World world(smallWorld(0.001));  // 1 mm/s: the whole world's fastest motion
  const Picture p = draw(world, speedUpTo(2.0));
  ASSERT_EQ(p.image.size(), cv::Size(800, 400));
  const Particles& P = world.particles();
  ASSERT_GT(P.size(), 0u);
  for (std::size_t i = 0; i < P.size(); i += 7) {
    const cv::Vec3b c = pixel(p.image, p.frame(Vec2(P.x[i], P.y[i])));
    ASSERT_EQ(c, bottomColour()) << "point " << i;
  }
  // The bar's left end shows that colour; turbo's bottom is dark blue, its top red.
  const cv::Rect& bar = p.layout.color_bar;
  EXPECT_EQ(pixel(p.image, cv::Point(bar.x, bar.y + bar.height / 2)), bottomColour());
  const cv::Vec3b c = bottomColour();  // BGR
  EXPECT_GT(c[0], c[2]) << "the bottom colour is red: " << c;
}

TEST(Render, MaterialAtTheTopIsTheBarsTopColour) {
  const World world(smallWorld(2.0));
  const Picture p = draw(world, speedUpTo(2.0));
  const Particles& P = world.particles();
  EXPECT_EQ(pixel(p.image, p.frame(Vec2(P.x[0], P.y[0]))), topColour());
  const cv::Rect& bar = p.layout.color_bar;
  EXPECT_EQ(pixel(p.image, cv::Point(bar.br().x - 1, bar.y + bar.height / 2)), topColour());
  const cv::Vec3b c = topColour();
  EXPECT_GT(c[2], c[0]) << "the top colour is not red: " << c;
}

TEST(Render, ColourBarScaleBarAndNamesAreDrawn) {
  const World world(smallWorld(0.001));
  const Picture p = draw(world, speedUpTo(2.0));
  cv::imwrite((std::filesystem::temp_directory_path() / "mpm_sdem_test_render.png").string(),
              p.image);
  // The colour bar: every pixel coloured, and the whole map across it.
  const cv::Rect& bar = p.layout.color_bar;
  ASSERT_GE(bar.width, 150);
  EXPECT_GE(bar.height, 8);
  EXPECT_TRUE(cv::Rect(0, 0, 800, 400).contains(bar.br() - cv::Point(1, 1)));
  EXPECT_EQ(countDifferent(p.image, bar, kBackground), bar.area());
  std::set<int> colours;
  for (int x = bar.x; x < bar.br().x; ++x) {
    const cv::Vec3b c = pixel(p.image, cv::Point(x, bar.y + bar.height / 2));
    colours.insert(c[0] << 16 | c[1] << 8 | c[2]);
  }
  EXPECT_GE(colours.size(), 150u);
  // Its labels: the title above, the ticks' numbers below (white text).
  const cv::Vec3b white(255, 255, 255);
  const cv::Rect above(bar.x, bar.y - p.layout.text_height - 6, bar.width, p.layout.text_height);
  const cv::Rect below(bar.x - 10, bar.br().y, bar.width + 20, 2 * p.layout.text_height);
  EXPECT_GT(countDifferent(p.image, above, kBackground), 100);
  EXPECT_GT(countBright(p.image, below), 50);
  // The scale bar: a round 1/10 to 1/4 of the 0.4 m width, i.e. 0.1 m = 200 px, drawn white.
  EXPECT_DOUBLE_EQ(p.layout.scale_length, 0.1);
  const cv::Rect& scale = p.layout.scale_bar;
  EXPECT_EQ(scale.width, 200);
  const cv::Rect middle_row(scale.x, scale.y + scale.height / 2, scale.width, 1);
  EXPECT_EQ(countDifferent(p.image, middle_row, white), 0);
  const cv::Rect beside(scale.br().x, scale.y - 4, 60, scale.height + 8);  // "0.1 m"
  EXPECT_GT(countDifferent(p.image, beside, kBackground), 50);
  // The block's name at its centre: white text over the grey block.
  const cv::Point centre = p.frame(Vec2(0.3, 0.03));
  const cv::Rect name(centre.x - 30, centre.y - 10, 60, 20);
  EXPECT_GT(countBright(p.image, name), 20);
  // And nothing where neither material nor an overlay is: the middle of the empty sky.
  const cv::Rect sky(350, 150, 100, 80);
  EXPECT_EQ(countDifferent(p.image, sky, kBackground), 0);
}

TEST(Render, NoOverlaysOnAThumbnail) {
  const World world(smallWorld(0.001));
  RenderDef def;
  def.width = 160;
  def.scale = speedUpTo(2.0);
  cv::Mat image;
  renderWorld(world, def, image);
  const cv::Rect top_right(100, 0, 60, 20);
  EXPECT_EQ(countDifferent(image, top_right, kBackground), 0);
}

// The video's frames are encoded on the recorder's own thread (VideoRecorder): every frame due
// reaches the file, in order, also when the simulation draws them faster than the codec takes
// them (a full queue makes record() wait). 0.03 s at 1000 fps, 1600 px wide: 31 frames a few
// steps apart, drawn faster than FFV1 encodes them, many more than the queue holds. Read back from
// the lossless .mkv (FFV1), the file holds exactly the pictures drawn at those times, in that
// order.
TEST(Video, EveryFrameDueReachesTheFileInOrder) {
  World world(smallWorld(0.5));
  RenderDef def;
  def.width = 1600;
  def.scale = speedUpTo(2.0);
  const std::string path =
      (std::filesystem::temp_directory_path() / "mpm_sdem_test_video.mkv").string();
  std::filesystem::remove(path);
  std::vector<cv::Mat> drawn;
  SampleClock due(1000);
  auto record = [&](VideoRecorder& video) {
    video.record(world);
    if (!due.due(world.time())) return;
    drawn.emplace_back();
    renderWorld(world, def, drawn.back());
  };
  int frames = 0;
  {
    VideoRecorder video(path, 1000, def, world);
    record(video);
    while (world.time() < 0.03 - 1e-9) {
      stepStable(world, 0.03);
      record(video);
    }
    frames = video.frames();
  }  // the destructor encodes what is queued and closes the file
  EXPECT_EQ(frames, 31);
  ASSERT_EQ(drawn.size(), 31u);
  cv::VideoCapture read(path);
  ASSERT_TRUE(read.isOpened());
  cv::Mat image;
  std::size_t k = 0;
  for (; read.read(image); ++k) {
    ASSERT_LT(k, drawn.size());
    ASSERT_EQ(image.size(), drawn[k].size());
    EXPECT_EQ(cv::norm(image, drawn[k], cv::NORM_INF), 0) << "frame " << k;
  }
  EXPECT_EQ(k, drawn.size());
  std::filesystem::remove(path);
}

// Parameter, then scene, then default; a scene's top for speeds never tops pressures.
TEST(View, ParameterThenSceneThenDefault) {
  const Scene scene = loadScene(test::sourcePath("config/scenes/debris_impact.yaml"));
  ASSERT_TRUE(scene.view.color_by && scene.view.max_value);
  EXPECT_EQ(*scene.view.color_by, ColorBy::kSpeed);
  const WorldDef& world = scene.world;
  ViewRequest none;
  EXPECT_EQ(chooseScale(none, scene.view, world).max_value, *scene.view.max_value);
  ViewRequest top;
  top.max_value = 0.5;
  EXPECT_EQ(chooseScale(top, scene.view, world).max_value, 0.5);
  ViewRequest pressure;
  pressure.color_by = ColorBy::kPressure;
  const ColorScale p = chooseScale(pressure, scene.view, world);
  EXPECT_EQ(p.color_by, ColorBy::kPressure);
  // rho g H = 1300 * 9.81 * 0.27 = 3443 Pa, rounded up to 4000.
  EXPECT_EQ(p.max_value, 4000);
  // sqrt(2 g H) = sqrt(2 * 9.81 * 0.27) = 2.30 m/s, rounded up to 2.5.
  EXPECT_EQ(chooseScale(none, none, world).max_value, 2.5);
  EXPECT_EQ(defaultMaxValue(world, ColorBy::kSpeed), 2.5);
  // Without gravity: the fastest initial speed; with nothing moving either, 1 m/s.
  WorldDef still = smallWorld(0.0);
  still.solver.gravity = Vec2(0, 0);
  EXPECT_EQ(defaultMaxValue(still, ColorBy::kSpeed), 1);
  still.bodies[0].velocity = Vec2(3.3, 0);
  EXPECT_EQ(defaultMaxValue(still, ColorBy::kSpeed), 4);
  // rho v^2 = 1000 kg/m^3 (3.3 m/s)^2 = 10.9 kPa, rounded up to 15 kPa.
  EXPECT_EQ(defaultMaxValue(still, ColorBy::kPressure), 1.5e4);
}
