// The pinhole camera of a distorted one and the undistorted images (geometry/undistortion.h,
// jobs/image_undistortion.h): a 3D point lands on the same pixel through the distorted image
// undistorted as through the PINHOLE camera directly.
#include "ramap/geometry/undistortion.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <random>

#include "ramap/geometry/camera_projection.h"
#include "ramap/io/colmap_model.h"
#include "ramap/jobs/image_undistortion.h"
#include "ramap/util/error.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A phone-like OPENCV camera with barrel distortion and an off-centre principal point.
Camera OpenCVCamera() {
  return Camera{
      3, CameraModel::kOpenCV, 640, 480, {520.0, 515.0, 318.0, 243.0, -0.12, 0.03, 0.001, -0.0005}};
}

TEST(Undistortion, PointsReprojectToTheSamePixelThroughThePinholeCamera) {
  const Camera distorted = OpenCVCamera();
  for (const double blank_pixels : {0.0, 0.5, 1.0}) {
    UndistortionOptions options;
    options.blank_pixels = blank_pixels;
    const Camera pinhole = UndistortedCamera(distorted, options, "test");
    EXPECT_EQ(pinhole.model, CameraModel::kPinhole);
    EXPECT_EQ(pinhole.params[0], 520.0);  // focal lengths kept, the image resized
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> uniform(-0.5, 0.5);
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d point(uniform(rng), 0.75 * uniform(rng), 1.0);
      const Eigen::Vector2d through_distorted =
          UndistortPixel(distorted, pinhole, ProjectToPixel(distorted, point));
      const Eigen::Vector2d direct = ProjectToPixel(pinhole, point);
      EXPECT_LT((through_distorted - direct).norm(), 1e-6) << "blank_pixels " << blank_pixels;
    }
  }
}

TEST(Undistortion, BlankPixelsBoundTheBorders) {
  const Camera distorted = OpenCVCamera();
  UndistortionOptions crop;  // blank_pixels 0: every undistorted pixel sees the distorted image
  const Camera cropped = UndistortedCamera(distorted, crop, "test");
  for (double x = 0.5; x < cropped.width; x += 7) {
    for (const double y : {0.5, cropped.height - 0.5}) {
      const Eigen::Vector2d source = UndistortPixel(cropped, distorted, Eigen::Vector2d(x, y));
      EXPECT_GE(source.x(), -0.5);
      EXPECT_LE(source.x(), distorted.width + 0.5);
      EXPECT_GE(source.y(), -0.5);
      EXPECT_LE(source.y(), distorted.height + 0.5);
    }
  }
  UndistortionOptions keep;  // blank_pixels 1: every distorted pixel is in the undistorted image
  keep.blank_pixels = 1.0;
  const Camera kept = UndistortedCamera(distorted, keep, "test");
  EXPECT_GT(kept.width, cropped.width);
  for (double x = 0.5; x < distorted.width; x += 7) {
    // Within half a pixel: the size is a whole number of pixels, the scale is not.
    const Eigen::Vector2d target = UndistortPixel(distorted, kept, Eigen::Vector2d(x, 0.5));
    EXPECT_GE(target.y(), -0.5);
    EXPECT_LE(target.x(), kept.width + 0.5);
  }
  // A pinhole camera is its own undistorted camera.
  const Camera pinhole{1, CameraModel::kPinhole, 640, 480, {500, 501, 320, 240}};
  EXPECT_EQ(UndistortedCamera(pinhole, crop, "test").params, pinhole.params);
  UndistortionOptions bad;
  bad.blank_pixels = 2;
  EXPECT_THROW(bad.Check(), InputError);
}

// A smooth grey pattern, so that bilinear sampling is nearly exact.
double Pattern(double x, double y) {
  return 128 + 60 * std::sin(x / 23.0) * std::cos(y / 31.0) + 30 * std::sin((x + y) / 47.0);
}

TEST(ImageUndistortion, ImagesAndModelInColmapsLayout) {
  test::TempDir dir;
  const Camera distorted = OpenCVCamera();
  // The distorted image of a pattern drawn on the ideal pinhole image of the same intrinsics.
  const Camera ideal{3, CameraModel::kPinhole, 640, 480, {520.0, 515.0, 318.0, 243.0}};
  cv::Mat image(480, 640, CV_8UC1);
  for (int row = 0; row < 480; ++row) {
    for (int col = 0; col < 640; ++col) {
      const Eigen::Vector2d p =
          UndistortPixel(distorted, ideal, Eigen::Vector2d(col + 0.5, row + 0.5));
      image.at<uint8_t>(row, col) = cv::saturate_cast<uint8_t>(Pattern(p.x(), p.y()));
    }
  }
  fs::create_directories(dir / "input/sub");
  cv::imwrite(dir / "input/sub/a.png", image);
  Reconstruction model;
  model.cameras[3] = distorted;
  Image a;
  a.image_id = 5;
  a.camera_id = 3;
  a.name = "sub/a.png";
  a.points2D.push_back({Eigen::Vector2d(100.5, 80.25), kInvalidPoint3DId});
  model.images[5] = a;

  const ImageUndistortionSummary summary = UndistortImages(
      model, dir / "input", dir / "out", UndistortionOptions(), ModelFormat::kBinary, 2, nullptr);
  EXPECT_EQ(summary.num_images, 1);
  const Reconstruction written = ReadColmapModel(dir / "out/sparse");
  const Camera& pinhole = written.cameras.at(3);
  EXPECT_EQ(pinhole.model, CameraModel::kPinhole);
  EXPECT_LT((written.images.at(5).points2D[0].xy -
             UndistortPixel(distorted, pinhole, Eigen::Vector2d(100.5, 80.25)))
                .norm(),
            1e-12);
  const cv::Mat out = cv::imread(dir / "out/images/sub/a.png", cv::IMREAD_UNCHANGED);
  ASSERT_EQ(out.cols, static_cast<int>(pinhole.width));
  ASSERT_EQ(out.rows, static_cast<int>(pinhole.height));
  // Each undistorted pixel shows the pattern at its ray through the ideal camera.
  double error = 0;
  int count = 0;
  for (int row = 10; row < out.rows - 10; row += 3) {
    for (int col = 10; col < out.cols - 10; col += 3) {
      const Eigen::Vector2d p =
          ProjectToPixel(ideal, PixelToBearing(pinhole, Eigen::Vector2d(col + 0.5, row + 0.5)));
      error += std::abs(out.at<uint8_t>(row, col) - Pattern(p.x(), p.y()));
      ++count;
    }
  }
  EXPECT_LT(error / count, 1.0) << "mean grey-level error";
  // The originals are never the output.
  EXPECT_THROW(UndistortImages(model, dir / "out/images", dir / "out", UndistortionOptions(),
                               ModelFormat::kBinary, 1, nullptr),
               InputError);
}

}  // namespace
}  // namespace ramap
