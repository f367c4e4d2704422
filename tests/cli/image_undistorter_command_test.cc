// `ramap image_undistorter` on a synthetic model seen through a distorted camera: undistorted
// images and a PINHOLE model in COLMAP's layout that read back, each observation on the pinhole
// pixel of its point; bad option values and an output over the originals refused, nothing written.
#include <gtest/gtest.h>

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "ramap/geometry/camera_projection.h"
#include "ramap/io/colmap_model.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

namespace fs = std::filesystem;

// A noise-free 5-view collection through a 320 x 240 OPENCV camera, its model in dir/model and
// an image of the camera's size per view in dir/images.
Reconstruction WriteScene(const test::TempDir& dir) {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kUnordered, SyntheticPath::kLine, 5);
  options.num_points = 300;
  options.camera.model = CameraModel::kOpenCV;
  options.camera.width = 320;
  options.camera.height = 240;
  options.camera.params = {260, 258, 159, 121, -0.12, 0.03, 0.001, -0.0005};
  const Reconstruction model = BuildSyntheticScene(options).ground_truth;
  WriteColmapModel(model, dir / "model", ModelFormat::kBinary);
  fs::create_directories(dir / "images");
  cv::Mat texture(240, 320, CV_8UC3);
  cv::RNG(3).fill(texture, cv::RNG::UNIFORM, 0, 255);
  cv::GaussianBlur(texture, texture, cv::Size(0, 0), 3.0);
  for (const auto& [id, image] : model.images) cv::imwrite(dir / ("images/" + image.name), texture);
  return model;
}

std::string Undistort(const test::TempDir& dir, const std::string& output,
                      const std::string& extra = "") {
  return test::RamapCommand() + "image_undistorter --image_path '" + (dir / "images") +
         "' --input_path '" + (dir / "model") + "' --output_path '" + output + "' " + extra;
}

TEST(ImageUndistorterCommand, ImagesAndPinholeModelInColmapsLayout) {
  test::TempDir dir;
  const Reconstruction distorted = WriteScene(dir);
  const test::CommandResult result = test::RunCommand(Undistort(dir, dir / "out"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("ramap image_undistorter: 5 images undistorted to 1 PINHOLE camera"),
            std::string::npos)
      << result.output;

  const Reconstruction model = ReadColmapModel(dir / "out/sparse");
  ASSERT_EQ(model.images.size(), 5u);
  ASSERT_EQ(model.cameras.size(), 1u);
  const Camera& pinhole = model.cameras.at(1);
  EXPECT_EQ(pinhole.model, CameraModel::kPinhole);
  EXPECT_EQ(model.points3D.size(), distorted.points3D.size());
  int num_checked = 0;
  for (const auto& [id, image] : model.images) {
    // Every image written in its own format, at the pinhole camera's size.
    const cv::Mat written = cv::imread(dir / ("out/images/" + image.name), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(written.empty()) << image.name;
    EXPECT_EQ(written.cols, static_cast<int>(pinhole.width));
    EXPECT_EQ(written.rows, static_cast<int>(pinhole.height));
    for (const Point2D& point : image.points2D) {
      if (point.point3D_id == kInvalidPoint3DId) continue;
      // The same ray through the pinhole camera: exact keypoints, Newton's inversion of the
      // distortion far below 1e-6 px.
      const Eigen::Vector2d expected =
          ProjectToPixel(pinhole, image.cam_from_world * model.points3D.at(point.point3D_id).xyz);
      EXPECT_LT((point.xy - expected).norm(), 1e-6);
      ++num_checked;
    }
  }
  EXPECT_GT(num_checked, 200);
  EXPECT_TRUE(fs::exists(dir / "out/sparse/rigs.bin"));
  EXPECT_TRUE(fs::exists(dir / "out/sparse/frames.bin"));
}

TEST(ImageUndistorterCommand, BadOptionValuesAreNamedAndNothingIsWritten) {
  test::TempDir dir;
  WriteScene(dir);
  const test::CommandResult blank =
      test::RunCommand(Undistort(dir, dir / "out", "--blank_pixels 2"));
  EXPECT_EQ(blank.exit_code, 2) << blank.output;
  EXPECT_NE(blank.output.find("--blank_pixels"), std::string::npos) << blank.output;
  const test::CommandResult type =
      test::RunCommand(Undistort(dir, dir / "out", "--output_type PMVS"));
  EXPECT_EQ(type.exit_code, 2) << type.output;
  EXPECT_NE(type.output.find("--output_type"), std::string::npos) << type.output;
  const test::CommandResult scales =
      test::RunCommand(Undistort(dir, dir / "out", "--min_scale 1.5 --max_scale 1.2"));
  EXPECT_EQ(scales.exit_code, 2) << scales.output;
  EXPECT_NE(scales.output.find("--max_scale"), std::string::npos) << scales.output;
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(ImageUndistorterCommand, TheOriginalsAreNeverTheOutput) {
  test::TempDir dir;
  const Reconstruction model = WriteScene(dir);
  const std::string first = model.images.begin()->second.name;
  const std::string before = test::ReadFileBytes(dir / ("images/" + first));
  // dir/images is the --image_path: output into dir would write the undistorted images there.
  const test::CommandResult result = test::RunCommand(Undistort(dir, dir.path()));
  EXPECT_EQ(result.exit_code, 2) << result.output;
  EXPECT_NE(result.output.find("--image_path itself"), std::string::npos) << result.output;
  EXPECT_EQ(test::ReadFileBytes(dir / ("images/" + first)), before);
  EXPECT_FALSE(fs::exists(dir / "sparse"));
}

}  // namespace
}  // namespace ramap
