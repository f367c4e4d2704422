#include "ramap/refine/bundle_adjustment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace ramap {
namespace {

// Ten cameras on an arc looking at a cloud of points; bearings exact.
struct Scene {
  Reconstruction reconstruction;
  std::map<uint32_t, std::vector<Eigen::Vector3d>> bearings;
  std::map<uint32_t, Rigid3d> true_poses;
  std::map<uint64_t, Eigen::Vector3d> true_points;
};

Scene MakeScene(std::mt19937& rng) {
  Scene scene;
  Camera camera;
  camera.camera_id = 1;
  camera.params = {500, 500, 320, 240};
  camera.width = 640;
  camera.height = 480;
  scene.reconstruction.cameras[1] = camera;
  std::normal_distribution<double> cloud(0, 1);
  for (uint32_t id = 1; id <= 10; ++id) {
    const double angle = 0.08 * id;
    const Eigen::Quaterniond rotation(Eigen::AngleAxisd(angle, Eigen::Vector3d::UnitY()));
    const Eigen::Vector3d center(6 * std::sin(angle), 0.1 * id, -6 * std::cos(angle));
    Image image;
    image.image_id = id;
    image.camera_id = 1;
    image.name = "image" + std::to_string(id);
    image.cam_from_world = Rigid3d(rotation, -(rotation * center));
    scene.true_poses[id] = image.cam_from_world;
    scene.reconstruction.images[id] = image;
  }
  for (uint64_t p = 0; p < 200; ++p) {
    Point3D point;
    point.xyz = Eigen::Vector3d(cloud(rng), cloud(rng), cloud(rng));
    scene.true_points[p] = point.xyz;
    for (auto& [id, image] : scene.reconstruction.images) {
      point.track.push_back({id, static_cast<uint32_t>(image.points2D.size())});
      Point2D observation;
      observation.point3D_id = p;
      image.points2D.push_back(observation);
      scene.bearings[id].push_back((image.cam_from_world * point.xyz).normalized());
    }
    scene.reconstruction.points3D[p] = point;
  }
  return scene;
}

TEST(BundleAdjustment, RecoversPerturbedPosesAndPoints) {
  std::mt19937 rng(7);
  Scene scene = MakeScene(rng);
  std::normal_distribution<double> noise(0, 0.02);
  for (auto& [id, image] : scene.reconstruction.images) {
    if (id == 1) continue;  // the gauge
    image.cam_from_world.translation += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    image.cam_from_world.rotation =
        Eigen::Quaterniond(Eigen::AngleAxisd(noise(rng), Eigen::Vector3d::UnitX())) *
        image.cam_from_world.rotation;
  }
  for (auto& [id, point] : scene.reconstruction.points3D)
    point.xyz += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  // A wrong observation is detached, not followed.
  scene.bearings[5][0] = (scene.bearings[5][0] + Eigen::Vector3d(0.05, 0, 0)).normalized();

  BundleAdjustmentOptions options;
  options.max_num_iterations = 100;
  // The observations here are the bearings (one made wrong above); fixed intrinsics keep them.
  options.refine_focal_length = options.refine_extra_params = false;
  // One solve at the loss scale, so that num_solves counts the second solve for the detached.
  options.wide_start_loss_factor = 0;
  const BundleAdjustmentSummary summary =
      BundleAdjust(scene.bearings, {{1, 500.0}}, &scene.reconstruction, options);
  EXPECT_GT(summary.initial_rmse_px, 1.0);
  EXPECT_LT(summary.final_rmse_px, 1e-3);
  EXPECT_EQ(summary.num_filtered_observations, 1);
  EXPECT_EQ(summary.num_solves, 1);  // one detached observation of 2000: not worth a second solve
  EXPECT_EQ(summary.filtered_per_image, (std::map<uint32_t, int>{{5, 1}}));
  EXPECT_EQ(scene.reconstruction.images.at(5).points2D[0].point3D_id, kInvalidPoint3DId);
  EXPECT_EQ(scene.reconstruction.points3D.at(0).track.size(), 9u);
  // Scale is free in BA with one camera fixed: compare directions of centres from camera 1.
  const Eigen::Vector3d c1 = CameraCenter(scene.true_poses.at(1));
  for (const auto& [id, image] : scene.reconstruction.images) {
    if (id == 1) continue;
    const Eigen::Vector3d est = (CameraCenter(image.cam_from_world) - c1).normalized();
    const Eigen::Vector3d truth = (CameraCenter(scene.true_poses.at(id)) - c1).normalized();
    EXPECT_LT((est - truth).norm(), 1e-4) << "image " << id;
    EXPECT_LT(image.cam_from_world.rotation.angularDistance(scene.true_poses.at(id).rotation),
              1e-4);
  }
}

// Once the poses stop moving, BA stops, though the points (triangulated again by the mapper)
// would go on lowering the cost; the poses are then where a solve to the end puts them.
TEST(BundleAdjustment, StopsWhenThePosesHaveSettled) {
  std::mt19937 rng(5);
  Scene scene = MakeScene(rng);
  // Keypoints with 0.5 px of noise (at 500 px focal length): the cost's minimum is not zero, and
  // its last decrease is slow.
  std::normal_distribution<double> pixel_noise(0, 0.5 / 500);
  for (auto& [id, bearings] : scene.bearings) {
    for (Eigen::Vector3d& b : bearings)
      b = (b / b.z() + Eigen::Vector3d(pixel_noise(rng), pixel_noise(rng), 0)).normalized();
  }
  std::normal_distribution<double> noise(0, 0.05);
  for (auto& [id, point] : scene.reconstruction.points3D)
    point.xyz += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  for (auto& [id, image] : scene.reconstruction.images) {
    if (id != 1) image.cam_from_world.translation += Eigen::Vector3d(noise(rng), 0, noise(rng));
  }
  BundleAdjustmentOptions options;
  options.refine_focal_length = options.refine_extra_params = false;
  options.function_tolerance = 1e-10;  // Ceres's own criterion out of the way
  Scene full = scene;
  const BundleAdjustmentSummary settled =
      BundleAdjust(scene.bearings, {{1, 500.0}}, &scene.reconstruction, options);
  options.pose_tolerance_deg = 0;
  const BundleAdjustmentSummary to_the_end =
      BundleAdjust(full.bearings, {{1, 500.0}}, &full.reconstruction, options);
  EXPECT_TRUE(settled.poses_settled);
  EXPECT_TRUE(settled.converged);
  EXPECT_FALSE(to_the_end.poses_settled);
  EXPECT_LT(settled.num_iterations, to_the_end.num_iterations);
  const Eigen::Vector3d c1 = CameraCenter(full.reconstruction.images.at(1).cam_from_world);
  for (const auto& [id, image] : scene.reconstruction.images) {
    if (id == 1) continue;
    const Rigid3d& end = full.reconstruction.images.at(id).cam_from_world;
    // 1e-3 deg per step at most, and less as the steps shrink.
    EXPECT_LT(image.cam_from_world.rotation.angularDistance(end.rotation), 0.003 * M_PI / 180)
        << "image " << id;
    const Eigen::Vector3d direction = (CameraCenter(image.cam_from_world) - c1).normalized();
    EXPECT_LT((direction - (CameraCenter(end) - c1).normalized()).norm(), 1e-4) << "image " << id;
  }
}

// BA solves with the world's origin among the points and returns the caller's frame: a scene far
// from its origin, held there by pose priors, comes back where the priors and the truth put it.
TEST(BundleAdjustment, ReturnsTheCallersFrameForASceneFarFromItsOrigin) {
  std::mt19937 rng(13);
  Scene scene = MakeScene(rng);
  const Eigen::Vector3d offset(400, -250, 120);
  std::map<uint32_t, PosePrior> priors;
  for (auto& [id, image] : scene.reconstruction.images) {
    image.cam_from_world.translation -= image.cam_from_world.rotation * offset;
    scene.true_poses[id] = image.cam_from_world;
    if (id % 3 == 1)
      priors[id] = {CameraCenter(image.cam_from_world), Eigen::Vector3d::Constant(0.01)};
  }
  for (auto& [id, point] : scene.reconstruction.points3D) {
    point.xyz += offset;
    scene.true_points[id] = point.xyz;
  }
  std::normal_distribution<double> noise(0, 0.02);
  for (auto& [id, image] : scene.reconstruction.images)
    image.cam_from_world.translation += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  for (auto& [id, point] : scene.reconstruction.points3D)
    point.xyz += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  BundleAdjustmentOptions options;
  options.refine_focal_length = options.refine_extra_params = false;
  const BundleAdjustmentSummary summary =
      BundleAdjust(scene.bearings, {{1, 500.0}}, &scene.reconstruction, options, priors);
  EXPECT_EQ(summary.num_priors, 4);
  EXPECT_LT(summary.final_rmse_px, 1e-3);
  for (const auto& [id, image] : scene.reconstruction.images) {
    EXPECT_LT((CameraCenter(image.cam_from_world) - CameraCenter(scene.true_poses.at(id))).norm(),
              1e-3)
        << "image " << id;
    EXPECT_LT(image.cam_from_world.rotation.angularDistance(scene.true_poses.at(id).rotation),
              1e-4);
  }
  for (const auto& [id, point] : scene.reconstruction.points3D)
    EXPECT_LT((point.xyz - scene.true_points.at(id)).norm(), 1e-3) << "point " << id;
}

// MakeScene's camera without a calibration: COLMAP's guess puts its principal point at the image's
// centre, while the true one lies 12 px right of it and 7 px above (the keypoints are projected
// through it).
Scene UncalibratedScene(std::mt19937& rng) {
  Scene scene = MakeScene(rng);
  Camera& camera = scene.reconstruction.cameras.at(1);
  camera.model = CameraModel::kSimplePinhole;
  camera.params = {500, 320, 240};
  for (auto& [id, image] : scene.reconstruction.images) {
    for (Point2D& point : image.points2D) {
      const Eigen::Vector3d x = image.cam_from_world * scene.true_points.at(point.point3D_id);
      point.xy = 500 * x.head<2>() / x.z() + Eigen::Vector2d(332, 233);
    }
  }
  return scene;
}

double LargestRotationErrorDeg(const Scene& scene) {
  double largest = 0;
  for (const auto& [id, image] : scene.reconstruction.images) {
    largest = std::max(
        largest, image.cam_from_world.rotation.angularDistance(scene.true_poses.at(id).rotation));
  }
  return largest * 180 / M_PI;
}

// An uncalibrated camera's principal point is refined with its focal length; a calibrated one's
// (prior_focal_length 1) is kept; so is any where refine_guessed_principal_point is off.
TEST(BundleAdjustment, GuessedPrincipalPointRefinedWithTheFocalLength) {
  std::mt19937 rng(17);
  const Scene start = UncalibratedScene(rng);
  BundleAdjustmentOptions options;
  options.refine_extra_params = false;
  Scene refined = start;
  BundleAdjust(refined.bearings, {{1, 500.0}}, &refined.reconstruction, options);
  const std::vector<double>& params = refined.reconstruction.cameras.at(1).params;
  EXPECT_NEAR(params[1], 332, 0.05);
  EXPECT_NEAR(params[2], 233, 0.05);
  EXPECT_LT(LargestRotationErrorDeg(refined), 0.01);

  Scene guess_kept = start;
  options.refine_guessed_principal_point = false;
  BundleAdjust(guess_kept.bearings, {{1, 500.0}}, &guess_kept.reconstruction, options);
  EXPECT_EQ(guess_kept.reconstruction.cameras.at(1).params[1], 320);
  EXPECT_GT(LargestRotationErrorDeg(guess_kept), 0.5);  // every camera turned by about 1.6 deg

  Scene calibrated = start;
  calibrated.reconstruction.cameras.at(1).has_prior_focal_length = true;
  options = BundleAdjustmentOptions();
  options.keep_prior_intrinsics = false;  // its focal length refined, its principal point not
  BundleAdjust(calibrated.bearings, {{1, 500.0}}, &calibrated.reconstruction, options);
  EXPECT_EQ(calibrated.reconstruction.cameras.at(1).params[1], 320);
}

// A refined principal point that moves beyond max_principal_point_shift is tested: BA solves again
// from the start with it held. Unless the move lowers the camera's median reprojection error by
// min_principal_point_error_decrease (1: never), the held solve is the result.
TEST(BundleAdjustment, DriftingPrincipalPointHeldAndSolvedAgain) {
  std::mt19937 rng(17);
  const Scene start = UncalibratedScene(rng);
  BundleAdjustmentOptions options;
  options.refine_extra_params = false;
  options.max_principal_point_shift = 0.01;  // 6.4 px across, 4.8 px down: 12 px is beyond
  options.min_principal_point_error_decrease = 1.0;
  Scene drifting = start;
  const BundleAdjustmentSummary summary =
      BundleAdjust(drifting.bearings, {{1, 500.0}}, &drifting.reconstruction, options);
  EXPECT_EQ(summary.principal_points_drifted, std::vector<uint32_t>{1});
  EXPECT_TRUE(summary.principal_points_confirmed.empty());
  Scene held = start;
  options.refine_guessed_principal_point = false;
  const BundleAdjustmentSummary held_summary =
      BundleAdjust(held.bearings, {{1, 500.0}}, &held.reconstruction, options);
  EXPECT_TRUE(held_summary.principal_points_drifted.empty());
  EXPECT_EQ(drifting.reconstruction.cameras.at(1).params, held.reconstruction.cameras.at(1).params);
  EXPECT_GT(summary.num_iterations, held_summary.num_iterations);
}

// A cropped photo's principal point lies far off the image's centre (here 12 px, beyond a
// max_principal_point_shift of 6.4 px): the move lowers the errors from about 12 px to the noise's,
// so it is kept, and so are the rotations it sets right.
TEST(BundleAdjustment, PrincipalPointFarOffTheCentreKeptWhereTheErrorsProveIt) {
  std::mt19937 rng(17);
  Scene scene = UncalibratedScene(rng);
  BundleAdjustmentOptions options;
  options.refine_extra_params = false;
  options.max_principal_point_shift = 0.01;
  const BundleAdjustmentSummary summary =
      BundleAdjust(scene.bearings, {{1, 500.0}}, &scene.reconstruction, options);
  EXPECT_EQ(summary.principal_points_confirmed, std::vector<uint32_t>{1});
  EXPECT_TRUE(summary.principal_points_drifted.empty());
  const std::vector<double>& params = scene.reconstruction.cameras.at(1).params;
  EXPECT_NEAR(params[1], 332, 0.05);
  EXPECT_NEAR(params[2], 233, 0.05);
  EXPECT_LT(LargestRotationErrorDeg(scene), 0.01);
}

// Detaches every observation of point `id` in image `image_id` for which `keep` is false.
template <typename Keep>
void KeepObservationsWhere(Scene* scene, Keep keep) {
  for (auto& [id, point] : scene->reconstruction.points3D) {
    std::vector<TrackElement> kept;
    for (const TrackElement& e : point.track) {
      if (keep(id, e.image_id)) {
        kept.push_back(e);
      } else {
        scene->reconstruction.images.at(e.image_id).points2D[e.point2D_idx].point3D_id =
            kInvalidPoint3DId;
      }
    }
    point.track = kept;
  }
}

TEST(BundleAdjustment, PointSubsetPrefersLongTracksAndCoversEveryImage) {
  std::mt19937 rng(3);
  Scene scene = MakeScene(rng);
  // Points 0-49 seen by every image; 50-199 cut to images 1-2 only, except 150-199 seen by 3-4.
  KeepObservationsWhere(&scene, [](uint64_t id, uint32_t image_id) {
    if (id < 50) return true;
    return id < 150 ? image_id <= 2 : (image_id == 3 || image_id == 4);
  });
  BundleAdjustmentOptions options;
  options.min_track_length = 2;  // the points of images 1-4 alone: the next test
  options.max_num_points = 60;
  options.min_observations_per_image = 55;
  const Reconstruction subset = PointsForBundleAdjustment(scene.reconstruction, options);
  // The 50 full tracks first, 10 more up to the cap (points 50-59, images 1 and 2), then only
  // what images 3 and 4 still need to reach 55 observations (points 150-154).
  for (uint64_t id = 0; id < 60; ++id) EXPECT_TRUE(subset.points3D.count(id)) << id;
  std::map<uint32_t, int> per_image;
  for (const auto& [id, point] : subset.points3D) {
    for (const TrackElement& e : point.track) ++per_image[e.image_id];
  }
  EXPECT_EQ(per_image[1], 60);
  EXPECT_EQ(per_image[2], 60);
  EXPECT_EQ(per_image[3], 55);
  EXPECT_EQ(per_image[4], 55);
  EXPECT_EQ(per_image[5], 50);
  EXPECT_EQ(subset.points3D.size(), 65u);
  // Observations of the points left out are detached.
  for (const auto& [image_id, image] : subset.images) {
    for (const Point2D& point : image.points2D) {
      EXPECT_TRUE(point.point3D_id == kInvalidPoint3DId || subset.points3D.count(point.point3D_id));
    }
  }
  options.max_num_points = 0;
  EXPECT_EQ(PointsForBundleAdjustment(scene.reconstruction, options).points3D.size(), 200u);
}

// Points 0-99 seen by every image, 100-199 by images 1 and 2 alone.
Scene SceneWithTwoViewPoints() {
  std::mt19937 rng(4);
  Scene scene = MakeScene(rng);
  KeepObservationsWhere(&scene,
                        [](uint64_t id, uint32_t image_id) { return id < 100 || image_id <= 2; });
  return scene;
}

TEST(BundleAdjustment, PointsSeenTwiceLeftOutWhereLongerTracksCoverTheirImages) {
  const Scene scene = SceneWithTwoViewPoints();
  BundleAdjustmentOptions options;
  options.min_observations_per_image = 100;
  ASSERT_EQ(options.min_track_length, 3);
  Reconstruction subset = PointsForBundleAdjustment(scene.reconstruction, options);
  EXPECT_EQ(subset.points3D.size(), 100u);
  for (const auto& [id, point] : subset.points3D) EXPECT_LT(id, 100u);
  for (const Point2D& point : subset.images.at(1).points2D) {
    EXPECT_TRUE(point.point3D_id == kInvalidPoint3DId || point.point3D_id < 100);
  }
  // Images 1 and 2 short of observations: every point they see, the two-view ones included.
  options.min_observations_per_image = 101;
  EXPECT_EQ(PointsForBundleAdjustment(scene.reconstruction, options).points3D.size(), 200u);
  options.min_observations_per_image = 100;
  options.min_track_length = 2;
  EXPECT_EQ(PointsForBundleAdjustment(scene.reconstruction, options).points3D.size(), 200u);
  options.min_track_length = 1;
  EXPECT_THROW(PointsForBundleAdjustment(scene.reconstruction, options), std::exception);
}

TEST(BundleAdjustment, ATwoImageModelKeepsEveryPoint) {
  std::mt19937 rng(6);
  Scene scene = MakeScene(rng);
  KeepObservationsWhere(&scene, [](uint64_t, uint32_t image_id) { return image_id <= 2; });
  for (uint32_t id = 3; id <= 10; ++id) scene.reconstruction.images.erase(id);
  BundleAdjustmentOptions options;
  EXPECT_EQ(PointsForBundleAdjustment(scene.reconstruction, options).points3D.size(), 200u);
  // The points seen twice do not count toward an image's floor: past it, still every point.
  options.min_observations_per_image = 50;
  EXPECT_EQ(PointsForBundleAdjustment(scene.reconstruction, options).points3D.size(), 200u);
}

}  // namespace
TEST(BundleAdjustment, LongTracksThinnedEvenlyKeepingTheirEnds) {
  std::mt19937 rng(5);
  const Scene scene = MakeScene(rng);  // every point seen by images 1-10
  BundleAdjustmentOptions options;
  options.max_observations_per_point = 4;
  const Reconstruction subset = PointsForBundleAdjustment(scene.reconstruction, options);
  ASSERT_EQ(subset.points3D.size(), 200u);
  for (const auto& [id, point] : subset.points3D) {
    std::vector<uint32_t> images;
    for (const TrackElement& e : point.track) images.push_back(e.image_id);
    EXPECT_EQ(images, (std::vector<uint32_t>{1, 4, 7, 10})) << "point " << id;
  }
  // The thinned observations are detached; the kept ones still name their point.
  for (const auto& [image_id, image] : subset.images) {
    const bool kept = image_id == 1 || image_id == 4 || image_id == 7 || image_id == 10;
    for (const Point2D& point : image.points2D) {
      EXPECT_EQ(point.point3D_id != kInvalidPoint3DId, kept) << "image " << image_id;
    }
  }
  options.max_observations_per_point = 1;
  EXPECT_THROW(PointsForBundleAdjustment(scene.reconstruction, options), std::exception);
}

TEST(BundleAdjustment, SolvesAgainWhenManyObservationsAreDetached) {
  std::mt19937 rng(11);
  Scene scene = MakeScene(rng);
  // Image 5's observations of 40 points (2% of all) are wrong by 25 px.
  for (size_t i = 0; i < 40; ++i) {
    scene.bearings[5][i] = (scene.bearings[5][i] + Eigen::Vector3d(0.05, 0, 0)).normalized();
  }
  BundleAdjustmentOptions options;
  options.refine_focal_length = options.refine_extra_params = false;
  options.min_filtered_fraction_to_solve_again = 0.01;
  Scene once = scene;
  const BundleAdjustmentSummary twice =
      BundleAdjust(scene.bearings, {{1, 500.0}}, &scene.reconstruction, options);
  EXPECT_EQ(twice.num_filtered_observations, 40);
  EXPECT_EQ(twice.num_solves, 2);
  EXPECT_LT(twice.final_rmse_px, 1e-3);
  options.min_filtered_fraction_to_solve_again = 0.05;
  const BundleAdjustmentSummary single =
      BundleAdjust(once.bearings, {{1, 500.0}}, &once.reconstruction, options);
  EXPECT_EQ(single.num_filtered_observations, 40);
  EXPECT_EQ(single.num_solves, 1);
}

namespace {

// Poses and points started far from the truth: a median reprojection error of several pixels, as
// from averaging's poses on sceaux_castle.
Scene FarStart(uint32_t seed) {
  std::mt19937 rng(seed);
  Scene scene = MakeScene(rng);
  std::normal_distribution<double> noise(0, 0.05);
  for (auto& [id, image] : scene.reconstruction.images) {
    if (id == 1) continue;
    image.cam_from_world.translation += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  }
  for (auto& [id, point] : scene.reconstruction.points3D)
    point.xyz += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  return scene;
}

// The median start error, in pixels at `focal_px`, of the scene's observations.
double MedianStartErrorPx(const Scene& scene, double focal_px) {
  std::vector<double> errors;
  for (const auto& [id, image] : scene.reconstruction.images) {
    for (size_t i = 0; i < image.points2D.size(); ++i) {
      const Eigen::Vector3d seen =
          image.cam_from_world * scene.reconstruction.points3D.at(image.points2D[i].point3D_id).xyz;
      const Eigen::Vector3d& bearing = scene.bearings.at(id)[i];
      errors.push_back(focal_px * (seen.hnormalized() - bearing.hnormalized()).norm());
    }
  }
  std::nth_element(errors.begin(), errors.begin() + errors.size() / 2, errors.end());
  return errors[errors.size() / 2];
}

// From a start whose median error exceeds the loss scale, BA first solves under a loss twice that
// median and then again at the loss scale; from a start within it, once.
TEST(BundleAdjustment, SolvesFirstUnderAWideLossFromAFarStart) {
  BundleAdjustmentOptions options;
  options.refine_focal_length = options.refine_extra_params = false;
  Scene far = FarStart(3);
  const double median_px = MedianStartErrorPx(far, 500.0);
  ASSERT_GT(median_px, 2 * options.loss_scale_px);
  Scene held = far;
  const BundleAdjustmentSummary wide =
      BundleAdjust(far.bearings, {{1, 500.0}}, &far.reconstruction, options);
  EXPECT_NEAR(wide.wide_start_loss_px, 2 * median_px, 1e-6 * median_px);
  EXPECT_EQ(wide.num_solves, 2);
  EXPECT_LT(wide.final_rmse_px, 1e-3);
  EXPECT_LT(LargestRotationErrorDeg(far), 1e-3);
  // Off: one solve at the loss scale.
  options.wide_start_loss_factor = 0;
  const BundleAdjustmentSummary narrow =
      BundleAdjust(held.bearings, {{1, 500.0}}, &held.reconstruction, options);
  EXPECT_EQ(narrow.wide_start_loss_px, 0);
  EXPECT_EQ(narrow.num_solves, 1);
  // From the solution (median error 0): one solve at the loss scale.
  options.wide_start_loss_factor = 2;
  const BundleAdjustmentSummary again =
      BundleAdjust(far.bearings, {{1, 500.0}}, &far.reconstruction, options);
  EXPECT_EQ(again.wide_start_loss_px, 0);
  EXPECT_EQ(again.num_solves, 1);
}

}  // namespace
}  // namespace ramap
