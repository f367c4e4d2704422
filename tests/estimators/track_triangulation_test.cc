#include "ramap/estimators/track_triangulation.h"

#include <gtest/gtest.h>

#include <random>

namespace ramap {
namespace {

constexpr double kFocal = 500.0;

// Four pinhole images along x looking down +z at random points; keypoint k of every image is the
// projection of point k.
struct Fixture {
  FeatureDatabase database;
  std::map<uint32_t, Rigid3d> poses;
  std::vector<Eigen::Vector3d> points;
  std::map<uint32_t, std::vector<Eigen::Vector3d>> bearings;
  std::vector<Track> tracks;

  Fixture() {
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    Camera camera;
    camera.camera_id = 1;
    camera.params = {kFocal, kFocal, 320, 240};
    database.cameras[1] = camera;
    for (int p = 0; p < 50; ++p) points.emplace_back(u(rng), u(rng), 6 + u(rng));
    for (uint32_t id = 1; id <= 4; ++id) {
      Image image;
      image.image_id = id;
      image.camera_id = 1;
      image.name = "im" + std::to_string(id);
      database.images[id] = image;
      poses[id] = Rigid3d(Eigen::Quaterniond::Identity(), Eigen::Vector3d(-0.4 * id, 0, 0));
      Keypoints keypoints;
      for (const Eigen::Vector3d& X : points) {
        const Eigen::Vector3d x = poses[id] * X;
        keypoints.data.push_back(static_cast<float>(kFocal * x.x() / x.z() + 320));
        keypoints.data.push_back(static_cast<float>(kFocal * x.y() / x.z() + 240));
      }
      for (size_t k = 0; k < keypoints.size(); ++k) {
        const Eigen::Vector2d xy = keypoints.xy(k);
        bearings[id].push_back(
            Eigen::Vector3d((xy.x() - 320) / kFocal, (xy.y() - 240) / kFocal, 1).normalized());
      }
      database.keypoints[id] = keypoints;
    }
    for (uint32_t p = 0; p < points.size(); ++p) tracks.push_back({{1, p}, {2, p}, {3, p}, {4, p}});
  }
};

TEST(TrackTriangulation, TriangulatesEveryTrackWithFixedPoses) {
  Fixture f;
  TrackTriangulationSummary summary;
  const Reconstruction model =
      BuildReconstruction(f.database, f.poses, f.tracks, f.bearings, {{1, kFocal}}, {}, &summary);
  EXPECT_EQ(model.images.size(), 4u);
  EXPECT_EQ(model.cameras.size(), 1u);
  ASSERT_EQ(summary.num_points, 50);
  EXPECT_EQ(summary.num_observations, 200);
  // Keypoints are float32, so points agree to float precision.
  EXPECT_LT(summary.mean_reprojection_error_px, 1e-3);
  for (const auto& [id, point] : model.points3D) {
    const uint32_t p = point.track[0].point2D_idx;
    EXPECT_LT((point.xyz - f.points[p]).norm(), 1e-4);
    for (const TrackElement& e : point.track)
      EXPECT_EQ(model.images.at(e.image_id).points2D[e.point2D_idx].point3D_id, id);
  }
}

TEST(TrackTriangulation, WrongObservationLeavesTheTrackAndUnposedImagesAreSkipped) {
  Fixture f;
  f.bearings[3][0] = (f.bearings[3][0] + Eigen::Vector3d(0, 0.05, 0)).normalized();
  f.poses.erase(4);
  const Reconstruction model =
      BuildReconstruction(f.database, f.poses, f.tracks, f.bearings, {{1, kFocal}});
  EXPECT_EQ(model.images.size(), 3u);
  const Point3D& first = model.points3D.begin()->second;
  ASSERT_EQ(first.track.size(), 2u);  // images 1 and 2; 3 disagrees, 4 has no pose
  EXPECT_EQ(model.images.at(3).points2D[0].point3D_id, kInvalidPoint3DId);
}

// Where BA starts, an observation 0.8 deg off its point (7 px at this focal length: beyond the 4 px
// bound, within the start's 1 deg) stays in its track for BA to weigh; one 3 deg off does not.
TEST(TrackTriangulation, ABundleAdjustmentStartKeepsObservationsWithinItsAngle) {
  Fixture f;
  const auto turn = [&](uint32_t image_id, uint32_t keypoint, double deg) {
    Eigen::Vector3d& bearing = f.bearings[image_id][keypoint];
    bearing = Eigen::AngleAxisd(deg * M_PI / 180.0, Eigen::Vector3d::UnitX()) * bearing;
  };
  turn(3, 0, 0.8);
  turn(3, 1, 3.0);
  const TrackTriangulationOptions options;
  const Reconstruction strict =
      BuildReconstruction(f.database, f.poses, f.tracks, f.bearings, {{1, kFocal}}, options);
  const Reconstruction start = BuildReconstruction(
      f.database, f.poses, f.tracks, f.bearings, {{1, kFocal}}, options.ForBundleAdjustmentStart());
  EXPECT_EQ(strict.images.at(3).points2D[0].point3D_id, kInvalidPoint3DId);
  EXPECT_NE(start.images.at(3).points2D[0].point3D_id, kInvalidPoint3DId);
  EXPECT_EQ(start.images.at(3).points2D[1].point3D_id, kInvalidPoint3DId);
  EXPECT_EQ(start.points3D.size(), strict.points3D.size());
}

TEST(TrackTriangulation, TheModelDoesNotDependOnTheThreads) {
  Fixture f;
  f.bearings[3][0] = (f.bearings[3][0] + Eigen::Vector3d(0, 0.05, 0)).normalized();
  f.tracks.push_back({{1, 7}, {4, 7}});  // a second track of point 7: its own id, in order
  TrackTriangulationSummary one_summary, three_summary;
  const Reconstruction one = BuildReconstruction(f.database, f.poses, f.tracks, f.bearings,
                                                 {{1, kFocal}}, {}, &one_summary, 1);
  const Reconstruction three = BuildReconstruction(f.database, f.poses, f.tracks, f.bearings,
                                                   {{1, kFocal}}, {}, &three_summary, 3);
  ASSERT_EQ(one.points3D.size(), 51u);
  ASSERT_EQ(three.points3D.size(), one.points3D.size());
  EXPECT_EQ(three_summary.num_observations, one_summary.num_observations);
  EXPECT_EQ(three_summary.mean_reprojection_error_px, one_summary.mean_reprojection_error_px);
  for (const auto& [id, point] : one.points3D) {
    const Point3D& other = three.points3D.at(id);
    EXPECT_EQ(other.xyz, point.xyz);
    ASSERT_EQ(other.track.size(), point.track.size());
    for (size_t k = 0; k < point.track.size(); ++k) {
      EXPECT_EQ(other.track[k].image_id, point.track[k].image_id);
      EXPECT_EQ(other.track[k].point2D_idx, point.track[k].point2D_idx);
    }
  }
}

}  // namespace
}  // namespace ramap
