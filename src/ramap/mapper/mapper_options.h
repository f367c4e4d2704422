// Every option of the mapper's stages, with their defaults (`ramap mapper --help` lists them).
#pragma once

#include <string>
#include <vector>

#include "ramap/averaging/direction_consistency.h"
#include "ramap/averaging/pair_directions.h"
#include "ramap/averaging/rotation_averaging.h"
#include "ramap/averaging/translation_averaging.h"
#include "ramap/averaging/windowed_translation_averaging.h"
#include "ramap/estimators/prior_alignment.h"
#include "ramap/estimators/reregistration.h"
#include "ramap/estimators/rotations.h"
#include "ramap/estimators/track_triangulation.h"
#include "ramap/estimators/view_graph_calibration.h"
#include "ramap/geometry/relative_pose.h"
#include "ramap/graph/keyframes.h"
#include "ramap/mapper/pose_prior_source.h"
#include "ramap/refine/bundle_adjustment.h"
#include "ramap/refine/given_intrinsics_check.h"
#include "ramap/scene/image_order.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct MapperOptions {
  // Focal lengths of uncalibrated cameras (prior_focal_length 0) from the view graph, first.
  ViewGraphCalibrationOptions view_graph_calibration;
  RelativePoseOptions relative_pose;
  InputOrder order = InputOrder::kAuto;
  KeyframeOptions view_graph;
  RotationAveragingOptions rotation_averaging;
  // Resolved into rotation_averaging.use_edge_weights per run (UseRotationEdgeWeights).
  EdgeWeighting rotation_edge_weights = EdgeWeighting::kAuto;
  // Where the edges are not weighted, rotation averaging runs again with them weighted, and that
  // solution is kept where the two differ by more than rotation_fold_min_difference_deg at some
  // image and it leaves out fewer inliers: the unweighted one folded the scene along symmetric
  // or repeated structure (estimators/rotation_folds.h).
  bool rotation_fold_check = true;
  double rotation_fold_min_difference_deg = 20.0;
  PairDirectionOptions pair_direction;
  // Which pair directions translation averaging may use: those their triangles support.
  DirectionConsistencyOptions direction_consistency;
  TranslationAveragingOptions translation_averaging;
  // Long sequences: translation averaging window by window, joined by shared frames and loops.
  WindowedTranslationOptions translation_windows;
  TrackTriangulationOptions triangulation;
  // Images the triangulated points leave out, placed again from those points.
  ReregistrationOptions reregistration;
  // Where a job's pose priors come from (RunMapperJob; RunMapper takes them loaded).
  PosePriorSource prior_source;
  // What to do with pose priors, when RunMapper is given any.
  PriorAlignmentOptions prior_alignment;
  // Final bundle adjustment ("averaging + BA"), on by default: averaging alone is less accurate
  // than COLMAP on the benchmark sets and cannot fix a focal length the view graph leaves free;
  // with BA ramap matches COLMAP. Averaging alone (false) is the fast option (BENCHMARKS.md,
  // "Same database, known intrinsics").
  bool refine = true;
  // Without that final BA (refine false): bundle adjustment of the poses, and of the intrinsics BA
  // would refine, on the calibration_num_points longest tracks only, then every track triangulated
  // again through them. It is the cheap multi-view step after averaging: nearly the full BA's
  // accuracy in less time, where averaging alone falls far behind without a calibration and cannot
  // calibrate a turntable at all; the full BA still places the cameras closer (BENCHMARKS.md,
  // "What each part of the back end buys"). Given intrinsics are tested on the subset too.
  // false: averaging alone.
  bool subset_adjustment = true;
  BundleAdjustmentOptions bundle_adjustment;
  // Rounds of bundle adjustment, each followed by every track triangulated again. A second round
  // costs much more time and gains nothing on the benchmark databases but sceaux_castle, whose
  // lens the given PINHOLE camera ignores (docs/benchmark-history.md, "BA in rounds").
  int num_refinement_rounds = 1;
  // Before it, whether the data prove given intrinsics wrong (refine/given_intrinsics_check.h).
  GivenIntrinsicsTestOptions given_intrinsics_test;
  // When bundle adjustment moves a focal length by more than this fraction from the value
  // averaging used (a guess the view graph could not correct: forward motion, a turntable), the
  // whole pipeline runs again through the refined intrinsics: averaging through a focal length 2x
  // off bends the model more than BA can straighten (kitti07_first160 from COLMAP's guess). 0:
  // never. Not for a given focal length that refine/given_intrinsics_check.h proved wrong: the test
  // crossed its valley from averaging's poses, and a second pass bought nothing there with given
  // focal lengths far from the truth either way (docs/benchmark-history.md, "A focal length proved
  // wrong").
  double max_focal_change_in_bundle_adjustment = 0.05;
  // When some camera's focal length is unknown and the view graph could not estimate it, the first
  // bundle adjustment only finds the intrinsics for a second pass (averaging through them, then
  // the final BA), so it adjusts at most this many points, each image keeping at least 50 of its
  // observations. A focal length far from the guess takes BA many iterations to reach; on fewer
  // points each is cheaper, and the second pass ends at the same focal length. 0: the first BA is
  // a full one. The same subset calibrates, before the full BA, any run that refines a focal
  // length: the full BA then starts past the valley and stops at the ordinary tolerance, in much
  // less time and at the same accuracy but on one set (docs/benchmark-history.md, "Self-calibration
  // on a subset first").
  int calibration_num_points = 2000;
  // A calibration pass keeps its intrinsics alone: the second pass averages again through them and
  // calibrates again on its own subset, from a start this close. So the calibration pass adjusts
  // at most this many points and averages translations with at most this many tracks
  // (TranslationAveraging.max_num_tracks), takes its relative poses from Nister's five-point
  // solver (RelativePose.nister_five_point), and its BA stops once the intrinsics have settled.
  // The per-image quotas (TranslationAveraging.min_tracks_per_image, 50 observations an image in
  // BA) still hold, so a large scene gets more. A smaller budget makes the calibration pass
  // cheaper, and the second pass, which calibrates again, ends as accurate
  // (docs/benchmark-history.md, "What a calibration pass needs"). 0: as the second pass.
  int calibration_pass_num_tracks = 300;
  // After the subset found the intrinsics, the full bundle adjustment holds them (unless some
  // camera was given: its test needs the full adjustment's intrinsics freed), through bearings
  // undistorted with them: it then costs what a calibrated run's does, since the residuals no
  // longer pass through the camera model and no point's row couples with a shared intrinsics block.
  // The subset's thousands of points fix a focal length and k1 about as well as the full BA did:
  // the poses' accuracy moves by a fraction of a point either way (docs/benchmark-history.md,
  // "Where the seconds of bundle adjustment go"). 0: the full BA refines them again.
  bool calibration_subset_only = true;
  // Components with fewer images are not written (COLMAP's Mapper.min_model_size is 10; ramap
  // writes smaller ones too because small data sets are common among its users).
  int min_component_size = 3;
  // Threads for the per-pair stages (relative poses and, after rotation averaging, pair
  // directions), triangulation, and the dense kernels of the sparse factorisations when the BLAS
  // is OpenBLAS. The model is the same for every run with the same number; across numbers,
  // OpenBLAS's kernels split their sums differently and the poses differ in the last digits.
  int num_threads = 2;

  void Check() const;
  // Whether some bundle adjustment follows averaging: the final one or the subset's.
  bool AdjustsAfterAveraging() const { return refine || subset_adjustment; }
  // The bounds of triangulation through averaging's poses: those of a BA's start when BA follows.
  TrackTriangulationOptions TriangulationOfAveragedPoses() const {
    return AdjustsAfterAveraging() ? triangulation.ForBundleAdjustmentStart() : triangulation;
  }
  // Translation averaging's options on the mapper's threads (num_threads).
  TranslationAveragingOptions TranslationAveragingWithThreads() const {
    TranslationAveragingOptions options = translation_averaging;
    options.num_threads = num_threads;
    return options;
  }
};

// Every mapper option, by section (each stage's struct declares its own; mapper_option_table.cc
// assembles them and declares the mapper's own): `ramap mapper`, `reconstruct`, `relative_poses`,
// `rotation_averager` and `bundle_adjuster` register them, summary.json lists them, Python takes
// them by these names, and docs/options.md is generated from them.
const OptionTable<MapperOptions>& MapperOptionTable();

// The declarations of the given sections (and the single options named in `extra`), in table
// order: the subset a command that runs some of the stages registers.
OptionTable<MapperOptions> MapperOptionSections(const std::vector<std::string>& sections,
                                                const std::vector<std::string>& extra = {});

}  // namespace ramap
