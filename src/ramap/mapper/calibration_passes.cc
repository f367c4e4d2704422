#include "ramap/mapper/calibration_passes.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <set>
#include <sstream>

namespace ramap {

void LogViewGraphCalibration(const ViewGraphCalibrationSummary& calibration, std::ostream* progress,
                             StageReport* report) {
  if (calibration.cameras.empty()) return;
  int num_unknown = 0, num_estimated = 0, num_given = 0, num_disproved = 0;
  std::ostringstream focal_lengths;
  int num_listed = 0;
  for (const CameraCalibration& camera : calibration.cameras) {
    if (camera.given) {
      ++num_given;
      num_disproved += camera.outcome == FocalOutcome::kDisproved;
    } else {
      ++num_unknown;
      num_estimated += camera.estimated;
    }
    // A collection of many cameras would make this line a page: the first ten, and how many more.
    if (num_listed++ == 10) focal_lengths << ", ...";
    if (num_listed > 10) continue;
    if (focal_lengths.tellp() > 0) focal_lengths << ", ";
    focal_lengths << std::fixed << std::setprecision(1) << camera.prior_focal_px << " -> "
                  << (camera.estimated ? camera.estimated_focal_px : camera.prior_focal_px)
                  << " px";
  }
  std::string counts;
  if (num_unknown > 0) {
    counts = std::to_string(num_estimated) + " of " + std::to_string(num_unknown) +
             " uncalibrated cameras estimated";
  }
  if (num_given > 0) {
    if (!counts.empty()) counts += "; ";
    counts += std::to_string(num_disproved) + " of " + std::to_string(num_given) +
              " given focal lengths disproved by the pairs";
  }
  if (calibration.scale_from_given) {
    counts +=
        "; the views fix only the focal lengths' ratios (they look at one point): their "
        "scale is the given focal lengths' median";
  }
  RecordStage(stage::kViewGraphCalibration, calibration.seconds,
              counts + " (" + focal_lengths.str() + ")", progress, report);
}

FirstPass FirstPassOptions(const MapperOptions& options,
                           const ViewGraphCalibrationSummary& calibration) {
  const bool unknown_focal = std::any_of(
      calibration.cameras.begin(), calibration.cameras.end(),
      [](const CameraCalibration& camera) { return !camera.given && !camera.estimated; });
  if (!options.AdjustsAfterAveraging() || !unknown_focal || options.calibration_num_points == 0 ||
      !(options.max_focal_change_in_bundle_adjustment > 0) ||
      !options.bundle_adjustment.refine_focal_length) {
    return {options, false};
  }
  MapperOptions pass = options;
  const int budget = options.calibration_pass_num_tracks;
  if (budget > 0) {
    pass.calibration_num_points = std::min(pass.calibration_num_points, budget);
    pass.translation_averaging.max_num_tracks =
        std::min(pass.translation_averaging.max_num_tracks, budget);
    pass.relative_pose.nister_five_point = true;
  }
  pass.bundle_adjustment = SubsetAdjustmentOptions(pass);
  return {pass, true};
}

BundleAdjustmentOptions SubsetAdjustmentOptions(const MapperOptions& options) {
  const int budget = options.bundle_adjustment.max_num_points;
  return PointSubsetOptions(options.bundle_adjustment,
                            budget == 0 ? options.calibration_num_points
                                        : std::min(budget, options.calibration_num_points));
}

double FocalChangeInBundleAdjustment(const FeatureDatabase& database,
                                     const ViewGraphCalibrationSummary& calibration,
                                     const std::set<uint32_t>& disproved,
                                     const std::vector<Reconstruction>& reconstructions,
                                     std::map<uint32_t, Camera>* refined) {
  // A given focal length the test proved wrong (refine/given_intrinsics_check.h) was refined from
  // averaging's poses on a subset, then by the full BA: a second pass bought nothing after that
  // (MapperOptions::max_focal_change_in_bundle_adjustment).
  for (const Reconstruction& reconstruction : reconstructions) {
    for (const auto& [camera_id, camera] : reconstruction.cameras)
      refined->emplace(camera_id, camera);
  }
  double change = 0.0;
  for (const auto& [camera_id, camera] : database.cameras) {
    const auto written = refined->find(camera_id);
    if (written == refined->end() || camera.params.empty() || disproved.count(camera_id)) continue;
    // What averaging used: the view graph's estimate, else the database's value.
    double used = camera.params[0];
    for (const CameraCalibration& estimate : calibration.cameras) {
      if (estimate.camera_id == camera_id)
        used = estimate.estimated ? estimate.estimated_focal_px : camera.params[0];
    }
    change = std::max(change, std::abs(written->second.params[0] / used - 1.0));
  }
  return change;
}

MapperOptions SecondPassOptions(const MapperOptions& options) {
  MapperOptions second = options;
  second.bundle_adjustment = PastTheFocalValley(options.bundle_adjustment);
  return second;
}

void MergePassSummaries(const MapperSummary& first, MapperSummary* second) {
  for (CameraIntrinsicsSummary& camera : second->cameras) {
    for (const CameraIntrinsicsSummary& earlier : first.cameras) {
      if (earlier.camera_id != camera.camera_id) continue;
      camera.view_graph = earlier.view_graph;
      camera.prior_params = earlier.prior_params;
    }
  }
  for (const MapperStageTiming& timing : first.timings) {
    auto it = std::find_if(second->timings.begin(), second->timings.end(),
                           [&](const MapperStageTiming& t) { return t.stage == timing.stage; });
    if (it == second->timings.end()) {
      second->timings.push_back(timing);
    } else {
      it->seconds += timing.seconds;
    }
  }
  second->total_seconds += first.total_seconds;
  second->num_averaging_passes = 2;
  second->calibration_pass = first.calibration_pass;
}

}  // namespace ramap
