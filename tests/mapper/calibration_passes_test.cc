#include "ramap/mapper/calibration_passes.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

ViewGraphCalibrationSummary OneCameraTheViewGraphCouldNotEstimate() {
  ViewGraphCalibrationSummary calibration;
  CameraCalibration camera;
  camera.camera_id = 1;
  camera.prior_focal_px = 768.0;
  camera.estimated = false;
  calibration.cameras.push_back(camera);
  return calibration;
}

TEST(CalibrationPasses, ACalibrationPassWorksOnItsOwnBudgets) {
  MapperOptions options;
  options.refine = true;
  const FirstPass first = FirstPassOptions(options, OneCameraTheViewGraphCouldNotEstimate());
  const MapperOptions& pass = first.options;
  EXPECT_TRUE(first.calibration_pass);
  const int budget = options.calibration_pass_num_tracks;
  ASSERT_GT(budget, 0);
  ASSERT_LT(budget, options.calibration_num_points);
  EXPECT_EQ(pass.calibration_num_points, budget);
  EXPECT_EQ(pass.bundle_adjustment.max_num_points, budget);
  EXPECT_EQ(pass.translation_averaging.max_num_tracks, budget);
  EXPECT_TRUE(pass.relative_pose.nister_five_point);
  EXPECT_FALSE(options.relative_pose.nister_five_point);

  // 0: the second pass's budgets.
  options.calibration_pass_num_tracks = 0;
  const MapperOptions full =
      FirstPassOptions(options, OneCameraTheViewGraphCouldNotEstimate()).options;
  EXPECT_EQ(full.calibration_num_points, options.calibration_num_points);
  EXPECT_EQ(full.bundle_adjustment.max_num_points, options.calibration_num_points);
  EXPECT_EQ(full.translation_averaging.max_num_tracks,
            options.translation_averaging.max_num_tracks);
  EXPECT_FALSE(full.relative_pose.nister_five_point);
}

TEST(CalibrationPasses, AFocalLengthTheViewGraphEstimatedNeedsNoCalibrationPass) {
  ViewGraphCalibrationSummary calibration = OneCameraTheViewGraphCouldNotEstimate();
  calibration.cameras[0].estimated = true;
  calibration.cameras[0].estimated_focal_px = 1500.0;
  MapperOptions options;
  const FirstPass first = FirstPassOptions(options, calibration);
  const MapperOptions& pass = first.options;
  EXPECT_FALSE(first.calibration_pass);
  EXPECT_EQ(pass.translation_averaging.max_num_tracks,
            options.translation_averaging.max_num_tracks);
  EXPECT_FALSE(pass.relative_pose.nister_five_point);
}

}  // namespace
}  // namespace ramap
