// Focal lengths of cameras without a calibration, from the view graph, before rotation averaging.
//
// For a pair with fundamental matrix F (x2^T F x1 = 0, pixels) and the right calibrations K1, K2,
// E = K2^T F K1 is an essential matrix: two equal singular values and a third of zero. A pair's
// cost at trial focal lengths is (s1 - s2) / (s1 + s2) of K2^T F K1 (Sweeney, Sattler, Hollerer,
// Turk, Pollefeys, "Optimizing the viewing graph for structure-from-motion", ICCV 2015; GLOMAP's
// view-graph calibration minimises the same cost). Each camera's focal length minimises the robust
// (Cauchy) sum of the costs of the pairs that see it, plus a weak prior towards the database's
// value; a camera shared by many images is estimated once. Cameras linked by pairs are estimated
// in turns (coordinate descent), each by a search over a log-spaced range and a golden-section
// refinement, so no start has to be close.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/scene/camera.h"
#include "ramap/scene/features.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct ViewGraphCalibrationOptions {
  // Estimate the focal length of every camera whose prior_focal_length flag is 0 (COLMAP's
  // "unknown": no EXIF, no user calibration).
  bool enable = true;
  // Test given focal lengths too (prior_focal_length 1: EXIF's, or the user's): a given value is
  // where the camera starts, kept when the pairs confirm it or cannot tell, and replaced by the
  // estimate when they prove it wrong (given_focal_tolerance). The mapper tests none when bundle
  // adjustment may not refine focal lengths (the user holds them).
  bool test_given_focal_lengths = true;
  // A trusted estimate more than this fraction away from a given focal length replaces it. Smaller
  // errors are left to the test of given intrinsics after averaging
  // (refine/given_intrinsics_check.h), which measures them on the reprojection error; averaging
  // bears them (a focal length 20% off bends relative rotations by a fraction of a degree at the
  // image centre).
  double given_focal_tolerance = 0.2;
  // Search range, absolute: the focal length over the image's longest side, 0.25 to 20 (a
  // field of view of 127 to 2.9 degrees across it), whatever the prior says, so that an EXIF value
  // 10x off is still tested back.
  double min_focal_ratio = 0.25;
  double max_focal_ratio = 20.0;
  // A camera is estimated from at least this many pairs with a fundamental matrix...
  int min_num_pairs = 3;
  // ...each with at least this many verified matches.
  int min_num_inliers = 30;
  // At most this many pairs per camera (those with the most inliers) enter its cost.
  int max_pairs_per_camera = 500;
  // Cauchy scale on a pair's cost.
  double loss_scale = 0.02;
  // Weight of the prior term (log(f / f_prior) / ln 2)^2, against pair costs of at most ~1 each.
  double prior_weight = 0.01;
  // Rounds of camera-by-camera minimisation (one where a single camera is estimated).
  int num_rounds = 3;
  // With several cameras, each round searches a camera's focal length within this factor of its
  // start (the common one, or its given value), not its whole range (view_graph_calibration.cc,
  // RoundRange).
  double round_search_factor = 3.0;
  // An estimate whose pairs' median cost stays above this is not trusted (F inconsistent with
  // any focal length: a wrong camera model, or matches of a moving scene).
  double max_median_cost = 0.1;
  // An estimate is trusted only when the cost is well determined: at focal lengths 20% below and
  // 25% above it, the pairs' robust cost must be at least (1 + min_cost_rise) times its minimum.
  // The threshold lies between the rises the benchmark sets show: the sets whose views fix the
  // focal length (Herz-Jesus-P8 and fountain-P11, from COLMAP's F or ramap's own, and
  // kitti07_first160) rise above it, with estimates near the truth; templeRing (a turntable: every
  // optical axis through one point at one distance, where F leaves the focal length undetermined)
  // and a noise-free synthetic turntable stay below it, and templeRing's estimate is far off
  // (BENCHMARKS.md, "Same database, unknown intrinsics").
  double min_cost_rise = 0.1;

  void Check() const;
};

// Its options (--ViewGraphCalibration.*), each declared once with its range and help
// (util/option_table.h): the command line, Check(), summary.json and Python read them.
const OptionTable<ViewGraphCalibrationOptions>& ViewGraphCalibrationOptionTable();

// What the view graph made of one camera's focal length.
enum class FocalOutcome {
  kEstimated,     // unknown, estimated
  kNotEstimated,  // unknown, the guess kept (see `problem`)
  kConfirmed,     // given, and the estimate agrees within given_focal_tolerance: given value kept
  kDisproved,     // given, and the estimate is trusted and further away: the estimate replaces it
  kUntested,      // given, and the pairs cannot tell (see `problem`): given value kept
};
const char* FocalOutcomeName(FocalOutcome outcome);

// One camera whose focal length was unknown, or given and tested.
struct CameraCalibration {
  uint32_t camera_id = 0;
  bool given = false;               // the database marked the focal length known (EXIF, the user)
  double prior_focal_px = 0.0;      // mean focal length given (COLMAP's guess, or EXIF)
  double estimated_focal_px = 0.0;  // the view graph's estimate (0 when none)
  int num_pairs = 0;                // pairs with a fundamental matrix that entered the cost
  double median_cost = 0.0;         // of those pairs at the estimate
  bool estimated = false;           // the estimate replaced the prior (kEstimated, kDisproved)
  FocalOutcome outcome = FocalOutcome::kNotEstimated;
  std::string problem;  // why the estimate is not trusted, when it is not
};

struct ViewGraphCalibrationSummary {
  std::vector<CameraCalibration> cameras;
  // The views fixed the focal lengths' ratios only (they all look at one point): the estimates'
  // common scale is the given focal lengths' consensus.
  bool scale_from_given = false;
  double seconds = 0.0;
};

// (s1 - s2) / (s1 + s2) of the singular values of K2^T F K1: 0 for a consistent calibration.
double EssentialMatrixCost(const Eigen::Matrix3d& F, const Eigen::Matrix3d& K1,
                           const Eigen::Matrix3d& K2);

// Estimates the focal length of each camera of `cameras` that `database` marks unknown
// (has_prior_focal_length false) from the database's verified pairs (configurations CALIBRATED and
// UNCALIBRATED, whose F is stored), and scales its focal length parameters to the estimate. A
// camera that cannot be estimated (too few pairs, only pure rotations, estimate at the edge of the
// range, pairs inconsistent) keeps its prior and is listed with the reason. With
// test_given_focal_lengths, a camera whose focal length is given is estimated too and keeps its
// value unless the estimate disproves it; then it takes the estimate and is marked unknown
// (has_prior_focal_length false), so that bundle adjustment refines it. With
// `share_identical_cameras`, cameras with the same model, size, parameters and prior flag (COLMAP's
// one camera per image, all with one guess) are estimated as one.
ViewGraphCalibrationSummary CalibrateFocalLengths(const FeatureDatabase& database,
                                                  const ViewGraphCalibrationOptions& options,
                                                  std::map<uint32_t, Camera>* cameras,
                                                  bool share_identical_cameras = true);

}  // namespace ramap
