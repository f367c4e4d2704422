// The given-intrinsics test on real images: fountain-P11 (COLMAP's SIFT, images at 640 px) with
// its calibration given 1.6 times too long. Averaging through it leaves many observations far off;
// the test must still see that freeing the focal length fits the views far better, and BA must
// end at the true focal length. (On the benchmark's database at 1600 px, whose pairs ramap
// verified, the plain RMSE kept the wrong value: docs/benchmark-history.md, "A focal length proved
// wrong".
// COLMAP's own databases, at 640 and 1600 px, do not show it.) By default the view graph proves
// such a value wrong before averaging (estimators/view_graph_calibration.h); the test of given
// intrinsics is the net for what it lets through, so it is exercised here with that test off.
#include <gtest/gtest.h>

#include "ramap/eval/pose_metrics.h"
#include "ramap/io/colmap_database.h"
#include "ramap/io/trajectory.h"
#include "ramap/mapper/mapper.h"
#include "test_support.h"

namespace ramap {
namespace {

// fountain-P11's database with its calibration given 1.6 times too long.
FeatureDatabase FountainWithFocalLengthTooLong(const std::string& images) {
  test::ColmapRun run;
  run.image_dir = images;
  run.camera_params = "2759.48,2764.16,1520.69,1006.81";
  run.max_image_size = 640;
  FeatureDatabase database = ReadColmapDatabase(test::CachedColmapDatabase(run));
  EXPECT_EQ(database.cameras.size(), 1u);
  Camera& camera = database.cameras.begin()->second;
  camera.params[0] *= 1.6;
  camera.params[1] *= 1.6;
  camera.has_prior_focal_length = true;
  return database;
}

void ExpectTruePoses(const MapperResult& result, const std::string& gt_dir) {
  std::vector<std::string> names;
  std::map<std::string, Rigid3d> truth;
  for (const GroundTruthPose& pose : ReadGroundTruth(gt_dir, GroundTruthFormat::kStrecha).poses) {
    names.push_back(pose.image_name);
    truth[pose.image_name] = pose.cam_from_world;
  }
  const PoseEvaluation evaluation =
      EvaluatePoses(PosesByName(result.reconstructions[0]), truth, names);
  EXPECT_LT(evaluation.rotation_error_median_deg, 0.2);
}

TEST(GivenIntrinsicsRealData, FountainFocalLengthGivenFarTooLongIsProvenWrong) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/fountain-P11/images");
  RAMAP_REQUIRE_SHARED_DATA(gt_dir, "strecha/fountain-P11/gt_dense_cameras");
  const FeatureDatabase database = FountainWithFocalLengthTooLong(images);
  MapperOptions options;
  options.view_graph_calibration.test_given_focal_lengths = false;
  const MapperResult result = RunMapper(database, options, "fountain-P11");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  const std::vector<GivenIntrinsicsTest>& tests =
      result.summary.components.at(0).given_intrinsics_test.groups;
  ASSERT_EQ(tests.size(), 1u);
  EXPECT_TRUE(tests[0].focal_accepted)
      << "held " << tests[0].held_rmse_px << " px, freed " << tests[0].freed_rmse_px << " px";
  const Camera& written = result.reconstructions[0].cameras.begin()->second;
  EXPECT_NEAR(written.params[0], 2759.48, 0.01 * 2759.48);
  ExpectTruePoses(result, gt_dir);
}

TEST(GivenIntrinsicsRealData, FountainFocalLengthGivenFarTooLongIsDisprovedByTheViewGraph) {
  RAMAP_REQUIRE_COLMAP();
  RAMAP_REQUIRE_SHARED_DATA(images, "strecha/fountain-P11/images");
  RAMAP_REQUIRE_SHARED_DATA(gt_dir, "strecha/fountain-P11/gt_dense_cameras");
  const MapperResult result =
      RunMapper(FountainWithFocalLengthTooLong(images), MapperOptions(), "fountain-P11");
  ASSERT_EQ(result.reconstructions.size(), 1u);
  ASSERT_EQ(result.summary.cameras.size(), 1u);
  const CameraCalibration& estimate = result.summary.cameras[0].view_graph;
  EXPECT_EQ(estimate.outcome, FocalOutcome::kDisproved) << estimate.problem;
  EXPECT_NEAR(estimate.estimated_focal_px, 2759.48, 0.1 * 2759.48);  // 6% off; BA then fixes it
  const Camera& written = result.reconstructions[0].cameras.begin()->second;
  EXPECT_NEAR(written.params[0], 2759.48, 0.01 * 2759.48);
  ExpectTruePoses(result, gt_dir);
}

}  // namespace
}  // namespace ramap
