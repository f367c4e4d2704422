// ComputeBearings: every keypoint's undistorted unit ray, through the database's cameras or given
// ones, each camera's mean focal length, and unusable cameras named.
#include "ramap/estimators/bearings.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ramap/geometry/camera_projection.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// A noise-free line seen through a distorted camera (OpenCV model, fx != fy), so that the
// bearings must undo the distortion to point at the points.
SyntheticScene DistortedScene() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 10);
  options.num_points = 400;
  options.camera.model = CameraModel::kOpenCV;
  options.camera.params = {500, 520, 320, 240, -0.15, 0.03, 0.001, -0.0005};
  return BuildSyntheticScene(options);
}

double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

TEST(Bearings, EachKeypointPointsAtItsPointThroughTheDistortedCamera) {
  const SyntheticScene scene = DistortedScene();
  const ImageBearings bearings = ComputeBearings(scene.database, "synthetic");
  ASSERT_EQ(bearings.bearings.size(), scene.database.images.size());
  int num_checked = 0;
  for (const auto& [image_id, image] : scene.ground_truth.images) {
    const std::vector<Eigen::Vector3d>& rays = bearings.bearings.at(image_id);
    ASSERT_EQ(rays.size(), scene.database.keypoints.at(image_id).size());
    for (size_t k = 0; k < image.points2D.size(); ++k) {
      const uint64_t point_id = image.points2D[k].point3D_id;
      if (point_id == kInvalidPoint3DId) continue;
      EXPECT_NEAR(rays[k].norm(), 1.0, 1e-12);
      const Eigen::Vector3d truth =
          image.cam_from_world * scene.ground_truth.points3D.at(point_id).xyz;
      // float32 keypoints round by ~3e-5 px, 6e-8 rad at 500 px; the distortion's inversion
      // converges far below that.
      EXPECT_LT(AngleRad(rays[k], truth), 1e-6) << "image " << image_id << " keypoint " << k;
      ++num_checked;
    }
  }
  EXPECT_GT(num_checked, 1000);
  EXPECT_EQ(bearings.focal_lengths_px.at(1), 510.0);  // (fx + fy) / 2
}

TEST(Bearings, GivenCamerasReplaceTheDatabasesForTheGivenImages) {
  const SyntheticScene scene = DistortedScene();
  std::map<uint32_t, Camera> refined = scene.database.cameras;
  refined.at(1) = test::VgaPinholeCamera(800, 800);
  const ImageBearings bearings = ComputeBearings(scene.database, refined, "refined", {3, 7});
  // Only the images asked for.
  ASSERT_EQ(bearings.bearings.size(), 2u);
  ASSERT_TRUE(bearings.bearings.count(3));
  ASSERT_TRUE(bearings.bearings.count(7));
  EXPECT_EQ(bearings.focal_lengths_px.at(1), 800.0);
  const Keypoints& keypoints = scene.database.keypoints.at(7);
  for (size_t k = 0; k < keypoints.size(); ++k) {
    // Through the pinhole camera: (x - cx, y - cy, f) normalised, as written by hand; the two
    // differ by rounding alone.
    const Eigen::Vector2d xy = keypoints.xy(k);
    const Eigen::Vector3d expected = Eigen::Vector3d(xy.x() - 320, xy.y() - 240, 800).normalized();
    EXPECT_LT(AngleRad(bearings.bearings.at(7)[k], expected), 1e-12);
  }
}

TEST(Bearings, UnusableCameraParametersNameTheSourceAndTheCamera) {
  SyntheticScene scene = DistortedScene();
  scene.database.cameras.at(1).params[0] = 0.0;  // fx
  test::ExpectInputError([&] { ComputeBearings(scene.database, "scene.db"); },
                         {"scene.db", "camera 1", "focal length"});
  scene.database.cameras.at(1).params.pop_back();
  test::ExpectInputError([&] { ComputeBearings(scene.database, "scene.db"); },
                         {"scene.db", "camera 1", "parameters"});
}

}  // namespace
}  // namespace ramap
