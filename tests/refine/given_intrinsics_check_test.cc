// Intrinsics a user gives (prior_focal_length 1): bundle adjustment keeps them unless the data
// prove them wrong, adds radial distortion to a pinhole camera whose residuals call for it, and
// refines identical cameras as one. Synthetic scenes with exact truth.
#include "ramap/refine/given_intrinsics_check.h"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "ramap/eval/pose_metrics.h"
#include "ramap/mapper/mapper.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// The collection of test::NoisyCollection through `camera`.
SyntheticSceneOptions Collection(uint64_t seed, const Camera& camera) {
  SyntheticSceneOptions options = test::NoisyCollection(seed);
  options.camera = camera;
  return options;
}

Camera Pinhole(double focal_px) { return test::VgaPinholeCamera(focal_px, focal_px); }

// The database as `reconstruct --ImageReader.camera_params` writes it: one camera per image, each
// a copy of `given`, marked known.
FeatureDatabase OneGivenCameraPerImage(FeatureDatabase database, const Camera& given) {
  database.cameras.clear();
  for (auto& [image_id, image] : database.images) {
    Camera camera = given;
    camera.camera_id = image_id;
    camera.has_prior_focal_length = true;
    database.cameras[image_id] = camera;
    image.camera_id = image_id;
  }
  return database;
}

const GivenIntrinsicsTest& OnlyTest(const MapperResult& result) {
  const std::vector<GivenIntrinsicsTest>& groups =
      result.summary.components.at(0).given_intrinsics_test.groups;
  EXPECT_EQ(groups.size(), 1u);
  return groups.at(0);
}

TEST(GivenIntrinsics, TrueCalibrationOneCameraPerImageIsKept) {
  const SyntheticScene scene = BuildSyntheticScene(Collection(7, Pinhole(500)));
  const FeatureDatabase database = OneGivenCameraPerImage(scene.database, Pinhole(500));
  const MapperResult result = RunMapper(database, MapperOptions(), "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  ASSERT_EQ(model.images.size(), scene.ground_truth.images.size());
  for (const auto& [camera_id, camera] : model.cameras) {
    EXPECT_EQ(camera.model, CameraModel::kPinhole);
    EXPECT_EQ(camera.params, Pinhole(500).params) << "camera " << camera_id;
  }
  const GivenIntrinsicsTest& test = OnlyTest(result);
  EXPECT_EQ(test.camera_ids.size(), database.cameras.size()) << "identical cameras as one";
  EXPECT_TRUE(test.distortion_tried);
  EXPECT_FALSE(test.focal_accepted);
  EXPECT_FALSE(test.distortion_accepted);
  EXPECT_LT(std::abs(test.freed_focal_px / 500.0 - 1.0), 0.01);
  EXPECT_TRUE(result.summary.components.at(0).given_intrinsics_test.poses_adjusted)
      << "the test runs before BA, which starts from the poses of its subset";
  EXPECT_LT(test::EvaluateAgainstTruth(model, scene).rotation_error_median_deg, 0.1);
}

TEST(GivenIntrinsics, FocalLengthTenPercentOffIsProvenWrong) {
  const SyntheticScene scene = BuildSyntheticScene(Collection(7, Pinhole(500)));
  const FeatureDatabase database = OneGivenCameraPerImage(scene.database, Pinhole(550));
  const MapperResult result = RunMapper(database, MapperOptions(), "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  for (const auto& [camera_id, camera] : model.cameras) {
    EXPECT_EQ(camera.model, CameraModel::kPinhole) << "no distortion where none is needed";
    EXPECT_NEAR(camera.params[0], 500.0, 5.0) << "camera " << camera_id;
  }
  EXPECT_LT(test::EvaluateAgainstTruth(model, scene).rotation_error_median_deg, 0.1);
}

// The test decides on a subset of the points; the full BA then refines the focal length it proved
// wrong on all of them, and the pipeline does not average again through it.
TEST(GivenIntrinsics, FocalLengthProvenWrongIsRefinedByTheFullAdjustmentInOnePass) {
  const SyntheticScene scene = BuildSyntheticScene(Collection(7, Pinhole(500)));
  const FeatureDatabase database = OneGivenCameraPerImage(scene.database, Pinhole(600));
  MapperOptions options;
  options.given_intrinsics_test.num_points = 300;  // of the scene's 3000
  std::ostringstream progress;
  const MapperResult result = RunMapper(database, options, "synthetic", &progress);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  const GivenIntrinsicsTest& test = OnlyTest(result);
  ASSERT_TRUE(test.focal_accepted);
  EXPECT_EQ(progress.str().find("averaging again"), std::string::npos) << progress.str();
  for (const auto& [camera_id, camera] : model.cameras) {
    EXPECT_NE(camera.params[0], test.freed_focal_px) << "camera " << camera_id << ": not refined";
    EXPECT_NEAR(camera.params[0], 500.0, 2.5) << "camera " << camera_id;
  }
  EXPECT_LT(test::EvaluateAgainstTruth(model, scene).rotation_error_median_deg, 0.1);
}

// A lens with k1 = -0.15, and the database that gives it as a plain PINHOLE camera.
SyntheticScene RadialLensScene() {
  Camera lens;
  lens.model = CameraModel::kSimpleRadial;
  lens.width = 640;
  lens.height = 480;
  lens.params = {500.0, 320.0, 240.0, -0.15};
  SyntheticScene scene = BuildSyntheticScene(Collection(13, lens));
  for (auto& [camera_id, camera] : scene.database.cameras) {
    camera = Pinhole(500);
    camera.camera_id = camera_id;
    camera.has_prior_focal_length = true;
  }
  return scene;
}

TEST(GivenIntrinsics, PinholeCameraWithRadialDistortionGetsItsK1) {
  const SyntheticScene scene = RadialLensScene();
  const MapperResult result = RunMapper(scene.database, MapperOptions(), "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  ASSERT_EQ(model.images.size(), scene.ground_truth.images.size());
  const Camera& camera = model.cameras.at(1);
  ASSERT_EQ(camera.model, CameraModel::kSimpleRadial);
  EXPECT_EQ(camera.params[0], 500.0) << "the given focal length kept";
  EXPECT_NEAR(camera.params[3], -0.15, 0.01);
  const GivenIntrinsicsTest& test = OnlyTest(result);
  EXPECT_TRUE(test.distortion_accepted);
  EXPECT_FALSE(test.focal_accepted);
  EXPECT_EQ(test.final_model, "SIMPLE_RADIAL");
  EXPECT_LT(test::EvaluateAgainstTruth(model, scene).rotation_error_median_deg, 0.1);
}

TEST(GivenIntrinsics, SecondRefinementRoundThroughTheFoundDistortion) {
  const SyntheticScene scene = RadialLensScene();
  MapperOptions options;
  options.num_refinement_rounds = 2;
  std::ostringstream progress;
  const MapperResult result = RunMapper(scene.database, options, "synthetic", &progress);
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const Reconstruction& model = result.reconstructions[0];
  ASSERT_EQ(model.images.size(), scene.ground_truth.images.size());
  EXPECT_NE(progress.str().find("round 2: "), std::string::npos) << progress.str();
  EXPECT_NEAR(model.cameras.at(1).params[3], -0.15, 0.01);
  EXPECT_LT(test::EvaluateAgainstTruth(model, scene).rotation_error_median_deg, 0.1);
}

TEST(GivenIntrinsics, TestOffLeavesTheGivenPinholeCamera) {
  Camera lens = Pinhole(500);
  const SyntheticScene scene = BuildSyntheticScene(Collection(7, lens));
  const FeatureDatabase database = OneGivenCameraPerImage(scene.database, Pinhole(550));
  MapperOptions options;
  options.given_intrinsics_test.enable = false;
  const MapperResult result = RunMapper(database, options, "synthetic");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  for (const auto& [camera_id, camera] : result.reconstructions[0].cameras)
    EXPECT_EQ(camera.params, Pinhole(550).params) << "camera " << camera_id;
  EXPECT_TRUE(result.summary.components.at(0).given_intrinsics_test.groups.empty());
}

}  // namespace
}  // namespace ramap
