// The comparison's PNG figures, read back as images: trajectories top-down at one scale on both
// axes, cumulative distributions that stay below 1 for unregistered images, and stacked bars as
// long as each row's time.
#include "ramap/compare/plots.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "ramap/util/image_codecs.h"
#include "test_support.h"

namespace ramap {
namespace {

// The bounding box of the pixels of exactly colour `bgr` outside the rectangle `excluded` (the
// legend, drawn in the same colours).
cv::Rect PixelsOfColour(const cv::Mat& image, const cv::Vec3b& bgr, const cv::Rect& excluded) {
  int x0 = image.cols, y0 = image.rows, x1 = -1, y1 = -1;
  for (int y = 0; y < image.rows; ++y) {
    for (int x = 0; x < image.cols; ++x) {
      if (image.at<cv::Vec3b>(y, x) != bgr || excluded.contains({x, y})) continue;
      x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
    }
  }
  return x1 < 0 ? cv::Rect() : cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
}

TEST(Plots, TrajectoriesAreDrawnOnTheReferencesPlaneAtOneScale) {
  test::TempDir dir;
  // The reference: a circle of radius 10 in a plane tilted 40 degrees, seen top-down on its own
  // principal axes it is a circle again, not an ellipse; a second series is a short line.
  const Eigen::Matrix3d tilt =
      Eigen::AngleAxisd(40 * M_PI / 180, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  PlotSeries reference{"ground truth", {}, {}}, other{"ramap", {}, {}};
  for (int k = 0; k <= 72; ++k) {
    const double a = 2 * M_PI * k / 72;
    reference.points.push_back(tilt * Eigen::Vector3d(10 * std::cos(a), 10 * std::sin(a), 0));
  }
  other.points = {Eigen::Vector3d(0, 0, 0), tilt * Eigen::Vector3d(5, 0, 0)};
  PlotTrajectories({reference, other}, "test", dir / "trajectories.png");
  const cv::Mat image = ReadImageFile(dir / "trajectories.png", cv::IMREAD_COLOR);
  ASSERT_EQ(image.size(), cv::Size(900, 640));
  // The reference's colour, (40, 40, 40), inside the plot area (the black text's antialiased
  // edges have greys of every shade) and away from the legend in its top right corner.
  const cv::Mat plot = image(cv::Rect(81, 51, 789, 529));  // columns 81-869, rows 51-579
  const cv::Rect circle = PixelsOfColour(plot, {40, 40, 40}, cv::Rect(569, 0, 250, 60));
  ASSERT_GT(circle.width, 100);
  // Equal scale: as wide as high, within the 3 px of the line's width and the antialiasing.
  EXPECT_NEAR(circle.width, circle.height, 4);
  // The second series is drawn in its own colour, inside the circle.
  const cv::Rect line = PixelsOfColour(plot, {0, 110, 230}, cv::Rect(569, 0, 250, 60));
  ASSERT_GT(line.area(), 0);
  EXPECT_TRUE(circle.contains(line.tl()) && circle.contains(line.br()));
}

TEST(Plots, UnregisteredImagesKeepTheCumulativeCurveBelowOne) {
  test::TempDir dir;
  const double inf = std::numeric_limits<double>::infinity();
  PlotCumulativeDistributions({{"ramap", {}, {1, 2, 3, inf}}, {"COLMAP", {}, {0.5, 1, 1.5, 2}}},
                              "test", "degrees", dir / "cdf.png");
  const cv::Mat image = ReadImageFile(dir / "cdf.png", cv::IMREAD_COLOR);
  ASSERT_EQ(image.size(), cv::Size(900, 640));
  // Fractions 0 to 1 span rows 580 (bottom of the plot) to 50 (top). The first series (colour
  // (0, 110, 230)) reaches 3 of 4, row 580 - 0.75 * 530 = 182.5; the second reaches 1, row 50.
  // The legends sit in the bottom right corner.
  const cv::Rect legend(650, 480, 250, 100);
  const cv::Rect first = PixelsOfColour(image, {0, 110, 230}, legend);
  const cv::Rect second = PixelsOfColour(image, {200, 120, 0}, legend);
  // The line is 2 px wide and antialiased: its top within 2 rows of the value's.
  EXPECT_NEAR(first.y, 182.5, 2.5);
  EXPECT_NEAR(second.y, 50, 2.5);
  // Each starts at the origin, the bottom left of the plot (column 80, row 580); the second is
  // drawn over the first there.
  EXPECT_NEAR(second.x, 80, 2);
  EXPECT_NEAR(second.y + second.height - 1, 580, 2);
  EXPECT_NEAR(first.y + first.height - 1, 580, 2);
}

TEST(Plots, StageBarsAreAsLongAsEachRowsTimeWithAColourPerStage) {
  test::TempDir dir;
  PlotStageTimes({{"ramap", {{"rotation averaging", 1.0}, {"bundle adjustment", 3.0}}},
                  {"COLMAP", {{"rotation averaging", 2.0}}}},
                 "test", dir / "stages.png");
  const cv::Mat image = ReadImageFile(dir / "stages.png", cv::IMREAD_COLOR);
  ASSERT_EQ(image.cols, 900);
  // Bars start at column 170; the rows' middles are 60 px apart from row 78.
  const auto segments = [&](int row) {
    std::vector<std::pair<cv::Vec3b, int>> runs;  // colour, length
    for (int x = 170; x < image.cols; ++x) {
      const cv::Vec3b pixel = image.at<cv::Vec3b>(row, x);
      if (pixel == cv::Vec3b(255, 255, 255)) break;
      if (runs.empty() || runs.back().first != pixel) runs.push_back({pixel, 0});
      ++runs.back().second;
    }
    return runs;
  };
  const auto ramap = segments(78), colmap = segments(138);
  ASSERT_EQ(ramap.size(), 2u);
  ASSERT_EQ(colmap.size(), 1u);
  // 1 s and 3 s, then 2 s: lengths in proportion, within a pixel of rounding each.
  EXPECT_NEAR(3.0 * ramap[0].second, ramap[1].second, 3);
  EXPECT_NEAR(2.0 * ramap[0].second, colmap[0].second, 2);
  // One colour per stage, whichever row it is in.
  EXPECT_EQ(ramap[0].first, colmap[0].first);
  EXPECT_NE(ramap[0].first, ramap[1].first);
}

}  // namespace
}  // namespace ramap
