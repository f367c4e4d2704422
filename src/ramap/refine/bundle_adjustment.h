// Optional final bundle adjustment (Ceres): camera poses and 3D points refined together, and the
// intrinsics of each camera (shared by its images) as COLMAP's options ask. This turns "motion
// averaging" into "motion averaging + BA", the variant that ramap compares with COLMAP's mapper.
//
// With the intrinsics fixed, residuals are taken on the normalised image plane of each
// observation's undistorted bearing and multiplied by the camera's focal length, so they are in
// pixels (exactly for pinhole cameras, to first order for distorted ones) while the camera model
// stays out of the cost function. A camera whose intrinsics are refined (perspective models:
// SIMPLE_PINHOLE, PINHOLE, SIMPLE_RADIAL, RADIAL, OPENCV, FULL_OPENCV) has pixel residuals through
// its model instead, the keypoint against the projection, and reconstruction->cameras is updated.
//
// Camera pose priors (GPS in the model's frame, after prior alignment) add residuals
// (c - p) / sigma per axis: a weak constraint beside thousands of pixel residuals per camera, which
// keeps the model in the priors' frame and scale instead of holding one camera fixed.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <ostream>
#include <set>
#include <vector>

#include "ramap/scene/features.h"
#include "ramap/scene/pose_prior.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct BundleAdjustmentOptions {
  // Ceres iterations (COLMAP's global BA uses at most 50).
  int max_num_iterations = 50;
  // Stop when an iteration lowers the cost by less than this fraction (Ceres' default is 1e-6).
  // The looser tolerance stops in far fewer iterations at the same accuracy, as close to the
  // truth as COLMAP's mapper (Herz-Jesus-P8 with every point).
  double function_tolerance = 1e-4;
  // Also stop once two successive accepted steps each moved every camera by less than this angle
  // (its rotation, its centre seen from its points, its refined focal length and principal
  // point; refine/pose_convergence.h), 0: off. The points left unsettled are triangulated again
  // after BA. A thousandth of a degree lies far below what AUC@1 resolves; a long chain still
  // drifting by more per step iterates to function_tolerance as before. The steps it saves only
  // settle points, so the mapper gets faster at the same accuracy (docs/benchmark-history.md,
  // "Where the seconds of bundle adjustment go").
  double pose_tolerance_deg = 1e-3;
  // Where the solve refines some focal length, that stop looks at the intrinsics alone: for a BA
  // kept only for its intrinsics (the mapper's calibration on a subset of the points, before a
  // full BA or a second pass that starts the poses afresh). Set by the mapper, not an option.
  bool settle_intrinsics_only = false;
  // Robust loss scale in pixels (Cauchy); COLMAP's default loss is a plain squared error, a soft
  // robust loss protects against the wrong matches that averaging lets through. 1 px (GLOMAP's
  // Huber scale too) rather than 2 px: it makes templeRing clearly more accurate and barely moves
  // the other sets, for some more iterations (BENCHMARKS.md, "What each part of the back end
  // buys").
  double loss_scale_px = 1.0;
  // Where the median reprojection error at the start exceeds loss_scale_px, the first solve's loss
  // scale is this many times that median, and a second solve follows at loss_scale_px (0: off).
  // A loss narrower than the typical error treats the inliers as outliers, and BA follows the few
  // observations that fit already into the wrong basin (sceaux_castle with its PINHOLE camera
  // held); where the start lies below the loss scale, as on the other benchmark sets, nothing
  // changes (docs/benchmark-history.md, "A wide loss where BA starts far").
  double wide_start_loss_factor = 2.0;
  // Observations whose bearing is within this angle of the image plane are skipped (fisheye edges).
  double min_bearing_z = 0.1;
  int num_threads = 2;
  // Observations with a larger reprojection error after BA are detached from their points, and
  // points left with fewer than two observations removed (COLMAP filters at 4 px).
  double max_reprojection_error_px = 4.0;
  // BA solves again without the detached observations only when they are at least this fraction
  // of all (0: whenever any was detached, as COLMAP's global BA). Under the 1 px Cauchy loss an
  // observation 4 px off weighs at most 1/17 of an inlier, so a few of them barely pull the
  // solution, and solving again costs more time than it moves the result
  // (docs/benchmark-history.md, "Where the seconds of bundle adjustment go"). Many detached
  // observations (an image placed wrong) still get the second solve. 5%, not 1%: the mapper's start
  // keeps observations up to 1 deg off (TrackTriangulationOptions::start_max_error_deg), so sets
  // whose images are all placed right detach a few percent (docs/benchmark-history.md,
  // "Observations kept where BA starts").
  double min_filtered_fraction_to_solve_again = 0.05;
  // Points adjusted at most (0: all): the longest tracks first, and every image keeps at least
  // min_observations_per_image of its observations; the mapper re-triangulates every track
  // afterwards. Bounds BA's time on large scenes. Far fewer points cost some accuracy (on
  // Herz-Jesus-P8), so the cap lies above the point counts of the benchmark scenes but the
  // largest, fountain-P11, which it trims.
  int max_num_points = 20000;
  int min_observations_per_image = 200;
  // Points seen in fewer images are adjusted only for an image that has fewer than
  // min_observations_per_image observations of longer tracks (then all of its own); the mapper
  // triangulates them again after BA. A point seen twice is checked by no third view: a wrong
  // match near the epipolar line fits it as well as a right one (GLOMAP, too, builds its tracks
  // from three views on). Leaving them out keeps the accuracy and shortens the full BA
  // (docs/benchmark-history.md, "Points seen in two images"). 2: every point.
  int min_track_length = 3;
  // Observations of one point adjusted at most (0: all), spread evenly over its track's images;
  // the others rejoin when every track is triangulated again. Schur elimination's work grows with
  // the square of a track's length, its information about the poses only linearly. Only long
  // videos have such tracks; 60 speeds up the long drives' BA without costing kitti07_first160
  // accuracy, which lower caps did (docs/benchmark-history.md, "Where the seconds of bundle
  // adjustment go").
  int max_observations_per_point = 60;
  // Intrinsics refined with the poses (COLMAP's --BundleAdjustment.refine_* and their defaults).
  // "Extra" parameters are the distortion coefficients.
  bool refine_focal_length = true;
  bool refine_principal_point = false;
  bool refine_extra_params = true;
  // A camera without a prior focal length (COLMAP's "unknown": prior_focal_length 0) has a guessed
  // principal point too, the image's centre. Where its focal length is refined, so is its
  // principal point, as refine_principal_point would. A principal point off the centre by p px
  // turns every camera by about p / f radians, which no pose can undo; refined, the benchmark sets'
  // rotations and principal points come much closer to the truth (BENCHMARKS.md, "The principal
  // point of an uncalibrated camera").
  bool refine_guessed_principal_point = true;
  // A refined guessed principal point farther from where BA started than this fraction of the
  // image's width (x) or height (y) is suspect: views that cannot tell it from a turn of every
  // camera (little rotation between them) let it drift. BA solves again with it held where it
  // started, and keeps it held unless the move lowers its camera's median reprojection error by
  // at least min_principal_point_error_decrease: a cropped photo's principal point does lie far
  // off the centre (a 65% crop anywhere puts it up to 27% off), and holding it there bends the
  // model (BENCHMARKS.md, "Internet conditions"). One outside the image is always held.
  double max_principal_point_shift = 0.1;
  double min_principal_point_error_decrease = 0.2;
  // A camera whose focal length the database marks known (prior_focal_length 1: the user's
  // calibration, or EXIF) keeps its focal length and principal point; its distortion is refined as
  // refine_extra_params says (EXIF gives none, and the data determine it well).
  // refine/given_intrinsics_check.h then decides whether the data prove the focal length wrong.
  // Refining such a focal length from averaging's poses chased their errors instead: given their
  // true calibrations, one camera per image, templeRing's and kitti07_first160's focal lengths
  // moved away from the truth (BENCHMARKS.md, "A calibration the user gives, one camera per
  // image").
  bool keep_prior_intrinsics = true;
  // Among those cameras, the ones whose given focal length the test proved wrong: BA refines it
  // from the test's value, as COLMAP refines every focal length, and still holds their principal
  // point. The test's subset of 2000 points leaves the focal length less certain than the full
  // adjustment does (docs/benchmark-history.md, "A focal length proved wrong").
  std::set<uint32_t> disproved_given_cameras;
  // Cameras with the same model, size, parameters and prior flag (one EXIF value, one user
  // calibration, or one guess: COLMAP's one camera per image) share one set of intrinsics. The
  // mapper's view-graph calibration estimates them as one too.
  bool share_identical_intrinsics = true;
  // function_tolerance while some camera's focal length is refined: it couples with depth and
  // moves slowly. From COLMAP's guess on templeRing (half the true focal length) the ordinary
  // tolerance stops far short of the truth, and this one reaches it within
  // intrinsics_max_num_iterations. A tenth of it (1e-7) took more dogleg steps on the real sets
  // without a calibration and ended at the same poses (`KINDS=bench-unknown-intrinsics
  // scripts/reproduce_mapper.sh` with each).
  double intrinsics_function_tolerance = 1e-6;
  int intrinsics_max_num_iterations = 200;

  void Check() const;
};

// Its options (--BundleAdjustment.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<BundleAdjustmentOptions>& BundleAdjustmentOptionTable();

struct BundleAdjustmentSummary {
  int num_images = 0;
  int num_points = 0;
  int num_observations = 0;
  double initial_rmse_px = 0.0;
  double final_rmse_px = 0.0;  // over the observations kept after filtering
  int num_iterations = 0;
  int num_filtered_observations = 0;
  // 2 when BA solved again: without the detached observations
  // (min_filtered_fraction_to_solve_again), or at loss_scale_px after a wide first loss.
  int num_solves = 0;
  // The first solve's loss scale where it was wider than loss_scale_px (wide_start_loss_factor),
  // else 0.
  double wide_start_loss_px = 0.0;
  // Where they were: image id -> observations detached from their points (gross errors gather in
  // an image whose pose or matches are wrong).
  std::map<uint32_t, int> filtered_per_image;
  int num_priors = 0;  // pose priors of registered images
  bool converged = false;
  // Cameras whose refined guessed principal point moved beyond max_principal_point_shift without
  // the reprojection errors to show for it: BA solved again with each held where it started.
  std::vector<uint32_t> principal_points_drifted;
  // Cameras whose guessed principal point moved as far and lowered their median reprojection
  // error by min_principal_point_error_decrease or more: kept where BA moved it.
  std::vector<uint32_t> principal_points_confirmed;
  // Whether the last solve ended because the poses had settled (pose_tolerance_deg) before Ceres's
  // function tolerance was reached.
  bool poses_settled = false;
  double seconds = 0.0;
};

// The points BundleAdjust would adjust under `options` (max_num_points, min_track_length,
// min_observations_per_image, max_observations_per_point): a copy of `reconstruction` with the
// other points removed, and their observations and the thinned ones detached.
Reconstruction PointsForBundleAdjustment(const Reconstruction& reconstruction,
                                         const BundleAdjustmentOptions& options);

// `options` once the focal length's valley has been crossed (a subset adjusted it, a test freed it,
// or a first pass found it): refined intrinsics then stop at the ordinary function_tolerance
// instead of the tight intrinsics_function_tolerance.
BundleAdjustmentOptions PastTheFocalValley(BundleAdjustmentOptions options);

// `options` for a BA on a subset of at most `max_num_points` points (0: all), the longest tracks:
// each image keeps at least 50 of its observations (or min_observations_per_image, if fewer), and
// each point every observation, since the count already bounds the cost.
BundleAdjustmentOptions PointSubsetOptions(BundleAdjustmentOptions options, int max_num_points);

// Whether `camera` arrived with values the user or EXIF gave and `options` keeps them
// (keep_prior_intrinsics).
bool HeldAsGiven(const BundleAdjustmentOptions& options, const Camera& camera);
// Whether BundleAdjust refines some intrinsic parameter of `camera` under `options`.
bool RefinesIntrinsics(const BundleAdjustmentOptions& options, const Camera& camera);
// Whether it refines the focal length of `camera` (not held as given, a perspective model).
bool RefinesFocalLength(const BundleAdjustmentOptions& options, const Camera& camera);

// Each camera of `reconstruction` mapped to the one whose intrinsics it shares in BA (itself, or
// the lowest id with the same model, size, parameters and prior flag), under `options`.
std::map<uint32_t, uint32_t> SharedIntrinsics(const BundleAdjustmentOptions& options,
                                              const Reconstruction& reconstruction);

// Refines `reconstruction` in place. `bearings` holds, per image id, the undistorted unit bearing
// of each of its points2D (same order). `focal_lengths_px` holds each camera's mean focal length.
// Refined intrinsics are written to reconstruction->cameras; `bearings` are then stale for them.
// The first registered image's pose is held fixed (gauge), unless `priors` (keyed by image id, in
// the reconstruction's frame) cover three or more registered images. With `progress`, each solve
// draws its iterations there (util/progress_line.h).
BundleAdjustmentSummary BundleAdjust(
    const KeypointBearings& bearings, const std::map<uint32_t, double>& focal_lengths_px,
    Reconstruction* reconstruction,
    const BundleAdjustmentOptions& options = BundleAdjustmentOptions(),
    const std::map<uint32_t, PosePrior>& priors = {}, std::ostream* progress = nullptr);

}  // namespace ramap
