// Stage 6 of the mapper on one component: bundle adjustment of the averaged model
// (refine/bundle_adjustment.h), then every track triangulated again. What runs is planned once
// from the options (PlanRefinement) and run by one loop (RefineComponent): the full adjustment
// (MapperOptions::refine, the default), or only that of a subset of the tracks
// (MapperOptions::subset_adjustment).
#pragma once

#include <string>
#include <vector>

#include "ramap/estimators/track_triangulation.h"
#include "ramap/mapper/mapper_state.h"
#include "ramap/refine/bundle_adjustment.h"
#include "ramap/refine/given_intrinsics_check.h"

namespace ramap {

enum class RefinementStep {
  // Where some camera's focal length is refined: BA of a subset of the points
  // (MapperOptions::calibration_num_points), kept for its intrinsics, which crosses the focal
  // length's long valley cheaply; every track is then triangulated again through them.
  kCalibrateOnSubset,
  // Whether the data prove given intrinsics wrong (refine/given_intrinsics_check.h), from the
  // poses at hand: BA then runs once, through the intrinsics the test kept.
  kTestGivenIntrinsics,
  // Bundle adjustment, then every track triangulated again.
  kBundleAdjust,
  // Another round (MapperOptions::num_refinement_rounds), through the intrinsics the last one
  // refined.
  kBundleAdjustAgain,
};

// "calibrate on a subset", "test the given intrinsics", "bundle adjustment", "bundle adjustment
// again".
std::string RefinementStepName(RefinementStep step);

struct RefinementPlan {
  std::vector<RefinementStep> steps;
  // The adjustment's options: the full BA's, or the subset's without it; the mapper's threads.
  BundleAdjustmentOptions adjustment;
  // The calibration's on a subset: the subset's options, settling the intrinsics alone.
  BundleAdjustmentOptions calibration;
  int calibration_num_points = 0;
  // After the calibration on a subset, the adjustment holds the intrinsics it found
  // (MapperOptions::calibration_subset_only), unless some camera is held as given.
  bool hold_calibrated_intrinsics = false;
  // A calibration pass keeps the calibration's intrinsics alone: it ends there.
  bool ends_after_calibration = false;
  GivenIntrinsicsTestOptions given_intrinsics_test;
  // Triangulation where BA starts, where the test is judged, and after BA.
  TrackTriangulationOptions start_triangulation;
  TrackTriangulationOptions judged_triangulation;
  TrackTriangulationOptions final_triangulation;
  // Pose priors as residuals of the adjustments, where the component is aligned to them.
  bool use_priors = false;
};

// The plan `options` make, for a calibration pass (mapper/calibration_passes.h) or not.
RefinementPlan PlanRefinement(const MapperOptions& options, bool calibration_pass);

// `plan` run on the component's model: its adjustments, the test of its given intrinsics, every
// track triangulated again after each, through the intrinsics they refined; the figures and the
// stages' lines into `state`.
ComponentState RefineComponent(const PassInput& input, const RefinementPlan& plan,
                               ComponentState state);

}  // namespace ramap
