// Every option of the mapper's stages, with their defaults (`ramap mapper --help` lists them).
#pragma once

#include "ramap/averaging/direction_consistency.h"
#include "ramap/averaging/pair_directions.h"
#include "ramap/averaging/rotation_averaging.h"
#include "ramap/averaging/translation_averaging.h"
#include "ramap/averaging/windowed_translation_averaging.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/graph/keyframes.h"
#include "ramap/pipeline/georegistration.h"
#include "ramap/pipeline/pose_prior_loading.h"
#include "ramap/pipeline/reregistration.h"
#include "ramap/pipeline/structure.h"
#include "ramap/pipeline/view_graph_calibration.h"
#include "ramap/refine/bundle_adjustment.h"
#include "ramap/refine/given_intrinsics_test.h"
#include "ramap/scene/image_order.h"

namespace ramap {

// Whether rotation averaging weights each edge by its pair's inlier count (IRLS weights times the
// count; RotationAveragingOptions::use_edge_weights).
enum class EdgeWeighting {
  // On when every camera's focal length is known (prior_focal_length 1), off otherwise. Measured
  // (scripts/reproduce_mapper.sh, averaging alone): with the true intrinsics AUC@3 rises on every
  // set (templeRing 59.4 -> 74.8, Herz-Jesus-P8 93.8 -> 97.5, kitti07_first160 59.8 -> 63.7,
  // fountain-P11 97.4 -> 98.3, lund_door 97.89 -> 97.93); through focal lengths from the view
  // graph it falls on three (fountain-P11 50.6 -> 45.4, kitti07_first160 49.9 -> 47.2,
  // Herz-Jesus-P8 89.6 -> 88.9). With BA every set stays within 0.1.
  kAuto,
  kOn,
  kOff,
};

struct MapperOptions {
  // Focal lengths of uncalibrated cameras (prior_focal_length 0) from the view graph, first.
  ViewGraphCalibrationOptions view_graph_calibration;
  RelativePoseOptions relative_pose;
  InputOrder order = InputOrder::kAuto;
  KeyframeOptions pose_graph;
  RotationAveragingOptions rotation_averaging;
  // Resolved into rotation_averaging.use_edge_weights per run (UseRotationEdgeWeights).
  EdgeWeighting rotation_edge_weights = EdgeWeighting::kAuto;
  PairDirectionOptions pair_direction;
  // Which pair directions translation averaging may use: those their triangles support.
  DirectionConsistencyOptions direction_consistency;
  TranslationAveragingOptions translation_averaging;
  // Long sequences: translation averaging window by window, joined by shared frames and loops.
  WindowedTranslationOptions translation_windows;
  StructureOptions structure;
  // Images the triangulated points leave out, placed again from those points.
  ReregistrationOptions reregistration;
  // Where a job's position priors come from (RunMapperJob; RunMapper takes them loaded).
  PosePriorSource prior_source;
  // What to do with position priors, when RunMapper is given any.
  GeoregistrationOptions georegistration;
  // Final bundle adjustment ("averaging + BA"), on by default: averaging alone gives up 0.2-17
  // AUC@3 points to COLMAP on the benchmark sets (BENCHMARKS.md, mapper table) and cannot fix a
  // focal length the view graph leaves free; with BA ramap matches COLMAP. Averaging alone (false)
  // is the fast option, 3-10x quicker.
  bool refine = true;
  BundleAdjustmentOptions bundle_adjustment;
  // Rounds of bundle adjustment, each followed by every track triangulated again. A second round
  // gains nothing on nine of the ten benchmark databases (AUC@3 within 0.4) at 40-70% more BA
  // time; on sceaux_castle, whose lens the given PINHOLE camera ignores, it gains 1.3-4.0 points
  // (BENCHMARKS.md, "BA in rounds").
  int num_refinement_rounds = 1;
  // After it, whether the data prove given intrinsics wrong (refine/given_intrinsics_test.h).
  GivenIntrinsicsTestOptions given_intrinsics_test;
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
  // first BA is a full one. The same subset calibrates, before the full BA, any run that refines
  // a focal length: the full BA then starts past the valley and stops at the ordinary tolerance
  // (unknown intrinsics, one run each: fountain-P11 13.3 -> 6.7 s, templeRing 11.9 -> 6.5 s,
  // Herz-Jesus-P8 4.3 -> 2.2 s, kitti07_first160 22.1 -> 12.0 s; AUC@3 the same within 0.05
  // except kitti07_first160, 57.7 -> 57.1).
  int calibration_num_points = 2000;
  // Components with fewer images are not written (COLMAP's Mapper.min_model_size is 10; ramap
  // writes smaller ones too because small data sets are common among its users).
  int min_component_size = 3;
  // Threads for the per-pair stages (relative poses and, after rotation averaging, pair
  // directions), triangulation, and the dense kernels of the sparse factorisations when the BLAS
  // is OpenBLAS. The model is the same for every run with the same number; across numbers,
  // OpenBLAS's kernels split their sums differently and the poses differ in the last digits.
  int num_threads = 2;

  void Check() const;
};

}  // namespace ramap
