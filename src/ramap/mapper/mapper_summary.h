// What the mapper reports besides its models: per stage, per component and per camera, and why each
// image or edge missing from the output is missing (summary.json).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/estimators/prior_alignment.h"
#include "ramap/estimators/reregistration.h"
#include "ramap/estimators/view_graph_calibration.h"
#include "ramap/mapper/stage_log.h"
#include "ramap/refine/bundle_adjustment.h"
#include "ramap/refine/given_intrinsics_check.h"
#include "ramap/scene/features.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

struct MapperComponentSummary {
  int num_images = 0;
  int num_points = 0;
  int num_observations = 0;
  double mean_reprojection_error_px = 0.0;
  int num_rotation_edges = 0;
  int num_pruned_edges = 0;
  bool rotation_certified = false;
  double certificate_bound_deg = 0.0;
  double certificate_cycle_lower_bound_deg = 0.0;  // see RotationCertificate
  double max_rotation_residual_deg = 0.0;
  int num_rotation_factorizations = 0;  // RotationAveragingResult::factorizations
  RotationAveragingTimings rotation_seconds;
  // Pair directions their triangles did not support (averaging/direction_consistency.h), the
  // tested pairs' median triangle residual and the threshold it gave.
  int num_rejected_directions = 0;
  double direction_median_residual_deg = 0.0;
  double direction_threshold_deg = 0.0;
  // Pair rows and track constraints translation averaging dropped as outliers.
  int num_rejected_translation_rows = 0;
  int num_translation_constraints = 0;
  int num_solver_iterations = 0;
  int num_factorizations = 0;
  int num_translation_windows = 0;  // 0: translation averaging in one system
  // The images averaging placed badly that were tried again from the points.
  std::vector<ReregisteredImage> reregistered_images;
  BundleAdjustmentSummary bundle_adjustment;  // zeros when not refined
  // The images bundle adjustment detached the most observations from (gross reprojection errors),
  // by name, most first; at most 20.
  std::vector<std::pair<std::string, int>> most_filtered_images;
  GivenIntrinsicsTestSummary given_intrinsics_test;  // no groups when nothing given was tested
  PriorAlignmentSummary prior_alignment;             // num_priors 0 when run without priors
};

// The intrinsics of one camera through the stages.
struct CameraIntrinsicsSummary {
  uint32_t camera_id = 0;
  std::string model;
  bool prior_focal_length_known = false;  // the database's prior_focal_length flag
  std::vector<double> prior_params;       // as the database gives them
  // Where the prior focal length came from: EXIF (with its resize or crop), the user, or a guess;
  // from a database, its prior_focal_length flag.
  std::string focal_source;
  CameraCalibration view_graph;      // camera_id 0 when not calibrated from the view graph
  std::vector<double> final_params;  // as written (after BA, when refined)
  std::string final_model;           // as written: a distortion model may have been added
};

struct MapperSummary {
  int num_images = 0;
  // 2 when bundle adjustment moved the intrinsics enough that averaging ran again through them.
  int num_averaging_passes = 1;
  // The first pass's bundle adjustment only calibrated (a camera the view graph could not
  // estimate; MapperOptions::calibration_num_points): a second pass always follows.
  bool calibration_pass = false;
  std::vector<CameraIntrinsicsSummary> cameras;
  int num_verified_pairs = 0;
  int num_relative_poses = 0;
  int num_registered_images = 0;
  bool sequential = false;
  int num_keyframes = 0;
  int num_loop_edges = 0;
  std::vector<MapperComponentSummary> components;
  std::vector<DroppedItem> dropped_images;
  std::vector<DroppedItem> dropped_edges;
  std::vector<DroppedItem> prior_outliers;  // pose priors the prior alignment rejected
  std::vector<MapperStageTiming> timings;
  double total_seconds = 0.0;
  // The process's peak resident memory when the mapper returned (MiB): what the run needed.
  double peak_rss_mib = 0.0;
};

// Each camera's intrinsics as given, as the view graph estimated them, and as written (from the
// largest model that holds the camera).
std::vector<CameraIntrinsicsSummary> SummariseIntrinsics(
    const FeatureDatabase& database, const ViewGraphCalibrationSummary& calibration,
    const std::vector<Reconstruction>& reconstructions);

// Counts the registered images and lists every other one with its reason from `image_reasons`.
void ListUnregisteredImages(const FeatureDatabase& database,
                            const std::vector<Reconstruction>& reconstructions,
                            std::map<uint32_t, std::string>* image_reasons, MapperSummary* summary);

}  // namespace ramap
