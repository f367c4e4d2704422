#include "ramap/pipeline/refine.h"

#include <algorithm>
#include <iomanip>
#include <map>
#include <sstream>

#include "ramap/pipeline/bearings.h"
#include "ramap/pipeline/calibration_passes.h"
#include "ramap/pipeline/mapper_options.h"
#include "ramap/pipeline/mapper_summary.h"
#include "ramap/pipeline/track_triangulation.h"

namespace ramap {

namespace {

void LogBundleAdjustment(const MapperContext& context, const BundleAdjustmentSummary& ba,
                         const std::string& what) {
  std::string held;
  for (const uint32_t camera_id : ba.principal_points_drifted)
    held += (held.empty() ? "; the principal point of camera " : ", ") + std::to_string(camera_id);
  if (!held.empty()) held += " drifted: every guessed one held where it started, solved again";
  const std::string wide = ba.wide_start_loss_px > 0
                               ? ", first under a " + std::to_string(ba.wide_start_loss_px) +
                                     " px loss (median start error above the loss scale)"
                               : "";
  context.log.Record(stage::kBundleAdjustment, ba.seconds,
                     what + std::to_string(ba.num_points) + " points, RMSE " +
                         std::to_string(ba.initial_rmse_px) + " -> " +
                         std::to_string(ba.final_rmse_px) + " px, " +
                         std::to_string(ba.num_iterations) + " iterations" + wide + held);
}

// The context's cameras with those of `model` in their place (in `cameras`), and the bearings of
// `model`'s images through them.
ImageBearings BearingsThrough(const MapperContext& context, const Reconstruction& model,
                              std::map<uint32_t, Camera>* cameras) {
  *cameras = context.cameras;
  for (const auto& [camera_id, camera] : model.cameras) (*cameras)[camera_id] = camera;
  std::vector<uint32_t> image_ids;
  for (const auto& [image_id, image] : model.images) image_ids.push_back(image_id);
  return ComputeBearings(context.database, *cameras, "bundle adjustment", image_ids);
}

// Every track triangulated with the poses and intrinsics of `model` (refined ones change every
// bearing of their images) under `options`; `what` opens the progress line.
Reconstruction TriangulateThrough(const MapperContext& context, const std::vector<Track>& tracks,
                                  const Reconstruction& model, const std::string& what,
                                  MapperComponentSummary* component,
                                  const TrackTriangulationOptions& options) {
  std::map<uint32_t, Rigid3d> poses;
  for (const auto& [image_id, image] : model.images) poses[image_id] = image.cam_from_world;
  const bool intrinsics_changed =
      std::any_of(model.cameras.begin(), model.cameras.end(), [&](const auto& entry) {
        const auto given = context.cameras.find(entry.first);
        return given == context.cameras.end() || given->second.params != entry.second.params;
      });
  if (!intrinsics_changed) {
    return TriangulateComponent(context, poses, tracks, context.bearings, context.cameras,
                                what + ": ", component, options);
  }
  std::map<uint32_t, Camera> cameras;
  const ImageBearings bearings = BearingsThrough(context, model, &cameras);
  return TriangulateComponent(context, poses, tracks, bearings, cameras,
                              what + " and intrinsics: ", component, options);
}

// One line per group of cameras with given intrinsics: what the data said of them.
void LogGivenIntrinsicsTest(const MapperContext& context, const GivenIntrinsicsTestSummary& test) {
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
    context.log.Record(stage::kBundleAdjustment, &group == &test.groups.front() ? test.seconds : 0,
                       line.str());
  }
}

// Whether BA holds some camera of `model` as given.
bool AnyHeldAsGiven(const BundleAdjustmentOptions& ba, const Reconstruction& model) {
  return std::any_of(model.cameras.begin(), model.cameras.end(),
                     [&](const auto& entry) { return HeldAsGiven(ba, entry.second); });
}

// Where some camera's focal length is refined, first on a subset of the points: the focal
// length's long valley (BundleAdjustmentOptions::intrinsics_function_tolerance) is crossed there,
// cheaply, and every track is triangulated again through the poses and intrinsics it found, for
// the full adjustment to start from. Returns whether it ran.
bool CalibrateOnSubset(const MapperContext& context, const std::vector<Track>& tracks,
                       const std::map<uint32_t, PosePrior>& priors,
                       MapperComponentSummary* component, Reconstruction* reconstruction) {
  const MapperOptions& options = context.options;
  const BundleAdjustmentOptions& ba = options.bundle_adjustment;
  const int num_points = options.calibration_num_points;
  const bool refines_focal =
      std::any_of(reconstruction->cameras.begin(), reconstruction->cameras.end(),
                  [&](const auto& entry) { return RefinesFocalLength(ba, entry.second); });
  if (!refines_focal || num_points == 0 ||
      static_cast<int>(reconstruction->points3D.size()) <= 2 * num_points) {
    return false;
  }
  BundleAdjustmentOptions subset_options = SubsetAdjustmentOptions(options);
  // Only its intrinsics are kept: its poses start the full BA, or none of them (a calibration
  // pass), so it ends once they have settled.
  subset_options.settle_intrinsics_only = true;
  Reconstruction subset = PointsForBundleAdjustment(*reconstruction, subset_options);
  const BundleAdjustmentSummary calibration =
      BundleAdjust(context.bearings.bearings, context.bearings.focal_lengths_px, &subset,
                   subset_options, priors);
  LogBundleAdjustment(context, calibration, "intrinsics on a subset: ");
  *reconstruction = TriangulateThrough(context, tracks, subset, "with the subset's poses",
                                       component, options.triangulation.ForBundleAdjustmentStart());
  return true;
}

// The given intrinsics tested (refine/given_intrinsics_test.h) from the poses `reconstruction`
// has, before bundle adjustment rather than after it: BA then runs once, through the intrinsics
// the test kept, instead of a second time where the data proved the given ones wrong (lund_door
// from its EXIF focal length), and it starts from the poses the test's subset was adjusted to,
// every track triangulated again through them and the kept intrinsics. Where the test changed
// some camera, `*bearings` become those through it (kept in `tested`), and the cameras whose focal
// length it proved wrong are refined from there (BundleAdjustmentOptions::disproved_given_cameras).
void TestGivenIntrinsicsFirst(const MapperContext& context, const std::vector<Track>& tracks,
                              BundleAdjustmentOptions* ba_options,
                              MapperComponentSummary* component, Reconstruction* reconstruction,
                              ImageBearings* tested, const ImageBearings** bearings) {
  GivenIntrinsicsTestSummary& test = component->given_intrinsics_test;
  if (!TestsSomeCamera(*ba_options, context.options.given_intrinsics_test, *reconstruction)) return;
  // The test compares errors, so it is judged on points triangulated within the bound the models
  // are held to: the observations BA's start keeps beyond it (TrackTriangulationOptions::
  // start_max_error_deg) carry averaging's pose errors, not the intrinsics'. Judged on those,
  // kitti07_first160's given camera no longer showed its distortion (0.822 -> 0.787 px freed,
  // under the 5% asked, against 0.705 -> 0.662 px) and scored 79.7 AUC@3 instead of 85.7.
  Reconstruction judged =
      TriangulateThrough(context, tracks, *reconstruction, "for the test of the given intrinsics",
                         component, context.options.triangulation);
  test = TestGivenIntrinsics((*bearings)->bearings, (*bearings)->focal_lengths_px, *ba_options,
                             context.options.given_intrinsics_test, &judged);
  reconstruction->cameras = judged.cameras;
  if (test.poses_adjusted) {
    for (auto& [image_id, image] : reconstruction->images)
      image.cam_from_world = judged.images.at(image_id).cam_from_world;
  }
  LogGivenIntrinsicsTest(context, test);
  if (std::any_of(test.groups.begin(), test.groups.end(), ChangesIntrinsics)) {
    std::map<uint32_t, Camera> cameras;
    *tested = BearingsThrough(context, *reconstruction, &cameras);
    *bearings = tested;
  }
  ba_options->disproved_given_cameras.merge(DisprovedCameras(test));
  // The test's freed step crossed the focal length's valley.
  if (!ba_options->disproved_given_cameras.empty()) *ba_options = PastTheFocalValley(*ba_options);
  if (test.poses_adjusted) {
    *reconstruction =
        TriangulateThrough(context, tracks, *reconstruction, "with the tested poses", component,
                           context.options.triangulation.ForBundleAdjustmentStart());
  }
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

}  // namespace

void RefineComponent(const MapperContext& context, const std::vector<Track>& tracks,
                     PriorAlignment* prior_alignment, MapperComponentSummary* component,
                     Reconstruction* reconstruction) {
  const MapperOptions& options = context.options;
  const bool use_priors =
      prior_alignment->summary.aligned && options.prior_alignment.use_in_bundle_adjustment;
  const std::map<uint32_t, PosePrior> priors =
      use_priors ? prior_alignment->inliers : std::map<uint32_t, PosePrior>();
  prior_alignment->summary.used_in_bundle_adjustment = use_priors;
  // Without the final BA, the subset's adjustment alone (MapperOptions::subset_adjustment): one
  // round on the subset's points, the given intrinsics tested on them.
  BundleAdjustmentOptions ba_options =
      options.refine ? options.bundle_adjustment : SubsetAdjustmentOptions(options);
  ImageBearings subset_bearings;
  const ImageBearings* bearings = &context.bearings;
  if (options.refine && CalibrateOnSubset(context, tracks, priors, component, reconstruction)) {
    if (options.calibration_subset_only && !AnyHeldAsGiven(ba_options, *reconstruction)) {
      // A calibration pass ends here: the second pass averages again through these intrinsics
      // and keeps none of this pass's poses, so a BA that holds the intrinsics would be wasted.
      if (context.summary.calibration_pass) return;
      std::map<uint32_t, Camera> cameras;
      subset_bearings = BearingsThrough(context, *reconstruction, &cameras);
      bearings = &subset_bearings;
      ba_options.refine_focal_length = false;
      ba_options.refine_principal_point = false;
      ba_options.refine_extra_params = false;
    }
    ba_options = PastTheFocalValley(ba_options);  // the subset crossed it
  }
  ImageBearings tested_bearings;
  TestGivenIntrinsicsFirst(context, tracks, &ba_options, component, reconstruction,
                           &tested_bearings, &bearings);
  Reconstruction adjusted = PointsForBundleAdjustment(*reconstruction, ba_options);
  BundleAdjustmentSummary& ba = component->bundle_adjustment;
  ba = BundleAdjust(bearings->bearings, bearings->focal_lengths_px, &adjusted, ba_options, priors,
                    context.log.progress());
  LogBundleAdjustment(context, ba, "");
  component->most_filtered_images =
      MostFilteredImages(context.database, component->bundle_adjustment);
  *reconstruction = TriangulateThrough(
      context, tracks, adjusted,
      options.refine ? "again with the refined poses" : "with the subset's poses", component,
      options.triangulation);
  const int num_rounds = options.refine ? options.num_refinement_rounds : 1;
  for (int round = 1; round < num_rounds; ++round) {
    std::map<uint32_t, Camera> cameras;
    const ImageBearings bearings = BearingsThrough(context, *reconstruction, &cameras);
    Reconstruction again = PointsForBundleAdjustment(*reconstruction, ba_options);
    const BundleAdjustmentSummary summary =
        BundleAdjust(bearings.bearings, bearings.focal_lengths_px, &again, ba_options, priors);
    LogBundleAdjustment(context, summary, "round " + std::to_string(round + 1) + ": ");
    *reconstruction = TriangulateThrough(context, tracks, again, "again with the refined poses",
                                         component, options.triangulation);
  }
}

}  // namespace ramap
