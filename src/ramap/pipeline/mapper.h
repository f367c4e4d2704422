// The mapper: a COLMAP database in, one COLMAP model per connected component out, by motion
// averaging instead of incremental bundle adjustment. The stages follow DESIGN.md and the method
// section of "Pushing the Envelope of Rotation Averaging for Visual SLAM" (Li, Yuan, Latecki,
// Ling):
//   1. relative rotations of every verified pair (grid-selected six points, Kneip's solvers);
//   2. pose graph: keyframe windows for sequences, one view graph for collections;
//   3. robust rotation averaging with pruning and a certificate;
//   4. pair directions with the averaged rotations, then translation averaging on feature tracks;
//   5. triangulation with the poses fixed;
//   6. optionally, bundle adjustment.
// With position priors (GPS), each component is georegistered after translation averaging
// (pipeline/georegistration.h), translation averaging is solved again with the priors as weak
// rows, and the model is triangulated, refined and written in the priors' metric frame.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "ramap/averaging/pair_directions.h"
#include "ramap/averaging/rotation_averaging.h"
#include "ramap/averaging/translation_averaging.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/graph/keyframes.h"
#include "ramap/pipeline/georegistration.h"
#include "ramap/pipeline/structure.h"
#include "ramap/pipeline/view_graph_calibration.h"
#include "ramap/refine/bundle_adjustment.h"
#include "ramap/scene/features.h"
#include "ramap/scene/image_order.h"
#include "ramap/scene/reconstruction.h"

namespace ramap {

struct MapperOptions {
  // Focal lengths of uncalibrated cameras (prior_focal_length 0) from the view graph, first.
  ViewGraphCalibrationOptions view_graph_calibration;
  RelativePoseOptions relative_pose;
  InputOrder order = InputOrder::kAuto;
  KeyframeOptions pose_graph;
  RotationAveragingOptions rotation_averaging;
  PairDirectionOptions pair_direction;
  TranslationAveragingOptions translation_averaging;
  StructureOptions structure;
  // What to do with position priors, when RunMapper is given any.
  GeoregistrationOptions georegistration;
  // Final bundle adjustment ("averaging + BA"), on by default: averaging alone gives up 2-33 AUC@3
  // points to COLMAP on the benchmark sets (BENCHMARKS.md, mapper table) and cannot fix a focal
  // length the view graph leaves free; with BA ramap matches COLMAP. Averaging alone (false) is
  // the fast option, 3-10x quicker.
  bool refine = true;
  BundleAdjustmentOptions bundle_adjustment;
  // When bundle adjustment moves a focal length by more than this fraction from the value
  // averaging used (a guess the view graph could not correct: forward motion, a turntable), the
  // whole pipeline runs again through the refined intrinsics: averaging through a focal length 2x
  // off bends the model more than BA can straighten (kitti07_first160 from COLMAP's guess). 0:
  // never.
  double max_focal_change_in_bundle_adjustment = 0.05;
  // When some camera's focal length is unknown and the view graph could not estimate it, the first
  // bundle adjustment only finds the intrinsics for a second pass (averaging through them, then
  // the final BA), so it adjusts at most this many points, each image keeping at least 50 of its
  // observations. A focal length far from the guess takes BA 100-400 iterations to reach; on fewer
  // points each is cheaper (measured: templeRing 12.3 -> 4.4 s; kitti07_first160, when its guess
  // was kept, 111 -> 21 s; the same focal length after the second pass within 0.3%). 0: the
  // first BA is a full one.
  int calibration_num_points = 2000;
  // Components with fewer images are not written (COLMAP's Mapper.min_model_size is 10; ramap
  // writes smaller ones too because small data sets are common among its users).
  int min_component_size = 3;
  // Threads for the per-pair relative pose estimation.
  int num_threads = 2;

  void Check() const;
};

struct MapperStageTiming {
  std::string stage;
  double seconds = 0.0;
};

// Why an image or an edge is missing from the output.
struct DroppedItem {
  std::string what;  // "IMAGE_NAME" or "NAME1 NAME2"
  std::string reason;
};

struct MapperComponentSummary {
  int num_images = 0;
  int num_points = 0;
  int num_observations = 0;
  double mean_reprojection_error_px = 0.0;
  int num_rotation_edges = 0;
  int num_pruned_edges = 0;
  bool rotation_certified = false;
  double certificate_bound_deg = 0.0;
  double max_rotation_residual_deg = 0.0;
  int num_translation_constraints = 0;
  int num_solver_iterations = 0;
  BundleAdjustmentSummary bundle_adjustment;  // zeros when not refined
  GeoregistrationSummary georegistration;     // num_priors 0 when run without priors
};

// The intrinsics of one camera through the stages.
struct CameraIntrinsicsSummary {
  uint32_t camera_id = 0;
  std::string model;
  bool prior_focal_length_known = false;  // the database's prior_focal_length flag
  std::vector<double> prior_params;       // as the database gives them
  CameraCalibration view_graph;           // camera_id 0 when not calibrated from the view graph
  std::vector<double> final_params;       // as written (after BA, when refined)
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
  std::vector<DroppedItem> prior_outliers;  // position priors the georegistration rejected
  std::vector<MapperStageTiming> timings;
  double total_seconds = 0.0;
};

struct MapperResult {
  // Largest component first; each georegistered one in the priors' frame (summary.components[k]
  // says which).
  std::vector<Reconstruction> reconstructions;
  MapperSummary summary;
  // The geodetic origin of that frame (east-north-up), when the priors had one.
  std::optional<GeodeticPoint> geodetic_origin;
};

// Runs every stage on `database`. Throws InputError (naming `source`, e.g. the database path) when
// nothing can be reconstructed: no verified pairs, no relative pose, no component of
// min_component_size images. `progress` receives one line per stage. `priors` (keyed by image id)
// georegister the components that have enough of them; the others are written as without priors,
// with the reason in their summary.
MapperResult RunMapper(const FeatureDatabase& database, const MapperOptions& options,
                       const std::string& source, std::ostream* progress = nullptr,
                       const PositionPriors& priors = PositionPriors());

}  // namespace ramap
