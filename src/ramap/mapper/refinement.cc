#include "ramap/mapper/refinement.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "ramap/mapper/calibration_passes.h"
#include "ramap/mapper/component_triangulation.h"

namespace ramap {

namespace {

void LogBundleAdjustment(const PassInput& input, const BundleAdjustmentSummary& ba,
                         const std::string& what, ComponentState* state) {
  const auto listed_cameras = [](const std::vector<uint32_t>& ids, const std::string& verdict) {
    std::string listed;
    for (const uint32_t camera_id : ids)
      listed +=
          (listed.empty() ? "; the principal point of camera " : ", ") + std::to_string(camera_id);
    return listed.empty() ? listed : listed + verdict;
  };
  const std::string held =
      listed_cameras(
          ba.principal_points_drifted,
          " moved far without lowering its errors: held where it started, solved again") +
      listed_cameras(ba.principal_points_confirmed,
                     " moved far and lowered its errors clearly: kept (a cropped photo's)");
  const std::string wide = ba.wide_start_loss_px > 0
                               ? ", first under a " + std::to_string(ba.wide_start_loss_px) +
                                     " px loss (median start error above the loss scale)"
                               : "";
  RecordStage(input, stage::kBundleAdjustment, ba.seconds,
              what + std::to_string(ba.num_points) + " points, RMSE " +
                  std::to_string(ba.initial_rmse_px) + " -> " + std::to_string(ba.final_rmse_px) +
                  " px, " + std::to_string(ba.num_iterations) + " iterations" + wide + held,
              state);
}

// The pass's cameras with those of `model` in their place (in `cameras`), and the bearings of
// `model`'s images through them.
ImageBearings BearingsThrough(const PassInput& input, const Reconstruction& model,
                              std::map<uint32_t, Camera>* cameras) {
  *cameras = input.cameras;
  for (const auto& [camera_id, camera] : model.cameras) (*cameras)[camera_id] = camera;
  std::vector<uint32_t> image_ids;
  for (const auto& [image_id, image] : model.images) image_ids.push_back(image_id);
  return ComputeBearings(input.database, *cameras, "bundle adjustment", image_ids);
}

// Every track triangulated with the poses and intrinsics of `model` (refined ones change every
// bearing of their images) under `options`; `what` opens the progress line.
Reconstruction TriangulateThrough(const PassInput& input, const std::vector<Track>& tracks,
                                  const Reconstruction& model, const std::string& what,
                                  ComponentState* state, const TrackTriangulationOptions& options) {
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [image_id, image] : model.images) poses[image_id] = image.cam_from_world;
  const bool intrinsics_changed =
      std::any_of(model.cameras.begin(), model.cameras.end(), [&](const auto& entry) {
        const auto given = input.cameras.find(entry.first);
        return given == input.cameras.end() || given->second.params != entry.second.params;
      });
  if (!intrinsics_changed) {
    return TriangulateComponent(input, poses, tracks, input.bearings, input.cameras, what + ": ",
                                options, state);
  }
  std::map<uint32_t, Camera> cameras;
  const ImageBearings bearings = BearingsThrough(input, model, &cameras);
  return TriangulateComponent(input, poses, tracks, bearings, cameras,
                              what + " and intrinsics: ", options, state);
}

// One line per group of cameras with given intrinsics: what the data said of them.
void LogGivenIntrinsicsTest(const PassInput& input, const GivenIntrinsicsTestSummary& test,
                            ComponentState* state) {
  for (const GivenIntrinsicsTest& group : test.groups) {
    std::ostringstream line;
    line << std::fixed << std::setprecision(3) << "given " << group.given_model << " camera "
         << group.camera_ids.front() << (group.camera_ids.size() > 1 ? " and its copies" : "")
         << " (" << group.num_images << " images), RMSE " << group.held_rmse_px << " px";
    line << "; focal length " << (group.distortion_tried ? "and radial distortion " : "")
         << "freed " << group.freed_rmse_px << " px (" << std::setprecision(1)
         << group.given_focal_px << " -> " << group.freed_focal_px << " px)";
    if (group.focal_only_rmse_px > 0)
      line << std::setprecision(3) << ", focal length alone " << group.focal_only_rmse_px << " px";
    line << ": " << (group.focal_accepted ? "focal length wrong" : "focal length kept")
         << (group.distortion_accepted ? ", distortion added (" + group.final_model + ")" : "");
    RecordStage(input, stage::kBundleAdjustment, &group == &test.groups.front() ? test.seconds : 0,
                line.str(), state);
  }
}

// Whether BA holds some camera of `model` as given.
bool AnyHeldAsGiven(const BundleAdjustmentOptions& ba, const Reconstruction& model) {
  return std::any_of(model.cameras.begin(), model.cameras.end(),
                     [&](const auto& entry) { return HeldAsGiven(ba, entry.second); });
}

// The images BA detached the most observations from, by name (MapperComponentSummary).
std::vector<std::pair<std::string, int>> MostFilteredImages(const FeatureDatabase& database,
                                                            const BundleAdjustmentSummary& ba) {
  std::vector<std::pair<std::string, int>> images;
  for (const auto& [image_id, count] : ba.filtered_per_image)
    images.emplace_back(database.images.at(image_id).name, count);
  std::stable_sort(images.begin(), images.end(),
                   [](const auto& a, const auto& b) { return a.second > b.second; });
  if (images.size() > 20) images.resize(20);
  return images;
}

// What the loop carries from one step to the next: the adjustment's options as the data adjust
// them (intrinsics held after a calibration, a focal valley crossed, given cameras disproved),
// the bearings in use, the priors.
struct RefinementRun {
  BundleAdjustmentOptions adjustment;
  ImageBearings own_bearings;  // through the intrinsics a step changed
  const ImageBearings* bearings = nullptr;
  std::map<uint32_t, PosePrior> priors;
  bool done = false;
};

// RefinementStep::kCalibrateOnSubset where some camera's focal length is refined and the model has
// more than twice the subset's points. Afterwards the adjustment starts past the focal valley and,
// with hold_calibrated_intrinsics, holds the intrinsics found, through bearings undistorted with
// them; a calibration pass ends here: the second pass averages again through these intrinsics and
// keeps none of this pass's poses, so a BA that holds the intrinsics would be wasted.
void CalibrateOnSubset(const PassInput& input, const RefinementPlan& plan, ComponentState* state,
                       RefinementRun* run) {
  Reconstruction& model = state->model;
  const int num_points = plan.calibration_num_points;
  const bool refines_focal = std::any_of(
      model.cameras.begin(), model.cameras.end(),
      [&](const auto& entry) { return RefinesFocalLength(plan.adjustment, entry.second); });
  if (!refines_focal || num_points == 0 ||
      static_cast<int>(model.points3D.size()) <= 2 * num_points) {
    return;
  }
  Reconstruction subset = PointsForBundleAdjustment(model, plan.calibration);
  const BundleAdjustmentSummary calibration =
      BundleAdjust(input.bearings.bearings, input.bearings.focal_lengths_px, &subset,
                   plan.calibration, run->priors);
  LogBundleAdjustment(input, calibration, "intrinsics on a subset: ", state);
  model = TriangulateThrough(input, state->translations->tracks, subset, "with the subset's poses",
                             state, plan.start_triangulation);
  if (plan.hold_calibrated_intrinsics && !AnyHeldAsGiven(run->adjustment, model)) {
    if (plan.ends_after_calibration) {
      run->done = true;
      return;
    }
    std::map<uint32_t, Camera> cameras;
    run->own_bearings = BearingsThrough(input, model, &cameras);
    run->bearings = &run->own_bearings;
    run->adjustment.refine_focal_length = false;
    run->adjustment.refine_principal_point = false;
    run->adjustment.refine_extra_params = false;
  }
  run->adjustment = PastTheFocalValley(run->adjustment);  // the subset crossed it
}

// RefinementStep::kTestGivenIntrinsics, where the model has a given camera to test. It is judged
// on points triangulated within the bound the models are held to: the observations BA's start
// keeps beyond it (TrackTriangulationOptions::start_max_error_deg) carry averaging's pose errors,
// not the intrinsics' (docs/benchmark-history.md, "The given camera's test, judged within the
// 4 px bound"). Where the test changed some camera, the bearings become those through it, and
// the cameras whose focal length it proved wrong are refined from there; where it adjusted the
// poses, every track is triangulated again through them.
void TestGivenIntrinsicsFirst(const PassInput& input, const RefinementPlan& plan,
                              ComponentState* state, RefinementRun* run) {
  Reconstruction& model = state->model;
  GivenIntrinsicsTestSummary& test = state->summary.given_intrinsics_test;
  if (!TestsSomeCamera(run->adjustment, plan.given_intrinsics_test, model)) return;
  const std::vector<Track>& tracks = state->translations->tracks;
  Reconstruction judged =
      TriangulateThrough(input, tracks, model, "for the test of the given intrinsics", state,
                         plan.judged_triangulation);
  test = TestGivenIntrinsics(run->bearings->bearings, run->bearings->focal_lengths_px,
                             run->adjustment, plan.given_intrinsics_test, &judged);
  model.cameras = judged.cameras;
  if (test.poses_adjusted) {
    for (auto& [image_id, image] : model.images)
      image.cam_from_world = judged.images.at(image_id).cam_from_world;
  }
  LogGivenIntrinsicsTest(input, test, state);
  if (std::any_of(test.groups.begin(), test.groups.end(), ChangesIntrinsics)) {
    std::map<uint32_t, Camera> cameras;
    run->own_bearings = BearingsThrough(input, model, &cameras);
    run->bearings = &run->own_bearings;
  }
  state->disproved_cameras.merge(DisprovedCameras(test));
  run->adjustment.disproved_given_cameras = state->disproved_cameras;
  // The test's freed step crossed the focal length's valley.
  if (!state->disproved_cameras.empty()) run->adjustment = PastTheFocalValley(run->adjustment);
  if (test.poses_adjusted) {
    model = TriangulateThrough(input, tracks, model, "with the tested poses", state,
                               plan.start_triangulation);
  }
}

// RefinementStep::kBundleAdjust: the adjustment through the bearings in use, then every track
// triangulated again; its summary is the component's.
void AdjustBundle(const PassInput& input, const RefinementPlan& plan, ComponentState* state,
                  RefinementRun* run) {
  Reconstruction adjusted = PointsForBundleAdjustment(state->model, run->adjustment);
  BundleAdjustmentSummary& ba = state->summary.bundle_adjustment;
  ba = BundleAdjust(run->bearings->bearings, run->bearings->focal_lengths_px, &adjusted,
                    run->adjustment, run->priors, input.progress);
  LogBundleAdjustment(input, ba, "", state);
  state->summary.most_filtered_images = MostFilteredImages(input.database, ba);
  state->model = TriangulateThrough(
      input, state->translations->tracks, adjusted,
      input.options.refine ? "again with the refined poses" : "with the subset's poses", state,
      plan.final_triangulation);
}

// RefinementStep::kBundleAdjustAgain: another round through the intrinsics the last one refined.
void AdjustBundleAgain(const PassInput& input, const RefinementPlan& plan, int round,
                       ComponentState* state, RefinementRun* run) {
  std::map<uint32_t, Camera> cameras;
  const ImageBearings bearings = BearingsThrough(input, state->model, &cameras);
  Reconstruction again = PointsForBundleAdjustment(state->model, run->adjustment);
  const BundleAdjustmentSummary summary = BundleAdjust(bearings.bearings, bearings.focal_lengths_px,
                                                       &again, run->adjustment, run->priors);
  LogBundleAdjustment(input, summary, "round " + std::to_string(round) + ": ", state);
  state->model =
      TriangulateThrough(input, state->translations->tracks, again, "again with the refined poses",
                         state, plan.final_triangulation);
}

}  // namespace

std::string RefinementStepName(RefinementStep step) {
  switch (step) {
    case RefinementStep::kCalibrateOnSubset:
      return "calibrate on a subset";
    case RefinementStep::kTestGivenIntrinsics:
      return "test the given intrinsics";
    case RefinementStep::kBundleAdjust:
      return "bundle adjustment";
    case RefinementStep::kBundleAdjustAgain:
      return "bundle adjustment again";
  }
  return "";
}

RefinementPlan PlanRefinement(const MapperOptions& options, bool calibration_pass) {
  RefinementPlan plan;
  // Without the final BA, the subset's adjustment alone (MapperOptions::subset_adjustment): one
  // round on the subset's points, the given intrinsics tested on them.
  if (options.refine) plan.steps.push_back(RefinementStep::kCalibrateOnSubset);
  plan.steps.push_back(RefinementStep::kTestGivenIntrinsics);
  plan.steps.push_back(RefinementStep::kBundleAdjust);
  for (int round = 1; options.refine && round < options.num_refinement_rounds; ++round)
    plan.steps.push_back(RefinementStep::kBundleAdjustAgain);
  plan.adjustment = options.refine ? options.bundle_adjustment : SubsetAdjustmentOptions(options);
  plan.adjustment.num_threads = options.num_threads;
  plan.calibration = SubsetAdjustmentOptions(options);
  plan.calibration.num_threads = options.num_threads;
  // Only its intrinsics are kept: its poses start the full BA, or none of them (a calibration
  // pass), so it ends once they have settled.
  plan.calibration.settle_intrinsics_only = true;
  plan.calibration_num_points = options.calibration_num_points;
  plan.hold_calibrated_intrinsics = options.calibration_subset_only;
  plan.ends_after_calibration = calibration_pass;
  plan.given_intrinsics_test = options.given_intrinsics_test;
  plan.start_triangulation = options.triangulation.ForBundleAdjustmentStart();
  plan.judged_triangulation = options.triangulation;
  plan.final_triangulation = options.triangulation;
  plan.use_priors = options.prior_alignment.use_in_bundle_adjustment;
  return plan;
}

ComponentState RefineComponent(const PassInput& input, const RefinementPlan& plan,
                               ComponentState state) {
  RefinementRun run;
  run.adjustment = plan.adjustment;
  run.bearings = &input.bearings;
  PriorAlignment& prior_alignment = state.prior_alignment;
  const bool use_priors = prior_alignment.summary.aligned && plan.use_priors;
  if (use_priors) run.priors = prior_alignment.inliers;
  prior_alignment.summary.used_in_bundle_adjustment = use_priors;
  int round = 0;
  for (const RefinementStep step : plan.steps) {
    if (run.done) break;
    switch (step) {
      case RefinementStep::kCalibrateOnSubset:
        CalibrateOnSubset(input, plan, &state, &run);
        break;
      case RefinementStep::kTestGivenIntrinsics:
        TestGivenIntrinsicsFirst(input, plan, &state, &run);
        break;
      case RefinementStep::kBundleAdjust:
        AdjustBundle(input, plan, &state, &run);
        round = 1;
        break;
      case RefinementStep::kBundleAdjustAgain:
        AdjustBundleAgain(input, plan, ++round, &state, &run);
        break;
    }
  }
  return state;
}

}  // namespace ramap
