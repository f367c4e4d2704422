// Accuracy of estimated camera poses against ground truth: registration rate, absolute trajectory
// error (ATE) after a similarity alignment, absolute rotation error, and relative pose error over
// all image pairs summarised as AUC at angular thresholds.
//
// ATE follows Sturm et al., "A Benchmark for the Evaluation of RGB-D SLAM Systems", IROS 2012
// (centres aligned by Umeyama's similarity, then the RMSE of the centre distances). The pairwise
// error and its AUC follow the COLMAP / GLOMAP benchmarks (Pan et al., ECCV 2024): per pair the
// larger of the relative rotation error and the relative translation-direction error, with an
// unregistered image making its pairs failures.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "ramap/eval/auc.h"
#include "ramap/geometry/alignment.h"
#include "ramap/geometry/rotation.h"
#include "ramap/scene/reconstruction.h"
#include "ramap/scene/rigid3.h"
#include "ramap/util/option_table.h"

namespace ramap {

struct PoseEvaluationOptions {
  // Alignment of estimated to ground-truth centres (Sim(3), least squares, by default).
  AlignmentOptions alignment;
  // Thresholds of the relative pose AUC, in degrees (the GLOMAP paper reports 1, 3, 5, 10).
  std::vector<double> auc_thresholds_deg = {1.0, 3.0, 5.0, 10.0};
  AucDefinition auc_definition = AucDefinition::kBenchmarkTrapezoid;
  // A pair whose ground-truth baseline is at most this (ground-truth units) has no meaningful
  // translation direction: only its rotation error counts (COLMAP's min_proj_center_dist). 0
  // still excludes exactly coincident centres.
  double min_baseline = 0.0;
  // Score both orders (i, j) and (j, i) of each pair, as COLMAP's current benchmark does; by
  // default each unordered pair counts once, i before j in input order.
  bool ordered_pairs = false;

  // Throws InputError naming the option (`ramap evaluate`'s names) for a value out of range.
  void Check() const;
};

// Its options, as `ramap evaluate` and Python's ramap.evaluate take them (--auc_thresholds, ...),
// each declared once with its range and help (util/option_table.h).
const OptionTable<PoseEvaluationOptions>& PoseEvaluationOptionTable();

// One input image.
struct ImageEvaluation {
  std::string name;
  bool registered = false;  // in the estimate
  bool has_ground_truth = false;
  bool alignment_inlier = false;  // used by the final alignment fit
  double position_error = -1.0;  // aligned centre distance, ground-truth units; -1 if not evaluated
  double rotation_error_deg = -1.0;  // angle(R_gt^T R_aligned); -1 if not evaluated
};

// Everything below is in ground-truth units or degrees. Statistics that could not be computed
// (no aligned image, no registered pair) are NaN, written as null in JSON.
struct PoseEvaluation {
  int num_images = 0;                  // every input image
  int num_registered = 0;              // input images present in the estimate
  int num_with_ground_truth = 0;       // input images with a ground-truth pose
  int num_evaluated = 0;               // registered and with ground truth: the ATE set
  int num_estimated_not_in_input = 0;  // estimated images not among the input names (ignored)

  // Estimate -> ground truth alignment.
  AlignmentStatus alignment_status = AlignmentStatus::kTooFewPoints;
  Sim3d gt_from_estimate;
  int num_alignment_inliers = 0;

  // Absolute trajectory error over the evaluated images (outliers of a robust fit included).
  double ate_rmse = 0.0;
  double ate_mean = 0.0;
  double ate_median = 0.0;
  double ate_max = 0.0;
  // Scene size from the ground truth of all input images: the path length through the centres in
  // input order (meaningful for sequences), and the extent, the largest distance of a centre from
  // their centroid (meaningful for unordered collections). ATE relative = ate_rmse / size.
  double gt_path_length = 0.0;
  double gt_extent = 0.0;
  double ate_rmse_over_path_length = 0.0;
  double ate_rmse_over_extent = 0.0;

  // Absolute rotation error after alignment, degrees.
  double rotation_error_median_deg = 0.0;
  double rotation_error_mean_deg = 0.0;
  double rotation_error_max_deg = 0.0;

  // Relative pose error over every pair of input images that both have ground truth. For the pair
  // (i, j), rel = cam_j_from_cam_i = cam_j_from_world * (cam_i_from_world)^-1; the rotation error
  // is the angle of R_rel_gt^T R_rel_est, the translation-direction error the angle between the
  // two rel translations (the direction of c_i - c_j in camera j's frame: scale-free). The pair
  // error is the larger; a pair with an unregistered image has error +inf.
  int num_pairs = 0;
  int num_failed_pairs = 0;
  double relative_rotation_error_median_deg = 0.0;     // over pairs of registered images
  double relative_translation_error_median_deg = 0.0;  // idem
  double pair_error_median_deg = 0.0;                  // over all pairs, failures as +inf
  std::vector<double> auc_thresholds_deg;
  std::vector<double> auc;  // in [0, 1], one per threshold
  AucDefinition auc_definition = AucDefinition::kBenchmarkTrapezoid;
  // The recall (share of all pairs, failures included, within a threshold) at 101 thresholds
  // evenly from 0 to the largest AUC threshold: the curve under the AUC, for the report's plot.
  std::vector<double> recall_curve_thresholds_deg;
  std::vector<double> recall_curve;

  std::vector<ImageEvaluation> images;  // in input order
};

// Image name -> cam_from_world of the registered images of a reconstruction.
// `source` (the model's path) names the model in the error for two images of one name.
std::map<std::string, Rigid3d> PosesByName(const Reconstruction& reconstruction,
                                           const std::string& source = "reconstruction");

// Evaluates `estimated` against `ground_truth` over `all_image_names` (the input: names missing
// from `estimated` are failures, names missing from `ground_truth` cannot be scored and are only
// counted). Throws InputError on a duplicate input name or invalid options.
PoseEvaluation EvaluatePoses(const std::map<std::string, Rigid3d>& estimated,
                             const std::map<std::string, Rigid3d>& ground_truth,
                             const std::vector<std::string>& all_image_names,
                             const PoseEvaluationOptions& options = PoseEvaluationOptions());

// Errors of one pair's relative pose cam_j_from_cam_i (see PoseEvaluation), in degrees.
struct PairPoseError {
  double rotation_deg = 0.0;
  double translation_deg = 0.0;  // 0 when the GT baseline is <= min_baseline; 180 when the
                                 // estimated centres coincide but the GT ones do not
  double error_deg() const {
    return rotation_deg > translation_deg ? rotation_deg : translation_deg;
  }
};
PairPoseError RelativePoseError(const Rigid3d& est_cam_i_from_world,
                                const Rigid3d& est_cam_j_from_world,
                                const Rigid3d& gt_cam_i_from_world,
                                const Rigid3d& gt_cam_j_from_world, double min_baseline = 0.0);

// The evaluation as JSON (NaN and infinities as null); per-image rows when `with_images`.
nlohmann::json PoseEvaluationToJson(const PoseEvaluation& evaluation, bool with_images = true);
// Writes PoseEvaluationToJson to `path` atomically; throws InputError when it cannot.
void WritePoseEvaluationJson(const PoseEvaluation& evaluation, const std::string& path);
// A short human-readable table.
std::string FormatPoseEvaluation(const PoseEvaluation& evaluation);

}  // namespace ramap
