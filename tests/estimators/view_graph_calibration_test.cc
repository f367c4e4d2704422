// Self-calibration of unknown focal lengths: the view-graph estimate from fundamental matrices,
// then bundle adjustment with the intrinsics, on synthetic scenes with exact truth.
#include "ramap/estimators/view_graph_calibration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>

#include "ramap/eval/pose_metrics.h"
#include "ramap/geometry/camera_distortion.h"
#include "ramap/geometry/camera_projection.h"
#include "ramap/mapper/mapper.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// The database as a user without a calibration gives it: the focal lengths scaled by `factor`
// and marked unknown.
FeatureDatabase WithUnknownFocalLengths(FeatureDatabase database, double factor) {
  for (auto& [camera_id, camera] : database.cameras) {
    camera.params[0] *= factor;
    if (camera.model == CameraModel::kPinhole || camera.model == CameraModel::kOpenCV) {
      camera.params[1] *= factor;
    }
    camera.has_prior_focal_length = false;
  }
  return database;
}

double RelativeError(double estimate, double truth) { return std::abs(estimate / truth - 1.0); }

TEST(ViewGraphCalibration, EssentialMatrixCostVanishesAtTheTrueCalibration) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(1));
  const Eigen::Matrix3d K = CalibrationMatrix(scene.database.cameras.at(1));
  const Eigen::Matrix3d K_off = CalibrationMatrix(scene.database.cameras.at(1), 1.3);
  std::vector<double> off_costs;
  for (const auto& [pair_id, geometry] : scene.database.two_view_geometries) {
    // Zero but for rounding: closed-form eigenvalues of M^T M leave a few 1e-9, six orders of
    // magnitude below the costs of a focal length 30% off.
    EXPECT_LT(EssentialMatrixCost(geometry.F, K, K), 1e-8);
    off_costs.push_back(EssentialMatrixCost(geometry.F, K_off, K_off));
  }
  ASSERT_GT(off_costs.size(), 20u);
  // A focal length 30% off leaves most pairs far from an essential matrix.
  std::sort(off_costs.begin(), off_costs.end());
  EXPECT_GT(off_costs[off_costs.size() / 2], 1e-3);
}

// Maps `database` with bundle adjustment and expects every image of `scene` registered, camera
// `camera_id`'s focal length within 1% of `truth`, rotations within 0.2 deg and positions within
// 1% of the scene's extent.
MapperResult ExpectRecoveredByBundleAdjustment(const FeatureDatabase& database,
                                               const SyntheticScene& scene, uint32_t camera_id,
                                               double truth) {
  MapperOptions options;
  options.refine = true;
  MapperResult result = RunMapper(database, options, "synthetic");
  EXPECT_EQ(result.reconstructions.size(), 1u);
  if (result.reconstructions.empty()) return result;
  const Reconstruction& model = result.reconstructions[0];
  EXPECT_EQ(model.images.size(), scene.ground_truth.images.size());
  EXPECT_LT(RelativeError(model.cameras.at(camera_id).params[0], truth), 0.01)
      << "after BA: " << model.cameras.at(camera_id).params[0] << " for " << truth;
  const PoseEvaluation evaluation = test::EvaluateAgainstTruth(model, scene);
  EXPECT_LT(evaluation.rotation_error_median_deg, 0.2);
  EXPECT_LT(evaluation.ate_rmse_over_extent, 0.01);
  return result;
}

class FocalPrior : public ::testing::TestWithParam<double> {};

TEST_P(FocalPrior, RecoveredFromTheViewGraphAndByBundleAdjustment) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(7));
  const double truth = scene.database.cameras.at(1).params[0];
  const FeatureDatabase database = WithUnknownFocalLengths(scene.database, GetParam());

  std::map<uint32_t, Camera> cameras = database.cameras;
  const ViewGraphCalibrationSummary calibration =
      CalibrateFocalLengths(database, ViewGraphCalibrationOptions(), &cameras);
  ASSERT_EQ(calibration.cameras.size(), 1u);
  ASSERT_TRUE(calibration.cameras[0].estimated) << calibration.cameras[0].problem;
  EXPECT_LT(RelativeError(cameras.at(1).params[0], truth), 0.01)
      << "view graph: " << cameras.at(1).params[0] << " for " << truth;

  const MapperResult result = ExpectRecoveredByBundleAdjustment(database, scene, 1, truth);
  ASSERT_EQ(result.summary.cameras.size(), 1u);
  EXPECT_TRUE(result.summary.cameras[0].view_graph.estimated);
}

INSTANTIATE_TEST_SUITE_P(PriorOff, FocalPrior, ::testing::Values(1.3, 0.7),
                         [](const ::testing::TestParamInfo<double>& info) {
                           return info.param > 1 ? std::string("ThirtyPercentHigh")
                                                 : std::string("ThirtyPercentLow");
                         });

TEST(ViewGraphCalibration, TwoCamerasWithDifferentFocalLengths) {
  SyntheticSceneOptions options = test::NoisyCollection(11);
  options.num_images = 20;
  Camera second = options.camera;
  second.params[0] *= 1.6;
  second.params[1] *= 1.6;
  options.second_camera = second;
  const SyntheticScene scene = BuildSyntheticScene(options);
  ASSERT_EQ(scene.database.cameras.size(), 2u);
  const FeatureDatabase database = WithUnknownFocalLengths(scene.database, 1.25);

  MapperOptions mapper;
  mapper.refine = true;
  const MapperResult result = RunMapper(database, mapper, "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  for (const uint32_t camera_id : {1u, 2u}) {
    const double truth = scene.database.cameras.at(camera_id).params[0];
    EXPECT_LT(RelativeError(result.reconstructions[0].cameras.at(camera_id).params[0], truth), 0.01)
        << "camera " << camera_id;
  }
}

// COLMAP's default: one camera per image, each with the same guess. They are estimated and
// refined as one, so the focal length is the same in every image and as good as a shared camera's.
TEST(ViewGraphCalibration, OneGuessedCameraPerImageCalibratedAsOne) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(7));
  const double truth = scene.database.cameras.at(1).params[0];
  FeatureDatabase database = WithUnknownFocalLengths(scene.database, 1.3);
  const Camera guess = database.cameras.at(1);
  database.cameras.clear();
  for (auto& [image_id, image] : database.images) {
    database.cameras[image_id] = guess;
    database.cameras[image_id].camera_id = image_id;
    image.camera_id = image_id;
  }
  const MapperResult result = RunMapper(database, MapperOptions(), "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  ASSERT_EQ(model.cameras.size(), database.cameras.size());
  for (const auto& [camera_id, camera] : model.cameras) {
    EXPECT_EQ(camera.params, model.cameras.begin()->second.params) << "camera " << camera_id;
    EXPECT_LT(RelativeError(camera.params[0], truth), 0.01) << "camera " << camera_id;
  }
  ASSERT_EQ(result.summary.cameras.size(), database.cameras.size());
  for (const CameraIntrinsicsSummary& camera : result.summary.cameras)
    EXPECT_TRUE(camera.view_graph.estimated) << "camera " << camera.camera_id;
}

// A collection through a SIMPLE_RADIAL camera (f 500, k -0.1) with `num_points` landmarks.
SyntheticScene RadialCameraScene(int num_points) {
  SyntheticSceneOptions options = test::NoisyCollection(13);
  options.num_points = num_points;
  Camera camera;
  camera.model = CameraModel::kSimpleRadial;
  camera.width = 640;
  camera.height = 480;
  camera.params = {500.0, 320.0, 240.0, -0.1};
  options.camera = camera;
  return BuildSyntheticScene(options);
}

// `scene`'s database with COLMAP's defaults for an unknown camera: 1.2 x the longest side, k = 0.
FeatureDatabase WithColmapsGuess(const SyntheticScene& scene) {
  FeatureDatabase database = scene.database;
  Camera& guess = database.cameras.at(1);
  guess.params = {1.2 * 640, 320.0, 240.0, 0.0};
  guess.has_prior_focal_length = false;
  return database;
}

TEST(ViewGraphCalibration, RadialDistortionRecoveredByBundleAdjustment) {
  const SyntheticScene scene = RadialCameraScene(test::NoisyCollection(13).num_points);
  const FeatureDatabase database = WithColmapsGuess(scene);

  MapperOptions mapper;
  mapper.refine = true;
  const MapperResult result = RunMapper(database, mapper, "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const std::vector<double>& refined = result.reconstructions[0].cameras.at(1).params;
  EXPECT_LT(RelativeError(refined[0], 500.0), 0.01) << refined[0];
  EXPECT_NEAR(refined[3], -0.1, 0.005);
  EXPECT_EQ(result.reconstructions[0].images.size(), scene.ground_truth.images.size());
}

// The subset of the default 2000 points finds the focal length and k, and the full BA holds them
// (calibration_subset_only) or refines them again: both end at the truth, with the poses within
// noise. Held through the view graph's bearings instead of the subset's (the undistortion left
// out), the poses here were ten times further off (rotations 0.18 deg, positions 0.3% of the
// extent). A subset of a few hundred points leaves k 0.02 off here: the default is what is held.
TEST(ViewGraphCalibration, IntrinsicsTheSubsetFoundAreHeldByTheFullAdjustment) {
  const SyntheticScene scene = RadialCameraScene(6000);  // over twice the subset, so that it runs
  const FeatureDatabase database = WithColmapsGuess(scene);
  for (const bool held : {true, false}) {
    SCOPED_TRACE(held ? "held" : "refined again");
    MapperOptions mapper;
    mapper.refine = true;
    mapper.calibration_subset_only = held;
    // One pass: a second one would average through the written intrinsics and hide what was held.
    mapper.max_focal_change_in_bundle_adjustment = 0;
    // The scene's principal point is exactly COLMAP's guess: refined, it only adds noise (rotations
    // 0.15 deg off instead of 0.03).
    mapper.bundle_adjustment.refine_guessed_principal_point = false;
    const MapperResult result = RunMapper(database, mapper, "synthetic");
    ASSERT_EQ(result.reconstructions.size(), 1u);
    const Reconstruction& model = result.reconstructions[0];
    ASSERT_GT(model.points3D.size(), 2u * mapper.calibration_num_points);
    const std::vector<double>& refined = model.cameras.at(1).params;
    EXPECT_LT(RelativeError(refined[0], 500.0), 0.01) << refined[0];
    EXPECT_NEAR(refined[3], -0.1, 0.005);
    const PoseEvaluation evaluation = test::EvaluateAgainstTruth(model, scene);
    EXPECT_EQ(evaluation.num_registered, static_cast<int>(scene.ground_truth.images.size()));
    EXPECT_LT(evaluation.rotation_error_median_deg, 0.05);
    EXPECT_LT(evaluation.ate_rmse_over_extent, 1e-3);
  }
}

// Without the final BA (Mapper.refine 0), the subset's adjustment alone calibrates the camera and
// places the images at the full BA's accuracy, adjusting no more than the subset's points;
// averaging alone, through the view graph's focal length and no k, is far off.
TEST(ViewGraphCalibration, SubsetAdjustmentCalibratesWithoutTheFinalBundleAdjustment) {
  const SyntheticScene scene = RadialCameraScene(6000);
  const FeatureDatabase database = WithColmapsGuess(scene);
  std::map<bool, PoseEvaluation> evaluations;
  for (const bool subset : {false, true}) {
    SCOPED_TRACE(subset ? "subset adjustment" : "averaging alone");
    MapperOptions mapper;
    mapper.refine = false;
    mapper.subset_adjustment = subset;
    mapper.bundle_adjustment.refine_guessed_principal_point = false;  // as above
    const MapperResult result = RunMapper(database, mapper, "synthetic");
    ASSERT_EQ(result.reconstructions.size(), 1u);
    const Reconstruction& model = result.reconstructions[0];
    evaluations[subset] = test::EvaluateAgainstTruth(model, scene);
    EXPECT_EQ(evaluations[subset].num_registered,
              static_cast<int>(scene.ground_truth.images.size()));
    const BundleAdjustmentSummary& ba = result.summary.components[0].bundle_adjustment;
    if (!subset) {
      EXPECT_EQ(ba.num_points, 0);
      continue;
    }
    EXPECT_GT(ba.num_points, 0);
    EXPECT_LE(ba.num_points, mapper.calibration_num_points * 11 / 10);
    EXPECT_GT(model.points3D.size(), 2u * mapper.calibration_num_points);
    const std::vector<double>& refined = model.cameras.at(1).params;
    EXPECT_LT(RelativeError(refined[0], 500.0), 0.01) << refined[0];
    EXPECT_NEAR(refined[3], -0.1, 0.005);
  }
  std::printf("rotation error median: averaging alone %.3f deg, subset adjustment %.3f deg\n",
              evaluations[false].rotation_error_median_deg,
              evaluations[true].rotation_error_median_deg);
  EXPECT_LT(evaluations[true].rotation_error_median_deg, 0.05);
  EXPECT_LT(evaluations[true].ate_rmse_over_extent, 1e-3);
  EXPECT_GT(evaluations[false].rotation_error_median_deg,
            4 * evaluations[true].rotation_error_median_deg);
}

// The bundle adjustments a mapper's progress log records (their stage lines).
int CountBundleAdjustments(const std::string& log) {
  std::istringstream lines(log);
  int count = 0;
  for (std::string line; std::getline(lines, line);)
    count += line.rfind("[ramap] bundle adjustment  ", 0) == 0;
  return count;
}

// The number `log` prints first between `before` and `after` (-1: none).
int LoggedCount(const std::string& log, const std::string& before, const std::string& after) {
  const size_t start = log.find(before);
  if (start == std::string::npos) return -1;
  const size_t end = log.find(after, start + before.size());
  if (end == std::string::npos) return -1;
  try {
    return std::stoi(log.substr(start + before.size(), end - start - before.size()));
  } catch (const std::exception&) {
    return -1;
  }
}

// Views fixating the origin from one distance: every pair's optical axes meet at equal distances,
// where F leaves the focal length free. The elevations vary (not one orbit, a critical motion for
// BA too), so the views together fix it.
std::vector<Rigid3d> FixatingViews(int num_views, double distance) {
  std::vector<Rigid3d> poses;
  for (int i = 0; i < num_views; ++i) {
    const double azimuth = 2.0 * M_PI * i / num_views;
    const double elevation = 0.35 * std::sin(4.0 * azimuth);
    const Eigen::Vector3d center =
        distance * Eigen::Vector3d(std::cos(elevation) * std::sin(azimuth), -std::sin(elevation),
                                   std::cos(elevation) * std::cos(azimuth));
    const Eigen::Vector3d z = -center.normalized();
    const Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z).normalized();
    Eigen::Matrix3d rotation;
    rotation << x.transpose(), z.cross(x).transpose(), z.transpose();
    const Eigen::Quaterniond q(rotation);
    poses.emplace_back(q, -(q * center));
  }
  return poses;
}

TEST(ViewGraphCalibration, FocalLengthTheViewGraphCannotFixFoundByACalibrationPass) {
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kGiven;
  options.given_poses = FixatingViews(36, 10.0);
  options.num_images = 0;
  options.overlap = 6;
  options.num_points = 3000;
  options.min_depth = 7.0;
  options.max_depth = 13.0;
  options.seed = 17;
  const SyntheticScene scene = BuildSyntheticScene(options);
  const double truth = scene.database.cameras.at(1).params[0];
  const FeatureDatabase database = WithUnknownFocalLengths(scene.database, 0.5);

  MapperOptions mapper;
  mapper.refine = true;
  // A subset of fewer than half the scene's 3400 tracks, so that the subset's calibration runs;
  // the calibration pass works on fewer still.
  mapper.calibration_num_points = 1000;
  mapper.calibration_pass_num_tracks = 400;
  std::ostringstream progress;
  const MapperResult result = RunMapper(database, mapper, "synthetic", &progress);
  // The first pass ends with its calibration subset: the second averages again and keeps none of
  // its poses, so no other BA runs before it.
  const std::string log = progress.str();
  const std::string first_pass = log.substr(0, log.find("averaging again"));
  ASSERT_NE(first_pass.size(), log.size()) << log;
  EXPECT_EQ(CountBundleAdjustments(first_pass), 1) << first_pass;
  EXPECT_EQ(CountBundleAdjustments(log), 3) << log;  // then the subset and the full BA
  const std::string second_pass = log.substr(first_pass.size());
  EXPECT_EQ(LoggedCount(first_pass, "and ", " tracks"), 400) << first_pass;
  EXPECT_GT(LoggedCount(second_pass, "and ", " tracks"), 1000) << second_pass;
  // Each image keeps at least 50 observations: more points than the budget, fewer than the second
  // pass's subset.
  EXPECT_LT(LoggedCount(first_pass, "on a subset: ", " points"), 1000) << first_pass;
  EXPECT_GE(LoggedCount(second_pass, "on a subset: ", " points"), 1000) << second_pass;
  ASSERT_EQ(result.summary.cameras.size(), 1u);
  const CameraCalibration& view_graph = result.summary.cameras[0].view_graph;
  EXPECT_FALSE(view_graph.estimated) << view_graph.estimated_focal_px;
  EXPECT_NE(view_graph.problem.find("undetermined"), std::string::npos) << view_graph.problem;
  // The cost's rise is said as a rise ("only 4% above its minimum", or "no higher than at the
  // estimate"), never as a negative share.
  EXPECT_EQ(view_graph.problem.find("-"), std::string::npos) << view_graph.problem;
  EXPECT_NE(view_graph.problem.find("the cost 20% away is "), std::string::npos)
      << view_graph.problem;
  EXPECT_TRUE(result.summary.calibration_pass);
  EXPECT_EQ(result.summary.num_averaging_passes, 2);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  EXPECT_EQ(model.images.size(), scene.ground_truth.images.size());
  EXPECT_LT(RelativeError(model.cameras.at(1).params[0], truth), 0.01)
      << model.cameras.at(1).params[0] << " for " << truth;
  // The final BA adjusts every point, not the calibration pass's subset.
  EXPECT_GT(result.summary.components[0].bundle_adjustment.num_points,
            mapper.calibration_num_points);
}

TEST(ViewGraphCalibration, CameraSeenOnlyInPureRotationsKeepsItsPrior) {
  SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(3));
  FeatureDatabase database = WithUnknownFocalLengths(scene.database, 1.3);
  for (auto& [pair_id, geometry] : database.two_view_geometries) {
    geometry.config = TwoViewConfig::kPanoramic;
  }
  std::map<uint32_t, Camera> cameras = database.cameras;
  const ViewGraphCalibrationSummary calibration =
      CalibrateFocalLengths(database, ViewGraphCalibrationOptions(), &cameras);
  ASSERT_EQ(calibration.cameras.size(), 1u);
  EXPECT_FALSE(calibration.cameras[0].estimated);
  EXPECT_NE(calibration.cameras[0].problem.find("pure rotations"), std::string::npos)
      << calibration.cameras[0].problem;
  EXPECT_EQ(cameras.at(1).params, database.cameras.at(1).params);
}

TEST(ViewGraphCalibration, BadFundamentalMatricesFallBackToThePrior) {
  SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(5));
  FeatureDatabase database = WithUnknownFocalLengths(scene.database, 1.3);
  int k = 0;
  for (auto& [pair_id, geometry] : database.two_view_geometries) {
    // NaN in some, and random matrices (no focal length fits them) in the others.
    if (k++ % 3 == 0) {
      geometry.F(0, 0) = std::nan("");
    } else {
      geometry.F = Eigen::Matrix3d::Random();
    }
  }
  std::map<uint32_t, Camera> cameras = database.cameras;
  const ViewGraphCalibrationSummary calibration =
      CalibrateFocalLengths(database, ViewGraphCalibrationOptions(), &cameras);
  ASSERT_EQ(calibration.cameras.size(), 1u);
  EXPECT_FALSE(calibration.cameras[0].estimated);
  EXPECT_FALSE(calibration.cameras[0].problem.empty());
  EXPECT_EQ(cameras.at(1).params, database.cameras.at(1).params);
}

// A focal length given 10% off is confirmed by the pairs (within given_focal_tolerance): it is
// kept as given, for the test of given intrinsics after averaging to judge. Untested where the
// options say so.
TEST(ViewGraphCalibration, GivenFocalLengthsNearTheEstimateAreKept) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(2));
  FeatureDatabase database = scene.database;
  database.cameras.at(1).has_prior_focal_length = true;
  database.cameras.at(1).params[0] *= 1.1;
  database.cameras.at(1).params[1] *= 1.1;
  std::map<uint32_t, Camera> cameras = database.cameras;
  const ViewGraphCalibrationSummary calibration =
      CalibrateFocalLengths(database, ViewGraphCalibrationOptions(), &cameras);
  ASSERT_EQ(calibration.cameras.size(), 1u);
  EXPECT_EQ(calibration.cameras[0].outcome, FocalOutcome::kConfirmed);
  EXPECT_TRUE(calibration.cameras[0].given);
  EXPECT_FALSE(calibration.cameras[0].estimated);
  EXPECT_EQ(cameras.at(1).params, database.cameras.at(1).params);
  EXPECT_TRUE(cameras.at(1).has_prior_focal_length);

  ViewGraphCalibrationOptions untested;
  untested.test_given_focal_lengths = false;
  EXPECT_TRUE(CalibrateFocalLengths(database, untested, &cameras).cameras.empty());
}

// An internet collection's camera: two photos whose EXIF focal length is 10x too long (a crop
// that kept its tags, say), among photos whose EXIF is right. The pairs prove the given value
// wrong; the view graph's estimate replaces it (from a start far outside the 0.25-4x of a prior
// that a factor range would search), and bundle adjustment refines it as a guess, not held. The
// views all look at one object, as a landmark's photos do: the pairs fix the ratios of the focal
// lengths but hardly their common scale, so the two-image camera would drag the right one along
// (to 617 px from 500) unless the given values' consensus sets the scale.
TEST(ViewGraphCalibration, TwoImageCameraGetsItsFocalLengthFromAnExifStartTenTimesOff) {
  const SyntheticScene scene = BuildSyntheticScene(test::NoisyCollection(17));
  const double truth = scene.database.cameras.at(1).params[0];
  FeatureDatabase database = scene.database;
  database.cameras.at(1).has_prior_focal_length = true;
  Camera exif = database.cameras.at(1);
  exif.camera_id = 2;
  exif.params[0] *= 10;
  if (!HasSingleFocalLength(exif.model)) exif.params[1] *= 10;
  database.cameras[2] = exif;
  for (const uint32_t image_id : {1u, 2u}) database.images.at(image_id).camera_id = 2;

  std::map<uint32_t, Camera> cameras = database.cameras;
  const ViewGraphCalibrationSummary calibration =
      CalibrateFocalLengths(database, ViewGraphCalibrationOptions(), &cameras);
  ASSERT_EQ(calibration.cameras.size(), 2u);
  EXPECT_EQ(calibration.cameras[0].outcome, FocalOutcome::kConfirmed);
  EXPECT_EQ(calibration.cameras[1].outcome, FocalOutcome::kDisproved)
      << calibration.cameras[1].problem;
  EXPECT_LT(RelativeError(cameras.at(2).params[0], truth), 0.02)
      << "view graph: " << cameras.at(2).params[0] << " for " << truth;
  EXPECT_FALSE(cameras.at(2).has_prior_focal_length);

  ExpectRecoveredByBundleAdjustment(database, scene, 2, truth);
}

}  // namespace
}  // namespace ramap
