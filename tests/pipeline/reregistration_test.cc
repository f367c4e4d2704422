// Images placed badly by averaging, registered again from the points the other images triangulate.
#include "ramap/pipeline/reregistration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "ramap/geometry/absolute_pose.h"
#include "ramap/pipeline/bearings.h"
#include "ramap/pipeline/track_triangulation.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

SyntheticScene Collection() { return BuildSyntheticScene(test::NoisyCollection(5)); }

// `pose` turned by `angle_deg` about an axis through its camera centre.
Rigid3d Turned(const Rigid3d& pose, double angle_deg) {
  const Eigen::Vector3d center = pose.Inverse().translation;
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(angle_deg * M_PI / 180.0, Eigen::Vector3d(1, 2, 0).normalized()));
  const Eigen::Quaterniond rotation = turn * pose.rotation;
  return Rigid3d(rotation, -(rotation * center));
}

TEST(AbsolutePose, RecoversAPoseFromBearingsWithOutliers) {
  const SyntheticScene scene = Collection();
  const Image& image = scene.ground_truth.images.begin()->second;
  std::vector<Eigen::Vector3d> bearings, points;
  for (const auto& [id, point] : scene.ground_truth.points3D) {
    const Eigen::Vector3d x = image.cam_from_world * point.xyz;
    if (x.z() <= 0) continue;
    bearings.push_back(x.normalized());
    points.push_back(point.xyz);
    if (bearings.size() % 5 == 0) bearings.back() = Eigen::Vector3d(0.1, -0.2, 1).normalized();
  }
  const std::optional<AbsolutePose> pose = EstimateAbsolutePose(bearings, points, {});
  ASSERT_TRUE(pose.has_value());
  EXPECT_LT(pose->cam_from_world.rotation.angularDistance(image.cam_from_world.rotation), 1e-6);
  EXPECT_NEAR(static_cast<double>(pose->inliers.size()), 0.8 * bearings.size(), 2.0);
}

TEST(Reregistration, CameraThirtyDegreesOffIsPlacedAgain) {
  const SyntheticScene scene = Collection();
  const FeatureDatabase& database = scene.database;
  const std::vector<Track> tracks = BuildTracks(database.two_view_geometries);
  const ImageBearings bearings = ComputeBearings(database, "synthetic");
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [id, image] : scene.ground_truth.images) poses[id] = image.cam_from_world;
  const uint32_t off = 5;
  poses[off] = Turned(poses[off], 30.0);
  const Reconstruction reconstruction =
      BuildReconstruction(database, poses, tracks, bearings.bearings, bearings.focal_lengths_px);

  const std::vector<ReregisteredImage> tried =
      ReregisterImages(tracks, bearings.bearings, bearings.focal_lengths_px, reconstruction,
                       ReregistrationOptions(), 4.0, &poses);
  ASSERT_EQ(tried.size(), 1u) << "only the image its points left out";
  EXPECT_EQ(tried[0].image_id, off);
  EXPECT_EQ(tried[0].name, database.images.at(off).name);
  EXPECT_TRUE(tried[0].replaced);
  EXPECT_NEAR(tried[0].rotation_change_deg, 30.0, 0.5);
  EXPECT_GT(tried[0].num_inliers_after, 10 * std::max(tried[0].num_inliers_before, 1));
  const Rigid3d& truth = scene.ground_truth.images.at(off).cam_from_world;
  EXPECT_LT(poses.at(off).rotation.angularDistance(truth.rotation) * 180.0 / M_PI, 0.1);
  for (const auto& [id, image] : scene.ground_truth.images) {
    if (id == off) continue;
    EXPECT_EQ(poses.at(id).rotation.coeffs(), image.cam_from_world.rotation.coeffs());
  }
}

TEST(Reregistration, WellPlacedImagesAreLeftAlone) {
  const SyntheticScene scene = Collection();
  const std::vector<Track> tracks = BuildTracks(scene.database.two_view_geometries);
  const ImageBearings bearings = ComputeBearings(scene.database, "synthetic");
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [id, image] : scene.ground_truth.images) poses[id] = image.cam_from_world;
  const Reconstruction reconstruction = BuildReconstruction(
      scene.database, poses, tracks, bearings.bearings, bearings.focal_lengths_px);
  EXPECT_TRUE(ReregisterImages(tracks, bearings.bearings, bearings.focal_lengths_px, reconstruction,
                               ReregistrationOptions(), 4.0, &poses)
                  .empty());
}

}  // namespace
}  // namespace ramap
