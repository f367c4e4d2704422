#include "ramap/io/point_colors.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "test_support.h"

namespace ramap {
namespace {

TEST(PointColors, MeanOfTheObservationsAndUnreadableImagesListed) {
  test::TempDir dir;
  // A red image and a blue one (OpenCV stores BGR), 8 x 6.
  cv::imwrite(dir / "red.png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(0, 0, 255)));
  cv::imwrite(dir / "blue.png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(255, 0, 0)));
  Reconstruction model;
  const std::vector<std::string> names = {"red.png", "blue.png", "missing.png"};
  for (uint32_t id = 1; id <= 3; ++id) {
    Image image;
    image.image_id = id;
    image.name = names[id - 1];
    Point2D seen;
    seen.xy = Eigen::Vector2d(3.5, 2.5);
    seen.point3D_id = 7;
    image.points2D.push_back(seen);
    model.images[id] = image;
  }
  model.points3D[7].track = {{1, 0}, {2, 0}, {3, 0}};
  const PointColorSummary summary = ColorPointsFromImages(dir.path(), &model);
  EXPECT_EQ(summary.num_images_read, 2);
  ASSERT_EQ(summary.unreadable_images.size(), 1u);
  EXPECT_EQ(summary.unreadable_images[0], "missing.png");
  EXPECT_EQ(model.points3D[7].color, (Eigen::Matrix<uint8_t, 3, 1>(128, 0, 128)));
}

}  // namespace
}  // namespace ramap
