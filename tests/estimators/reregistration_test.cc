// Images placed badly by averaging, registered again from the points the other images triangulate.
#include "ramap/estimators/reregistration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "ramap/estimators/bearings.h"
#include "ramap/estimators/track_triangulation.h"
#include "ramap/geometry/absolute_pose.h"
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

// A scene's tracks and bearings, its images at their true poses, and the points triangulated
// through them.
struct Placed {
  std::vector<Track> tracks;
  ImageBearings bearings;
  std::map<uint32_t, Rigid3d> poses;
  Reconstruction reconstruction;
};

Placed AtTheTruePoses(const SyntheticScene& scene) {
  Placed placed;
  placed.tracks = BuildTracks(scene.database.two_view_geometries);
  placed.bearings = ComputeBearings(scene.database, "synthetic");
  for (const auto& [id, image] : scene.ground_truth.images) placed.poses[id] = image.cam_from_world;
  placed.reconstruction =
      BuildReconstruction(scene.database, placed.poses, placed.tracks, placed.bearings.bearings,
                          placed.bearings.focal_lengths_px);
  return placed;
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
  Placed placed = AtTheTruePoses(Collection());
  EXPECT_TRUE(ReregisterImages(placed.tracks, placed.bearings.bearings,
                               placed.bearings.focal_lengths_px, placed.reconstruction,
                               ReregistrationOptions(), 4.0, &placed.poses)
                  .empty());
}

// Bearings through a focal length far off bend every ray: the points leave out most observations of
// most images (the median image keeps 41% here, where the former absolute bound of 50% tried 15 of
// 16 images). Absolute poses through that focal length cannot set the model right; only the
// images left out far more than the others are tried.
TEST(Reregistration, AFocalLengthFarOffLeavesOutMostImagesAndOnlyTheWorstAreTried) {
  SyntheticScene scene = Collection();
  for (auto& [id, camera] : scene.database.cameras) {
    camera.params[0] *= 1.6;
    camera.params[1] *= 1.6;
  }
  const Placed placed = AtTheTruePoses(scene);
  const auto tried = [&](double max_inlier_ratio) {
    ReregistrationOptions options;
    options.max_inlier_ratio = max_inlier_ratio;
    std::map<uint32_t, Rigid3d> trial = placed.poses;
    std::set<uint32_t> ids;
    for (const ReregisteredImage& image :
         ReregisterImages(placed.tracks, placed.bearings.bearings, placed.bearings.focal_lengths_px,
                          placed.reconstruction, options, 4.0, &trial)) {
      ids.insert(image.image_id);
    }
    return ids;
  };
  const std::set<uint32_t> below_the_median = tried(1.0);
  const std::set<uint32_t> far_below = tried(ReregistrationOptions().max_inlier_ratio);
  EXPECT_GE(below_the_median.size(), scene.database.images.size() / 2 - 1);
  EXPECT_LE(far_below.size(), scene.database.images.size() / 2);
  EXPECT_FALSE(far_below.empty());
  EXPECT_TRUE(std::includes(below_the_median.begin(), below_the_median.end(), far_below.begin(),
                            far_below.end()));
}

}  // namespace
}  // namespace ramap
