// The refinement plan: which steps run, made once from the options, and the options each step
// works with.
#include "ramap/mapper/refinement.h"

#include <gtest/gtest.h>

#include <vector>

namespace ramap {
namespace {

using Steps = std::vector<RefinementStep>;

TEST(RefinementPlan, TheDefaultsCalibrateOnASubsetTestTheGivenCameraThenAdjustOnce) {
  MapperOptions options;
  options.num_threads = 3;
  const RefinementPlan plan = PlanRefinement(options, false);
  EXPECT_EQ(plan.steps, (Steps{RefinementStep::kCalibrateOnSubset,
                               RefinementStep::kTestGivenIntrinsics, RefinementStep::kBundleAdjust}));
  // The full BA's options with the mapper's threads; the calibration's on the subset, settling the
  // intrinsics alone.
  EXPECT_EQ(plan.adjustment.max_num_points, options.bundle_adjustment.max_num_points);
  EXPECT_EQ(plan.adjustment.num_threads, 3);
  EXPECT_FALSE(plan.adjustment.settle_intrinsics_only);
  EXPECT_EQ(plan.calibration.max_num_points, options.calibration_num_points);
  EXPECT_EQ(plan.calibration.num_threads, 3);
  EXPECT_TRUE(plan.calibration.settle_intrinsics_only);
  EXPECT_EQ(plan.calibration_num_points, options.calibration_num_points);
  EXPECT_TRUE(plan.hold_calibrated_intrinsics);
  EXPECT_FALSE(plan.ends_after_calibration);
  // BA starts from the looser angular bound and ends at the models' pixel bound.
  EXPECT_GT(plan.start_triangulation.max_error_deg, 0.0);
  EXPECT_EQ(plan.final_triangulation.max_error_deg, 0.0);
  EXPECT_EQ(plan.judged_triangulation.max_reprojection_error_px,
            options.triangulation.max_reprojection_error_px);
  EXPECT_TRUE(plan.use_priors);
}

TEST(RefinementPlan, WithoutTheFinalAdjustmentTheSubsetIsAdjustedOnce) {
  MapperOptions options;
  options.refine = false;
  options.num_refinement_rounds = 3;  // rounds are the final BA's
  const RefinementPlan plan = PlanRefinement(options, false);
  EXPECT_EQ(plan.steps,
            (Steps{RefinementStep::kTestGivenIntrinsics, RefinementStep::kBundleAdjust}));
  EXPECT_EQ(plan.adjustment.max_num_points, options.calibration_num_points);
}

TEST(RefinementPlan, MoreRoundsAdjustAgain) {
  MapperOptions options;
  options.num_refinement_rounds = 3;
  const RefinementPlan plan = PlanRefinement(options, false);
  EXPECT_EQ(plan.steps,
            (Steps{RefinementStep::kCalibrateOnSubset, RefinementStep::kTestGivenIntrinsics,
                   RefinementStep::kBundleAdjust, RefinementStep::kBundleAdjustAgain,
                   RefinementStep::kBundleAdjustAgain}));
}

TEST(RefinementPlan, ACalibrationPassEndsWithTheCalibration) {
  MapperOptions options;
  EXPECT_TRUE(PlanRefinement(options, true).ends_after_calibration);
  options.calibration_subset_only = false;
  const RefinementPlan plan = PlanRefinement(options, true);
  EXPECT_FALSE(plan.hold_calibrated_intrinsics);
  options.prior_alignment.use_in_bundle_adjustment = false;
  EXPECT_FALSE(PlanRefinement(options, false).use_priors);
}

TEST(RefinementPlan, EveryStepHasAName) {
  for (const RefinementStep step :
       {RefinementStep::kCalibrateOnSubset, RefinementStep::kTestGivenIntrinsics,
        RefinementStep::kBundleAdjust, RefinementStep::kBundleAdjustAgain}) {
    EXPECT_FALSE(RefinementStepName(step).empty());
  }
}

}  // namespace
}  // namespace ramap
