// The summary's per-camera intrinsics (as given, as the view graph estimated them, as written) and
// the images left out of every model with their reasons.
#include "ramap/mapper/mapper_summary.h"

#include <gtest/gtest.h>

#include "test_support.h"

namespace ramap {
namespace {

// Cameras 1 (a guess, SIMPLE_RADIAL) and 2 (given, PINHOLE), images 1-4 named a.png to d.png.
FeatureDatabase TwoCameraDatabase() {
  FeatureDatabase database;
  Camera guessed;
  guessed.camera_id = 1;
  guessed.model = CameraModel::kSimpleRadial;
  guessed.width = 640;
  guessed.height = 480;
  guessed.params = {768, 320, 240, 0};
  database.cameras[1] = guessed;
  Camera given = test::VgaPinholeCamera(500, 505);
  given.camera_id = 2;
  given.has_prior_focal_length = true;
  database.cameras[2] = given;
  const std::vector<std::string> names = {"a.png", "b.png", "c.png", "d.png"};
  for (uint32_t id = 1; id <= 4; ++id) {
    database.images[id].image_id = id;
    database.images[id].name = names[id - 1];
    database.images[id].camera_id = id <= 2 ? 1 : 2;
  }
  return database;
}

Reconstruction ModelWith(const std::map<uint32_t, Camera>& cameras,
                         const std::vector<uint32_t>& image_ids) {
  Reconstruction model;
  model.cameras = cameras;
  for (const uint32_t id : image_ids) model.images[id].image_id = id;
  return model;
}

TEST(MapperSummary, EachCameraAsGivenAsEstimatedAndAsWritten) {
  const FeatureDatabase database = TwoCameraDatabase();
  ViewGraphCalibrationSummary calibration;
  CameraCalibration estimate;
  estimate.camera_id = 1;
  estimate.prior_focal_px = 768;
  estimate.estimated_focal_px = 512;
  estimate.estimated = true;
  calibration.cameras.push_back(estimate);

  // Camera 1 refined (a distortion model added) in the largest model, camera 2 only in the
  // second; camera 1 also in the second, with other values that must not be taken.
  Camera refined;
  refined.camera_id = 1;
  refined.model = CameraModel::kRadial;
  refined.params = {510, 321, 239, -0.01, 0.001};
  Camera other = refined;
  other.params[0] = 999;
  Camera given = database.cameras.at(2);
  given.params = {501, 504, 320, 240};
  const std::vector<Reconstruction> models = {ModelWith({{1, refined}}, {1, 2}),
                                              ModelWith({{1, other}, {2, given}}, {3})};

  const std::vector<CameraIntrinsicsSummary> cameras =
      SummariseIntrinsics(database, calibration, models);
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_EQ(cameras[0].camera_id, 1u);
  EXPECT_EQ(cameras[0].model, "SIMPLE_RADIAL");
  EXPECT_FALSE(cameras[0].prior_focal_length_known);
  EXPECT_EQ(cameras[0].prior_params, database.cameras.at(1).params);
  EXPECT_EQ(cameras[0].view_graph.camera_id, 1u);
  EXPECT_EQ(cameras[0].view_graph.estimated_focal_px, 512.0);
  EXPECT_EQ(cameras[0].final_params, refined.params);
  EXPECT_EQ(cameras[0].final_model, "RADIAL");

  EXPECT_EQ(cameras[1].camera_id, 2u);
  EXPECT_EQ(cameras[1].model, "PINHOLE");
  EXPECT_TRUE(cameras[1].prior_focal_length_known);
  EXPECT_EQ(cameras[1].view_graph.camera_id, 0u);  // not calibrated from the view graph
  EXPECT_EQ(cameras[1].final_params, given.params);
  EXPECT_EQ(cameras[1].final_model, "PINHOLE");
}

TEST(MapperSummary, ACameraNoModelHoldsHasNoFinalParameters) {
  const FeatureDatabase database = TwoCameraDatabase();
  const std::vector<CameraIntrinsicsSummary> cameras =
      SummariseIntrinsics(database, {}, {ModelWith({{1, database.cameras.at(1)}}, {1, 2})});
  ASSERT_EQ(cameras.size(), 2u);
  EXPECT_FALSE(cameras[0].final_params.empty());
  EXPECT_TRUE(cameras[1].final_params.empty());
  EXPECT_TRUE(cameras[1].final_model.empty());
}

TEST(MapperSummary, UnregisteredImagesAreListedWithTheirReasons) {
  const FeatureDatabase database = TwoCameraDatabase();
  // Image 1's reason was set by an early stage, then a later one registered it after all.
  std::map<uint32_t, std::string> reasons = {
      {1, "no rotation"}, {2, "no relative pose"}, {4, "component of 1 image"}};
  MapperSummary summary;
  ListUnregisteredImages(database, {ModelWith({}, {1, 3}), ModelWith({}, {})}, &reasons, &summary);
  EXPECT_EQ(summary.num_registered_images, 2);
  ASSERT_EQ(summary.dropped_images.size(), 2u);
  EXPECT_EQ(summary.dropped_images[0].what, "b.png");
  EXPECT_EQ(summary.dropped_images[0].reason, "no relative pose");
  EXPECT_EQ(summary.dropped_images[1].what, "d.png");
  EXPECT_EQ(summary.dropped_images[1].reason, "component of 1 image");
  // The registered image's stale reason is gone.
  EXPECT_FALSE(reasons.count(1));
}

}  // namespace
}  // namespace ramap
