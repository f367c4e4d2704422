#include "ramap/pipeline/mapper_option_table.h"

#include <algorithm>
#include <stdexcept>

#include "ramap/geometry/correspondence_sampling.h"

namespace ramap {

namespace {

using Declaration = OptionDeclaration<MapperOptions>;
using Table = OptionTable<MapperOptions>;

template <typename Access>
Declaration Number(std::string name, Access access, OptionRange range, std::string help = "") {
  return NumberOption<MapperOptions>(std::move(name), access, range, std::move(help));
}

template <typename Access>
Declaration Bool(std::string name, Access access, std::string help = "") {
  return BoolOption<MapperOptions>(std::move(name), access, std::move(help));
}

template <typename Value, typename Access>
Declaration Choice(std::string name, Access access,
                   std::vector<std::pair<std::string, Value>> names, std::string help) {
  return ChoiceOption<MapperOptions>(std::move(name), access, std::move(names), std::move(help));
}

// "auto", "1" and "0" as three values of an enum.
template <typename Value>
std::vector<std::pair<std::string, Value>> AutoOnOff(Value when_auto, Value when_on,
                                                     Value when_off) {
  return {{"auto", when_auto}, {"1", when_on}, {"0", when_off}};
}

void AddRelativePose(Table& t) {
  t.push_back(Number(
      "RelativePose.min_num_inliers",
      [](auto& o) -> auto& { return o.relative_pose.min_num_inliers; }, AtLeast(6),
      "pairs with fewer verified matches are not used"));
  t.push_back(Number(
      "RelativePose.grid_cols", [](auto& o) -> auto& { return o.relative_pose.grid_cols; },
      AtLeast(1, 100), "columns of the grid the six matches are drawn from"));
  t.push_back(Number(
      "RelativePose.grid_rows", [](auto& o) -> auto& { return o.relative_pose.grid_rows; },
      AtLeast(1, 100), "rows of the grid the six matches are drawn from"));
  std::vector<std::pair<std::string, CorrespondenceSampler>> samplers;
  for (const char* name : {"grid", "random", "roi", "ransac5"}) {
    samplers.emplace_back(name, CorrespondenceSamplerFromName(name));
  }
  t.push_back(Choice(
      "RelativePose.sampler", [](auto& o) -> auto& { return o.relative_pose.sampler; }, samplers,
      "how the matches of a pair's relative rotation are drawn"));
  t.push_back(Bool(
      "RelativePose.use_descriptor_ratios",
      [](auto& o) -> auto& { return o.relative_pose.use_descriptor_ratios; },
      "1: grid selection ranks matches by ramap's stored descriptor ratio, not "
      "Sampson error"));
  t.push_back(Bool(
      "RelativePose.nister_five_point",
      [](auto& o) -> auto& { return o.relative_pose.nister_five_point; },
      "1: candidates of each five of the six matches from Nister's essential "
      "matrix, not Kneip's rotation-only solver"));
  t.push_back(Number(
      "RelativePose.confident_inlier_ratio",
      [](auto& o) -> auto& { return o.relative_pose.confident_inlier_ratio; }, AtLeast(0),
      "stop solving five-point candidates once one explains this fraction of 50 "
      "matches (pairs of at least confident_min_matches; above 1: never)"));
  t.push_back(Number(
      "RelativePose.confident_max_rms_error_px",
      [](auto& o) -> auto& { return o.relative_pose.confident_max_rms_error_px; }, AtLeast(0),
      "...and whose inliers there have at most this RMS epipolar error (after one "
      "refinement on them)"));
  t.push_back(Number(
      "RelativePose.confident_narrow_view_deg",
      [](auto& o) -> auto& { return o.relative_pose.confident_narrow_view_deg; }, AtLeast(0),
      "matches spread less than this (RMS angle to their mean bearing) are a "
      "narrow view..."));
  t.push_back(Number(
      "RelativePose.confident_narrow_view_rms_error_px",
      [](auto& o) -> auto& { return o.relative_pose.confident_narrow_view_rms_error_px; },
      AtLeast(0), "...whose confident candidates must meet this error bound instead"));
  t.push_back(Number(
      "RelativePose.confident_min_matches",
      [](auto& o) -> auto& { return o.relative_pose.confident_min_matches; }, AtLeast(0),
      "pairs with fewer matches always solve every candidate"));
  t.push_back(Number(
      "RelativePose.confident_noise_sample",
      [](auto& o) -> auto& { return o.relative_pose.confident_noise_sample; }, AtLeast(0),
      "pairs estimated first with every candidate to scale the confident error "
      "bound to the keypoints' noise (0: the bound as given)"));
  t.push_back(Number(
      "RelativePose.max_epipolar_error_px",
      [](auto& o) -> auto& { return o.relative_pose.max_epipolar_error_px; }, Above(0),
      "inlier threshold, pixels"));
  t.push_back(Number(
      "RelativePose.pure_rotation_parallax_px",
      [](auto& o) -> auto& { return o.relative_pose.pure_rotation_parallax_px; }, AtLeast(0),
      "pairs whose matches move less than this are a pure rotation"));
}

void AddRotationAveraging(Table& t) {
  t.push_back(FormerlyNamed(
      Choice(
          "ViewGraph.sequential", [](auto& o) -> auto& { return o.order; },
          AutoOnOff(InputOrder::kAuto, InputOrder::kSequential, InputOrder::kUnordered),
          "keyframe windows for sequences (1), one view graph for collections (0)"),
      "PoseGraph.sequential"));
  t.push_back(FormerlyNamed(Number(
                                "ViewGraph.keyframe_interval",
                                [](auto& o) -> auto& { return o.view_graph.keyframe_interval; },
                                AtLeast(1), "frames between keyframes of a sequence"),
                            "PoseGraph.keyframe_interval"));
  t.push_back(Number(
      "RotationAveraging.max_l1_iterations",
      [](auto& o) -> auto& { return o.rotation_averaging.max_l1_iterations; }, AtLeast(0),
      "iterations of the L1 start"));
  t.push_back(Number(
      "RotationAveraging.max_irls_iterations",
      [](auto& o) -> auto& { return o.rotation_averaging.max_irls_iterations; }, AtLeast(0),
      "iterations of the robust refinement"));
  t.push_back(Number(
      "RotationAveraging.max_pcg_iterations",
      [](auto& o) -> auto& { return o.rotation_averaging.max_pcg_iterations; }, AtLeast(0),
      "IRLS steps reuse the last factorisation for up to this many "
      "conjugate-gradient iterations before refactorising (0: refactorise every "
      "step)"));
  t.push_back(Choice(
      "RotationAveraging.loss", [](auto& o) -> auto& { return o.rotation_averaging.loss; },
      std::vector<std::pair<std::string, RobustLoss>>{{"geman_mcclure", RobustLoss::kGemanMcClure},
                                                      {"l1_half", RobustLoss::kL1Half}},
      "the robust loss of the refinement"));
  t.push_back(Number(
      "RotationAveraging.sigma_deg",
      [](auto& o) -> auto& { return o.rotation_averaging.sigma_deg; }, Above(0),
      "the loss's scale"));
  t.push_back(Choice(
      "RotationAveraging.pruning",
      [](auto& o) -> auto& { return o.rotation_averaging.pruning_mode; },
      std::vector<std::pair<std::string, PruningThresholdMode>>{
          {"fixed", PruningThresholdMode::kFixedAngle},
          {"duality", PruningThresholdMode::kStrongDualityBound},
          {"adaptive", PruningThresholdMode::kAdaptive}},
      "prune edges above alpha_max as a fixed angle, the strong-duality bound, or "
      "adaptive_multiplier times the median residual"));
  t.push_back(Number(
      "RotationAveraging.alpha_max_deg",
      [](auto& o) -> auto& { return o.rotation_averaging.alpha_max_deg; },
      OptionRange{0, true, 180, false}, "the pruning threshold's ceiling"));
  t.push_back(Number(
      "RotationAveraging.adaptive_multiplier",
      [](auto& o) -> auto& { return o.rotation_averaging.adaptive_multiplier; }, Above(0),
      "adaptive pruning: the threshold in median residuals"));
  t.push_back(Number(
      "RotationAveraging.adaptive_min_deg",
      [](auto& o) -> auto& { return o.rotation_averaging.adaptive_min_deg; }, AtLeast(0),
      "adaptive pruning: the threshold's floor"));
  t.push_back(Number(
      "RotationAveraging.max_pruning_rounds",
      [](auto& o) -> auto& { return o.rotation_averaging.max_pruning_rounds; }, AtLeast(0),
      "rounds of pruning and solving again"));
  t.push_back(Bool(
      "RotationAveraging.certificate",
      [](auto& o) -> auto& { return o.rotation_averaging.compute_certificate; },
      "1: check the solution's global optimality"));
  t.push_back(Bool(
      "RotationAveraging.certificate_cycle_check",
      [](auto& o) -> auto& { return o.rotation_averaging.certificate_cycle_check; },
      "skip the certificate's chordal refinement when a triangle of kept edges "
      "already proves it cannot pass"));
  t.push_back(Choice(
      "RotationAveraging.edge_weights", [](auto& o) -> auto& { return o.rotation_edge_weights; },
      AutoOnOff(EdgeWeighting::kAuto, EdgeWeighting::kOn, EdgeWeighting::kOff),
      "weight edges by their inlier counts (auto: when every camera's focal "
      "length is known)"));
}

void AddDirectionCheck(Table& t) {
  t.push_back(Choice(
      "TranslationAveraging.direction_check",
      [](auto& o) -> auto& { return o.direction_consistency.mode; },
      std::vector<std::pair<std::string, DirectionCheckMode>>{
          {"off", DirectionCheckMode::kOff},
          {"fixed", DirectionCheckMode::kFixed},
          {"adaptive", DirectionCheckMode::kAdaptive}},
      "reject pair directions their short cycles do not support, above "
      "direction_max_residual_deg (fixed) or above direction_threshold_multiplier "
      "times the median cycle residual (adaptive)"));
  t.push_back(Number(
      "TranslationAveraging.direction_threshold_multiplier",
      [](auto& o) -> auto& { return o.direction_consistency.threshold_multiplier; }, Above(0),
      "adaptive: the threshold in median residuals"));
  t.push_back(Number(
      "TranslationAveraging.direction_min_threshold_deg",
      [](auto& o) -> auto& { return o.direction_consistency.min_threshold_deg; }, AtLeast(0),
      "adaptive: the threshold's floor"));
  t.push_back(Number(
      "TranslationAveraging.direction_max_residual_deg",
      [](auto& o) -> auto& { return o.direction_consistency.max_residual_deg; },
      OptionRange{0, true, 180, false}, "fixed: the threshold; adaptive: its ceiling"));
  t.push_back(Number(
      "TranslationAveraging.direction_min_num_cycles",
      [](auto& o) -> auto& { return o.direction_consistency.min_num_cycles; }, AtLeast(1),
      "pairs closing fewer cycles are not tested"));
}

void AddTranslationSolver(Table& t) {
  t.push_back(Number(
      "TranslationAveraging.min_triangulation_angle_deg",
      [](auto& o) -> auto& { return o.translation_averaging.min_triangulation_angle_deg; },
      Above(0, 90), "track rows need rays at least this far apart"));
  t.push_back(Number(
      "TranslationAveraging.max_rejection_rounds",
      [](auto& o) -> auto& { return o.translation_averaging.max_rejection_rounds; }, AtLeast(0),
      "solve again without the rows the solution marks as outliers, this many "
      "times (0: never)"));
  t.push_back(Number(
      "TranslationAveraging.rejection_multiplier",
      [](auto& o) -> auto& { return o.translation_averaging.rejection_multiplier; }, Above(1),
      "outliers: residuals above this many times the system's median residual"));
  t.push_back(Number(
      "TranslationAveraging.rejection_min_angle_deg",
      [](auto& o) -> auto& { return o.translation_averaging.rejection_min_angle_deg; }, AtLeast(0),
      "a pair row is an outlier only when its direction is missed by more than this"));
  t.push_back(Number(
      "TranslationAveraging.max_num_tracks",
      [](auto& o) -> auto& { return o.translation_averaging.max_num_tracks; }, AtLeast(1),
      "tracks in the system at most"));
  t.push_back(Number(
      "TranslationAveraging.min_tracks_per_image",
      [](auto& o) -> auto& { return o.translation_averaging.min_tracks_per_image; }, AtLeast(0),
      "past max_num_tracks, tracks are still used while a camera has fewer (0: "
      "off)"));
  t.push_back(Choice(
      "TranslationAveraging.solver",
      [](auto& o) -> auto& { return o.translation_averaging.solver; },
      std::vector<std::pair<std::string, TranslationSolver>>{{"irls", TranslationSolver::kIrls},
                                                             {"admm", TranslationSolver::kAdmm}},
      "the L1 solver"));
  t.push_back(Number(
      "TranslationAveraging.max_irls_iterations",
      [](auto& o) -> auto& { return o.translation_averaging.max_irls_iterations; }, AtLeast(0),
      "iterations of the IRLS solver"));
  t.push_back(Number(
      "TranslationAveraging.irls_cost_tolerance",
      [](auto& o) -> auto& { return o.translation_averaging.irls_cost_tolerance; },
      OptionRange{0, false, 1, true},
      "stop IRLS when a step lowers its objective by less (0: off)"));
  t.push_back(Number(
      "TranslationAveraging.irls_extrapolation",
      [](auto& o) -> auto& { return o.translation_averaging.irls_extrapolation; }, AtLeast(1, 3),
      "IRLS steps taken this many times over when that lowers the objective more "
      "(1: plain)"));
  t.push_back(Number(
      "TranslationAveraging.max_pcg_iterations",
      [](auto& o) -> auto& { return o.translation_averaging.max_pcg_iterations; }, AtLeast(0),
      "IRLS steps reuse the last factorisation for up to this many "
      "conjugate-gradient iterations before refactorising (0: refactorise every "
      "step)"));
  t.push_back(Number(
      "TranslationAveraging.max_admm_iterations",
      [](auto& o) -> auto& { return o.translation_averaging.max_admm_iterations; }, AtLeast(0),
      "iterations of the ADMM solver"));
  t.push_back(Number(
      "TranslationAveraging.admm_rho",
      [](auto& o) -> auto& { return o.translation_averaging.admm_rho; }, Above(0),
      "the ADMM solver's penalty"));
  t.push_back(Bool(
      "TranslationAveraging.admm_adaptive_rho",
      [](auto& o) -> auto& { return o.translation_averaging.admm_adaptive_rho; },
      "1: the penalty follows the residuals' balance"));
  t.push_back(Number(
      "TranslationAveraging.pair_constraint_weight",
      [](auto& o) -> auto& { return o.translation_averaging.pair_constraint_weight; }, Above(0),
      "a pair direction's weight against a track's"));
}

void AddTranslationWindows(Table& t) {
  t.push_back(Number(
      "TranslationAveraging.window_min_num_images",
      [](auto& o) -> auto& { return o.translation_windows.min_num_images; }, AtLeast(0),
      "sequences of at least this many images are solved in windows joined by "
      "their shared frames and loops (0: never)"));
  t.push_back(Number(
      "TranslationAveraging.window_frames",
      [](auto& o) -> auto& { return o.translation_windows.window_frames; }, AtLeast(3),
      "frames per window"));
  t.push_back(Number(
      "TranslationAveraging.window_overlap_frames",
      [](auto& o) -> auto& { return o.translation_windows.overlap_frames; }, AtLeast(2),
      "frames each window shares with the next (below window_frames)"));
  t.push_back(Number(
      "TranslationAveraging.window_irls_cost_tolerance",
      [](auto& o) -> auto& { return o.translation_windows.irls_cost_tolerance; }, AtLeast(0),
      "a window's IRLS stops when a step lowers its objective by less (0: off)"));
  t.push_back(Number(
      "TranslationAveraging.window_max_num_iterations",
      [](auto& o) -> auto& { return o.translation_windows.alignment.max_num_iterations; },
      AtLeast(0),
      "Ceres iterations placing the windows by their loops (0: the chain of shared frames "
      "alone)"));
  t.push_back(Number(
      "TranslationAveraging.window_direction_sigma_rad",
      [](auto& o) -> auto& { return o.translation_windows.alignment.direction_sigma_rad; },
      Above(0), "noise of a direction between windows; larger angles are weighed as their size"));
  t.push_back(Number(
      "TranslationAveraging.window_huber_overlap_residuals",
      [](auto& o) -> auto& { return o.translation_windows.alignment.huber_overlap_residuals; },
      Above(0),
      "shared-frame residuals past this many times the chain's median are weighed as their "
      "size"));
  t.push_back(Number(
      "TranslationAveraging.window_max_directions_per_pair", [](auto& o) -> auto& {
        return o.translation_windows.alignment.max_directions_per_window_pair;
      },
      AtLeast(0), "directions used per pair of windows at most (0: all)"));
}

void AddPairDirections(Table& t) {
  t.push_back(Number(
      "PairDirection.max_num_matches",
      [](auto& o) -> auto& { return o.pair_direction.max_num_matches; }, AtLeast(0),
      "a pair's direction from at most this many of its inliers, evenly spaced "
      "(0: all)"));
  t.push_back(Number(
      "PairDirection.min_ray_angle_deg",
      [](auto& o) -> auto& { return o.pair_direction.min_ray_angle_deg; }, AtLeast(0),
      "matches whose rays meet at a smaller angle carry no direction"));
  t.push_back(Number(
      "PairDirection.num_reweighting_rounds",
      [](auto& o) -> auto& { return o.pair_direction.num_reweighting_rounds; }, AtLeast(0),
      "Cauchy reweighting rounds against wrong matches"));
  t.push_back(Number(
      "PairDirection.residual_scale_deg",
      [](auto& o) -> auto& { return o.pair_direction.residual_scale_deg; }, Above(0),
      "Cauchy scale of a match's coplanarity residual"));
  t.push_back(Number(
      "PairDirection.min_num_matches",
      [](auto& o) -> auto& { return o.pair_direction.min_num_matches; }, AtLeast(2),
      "fewer usable matches: no direction"));
  t.push_back(Number(
      "PairDirection.min_cheirality_ratio",
      [](auto& o) -> auto& { return o.pair_direction.min_cheirality_ratio; },
      OptionRange{0.5, true, 1, false},
      "share of matches in front of both cameras that settles the sign"));
  t.push_back(Number(
      "PairDirection.min_agreeing_share",
      [](auto& o) -> auto& { return o.pair_direction.min_agreeing_share; }, AtLeast(0, 1),
      "below this share of matches agreeing with a pair's direction, restart from "
      "sampled two-match directions (0: never; try 0.5 with many wrong matches)"));
  t.push_back(Number(
      "PairDirection.num_sampled_starts",
      [](auto& o) -> auto& { return o.pair_direction.num_sampled_starts; }, AtLeast(1),
      "two-match directions the restart tries"));
}

void AddTriangulation(Table& t) {
  t.push_back(Number(
      "Triangulation.max_reprojection_error_px",
      [](auto& o) -> auto& { return o.triangulation.max_reprojection_error_px; }, Above(0),
      "observations farther from their point are not kept"));
  t.push_back(Number(
      "Triangulation.min_triangulation_angle_deg",
      [](auto& o) -> auto& { return o.triangulation.min_triangulation_angle_deg; }, AtLeast(0, 90),
      "points seen under a smaller angle are not kept"));
  t.push_back(Number(
      "Triangulation.start_max_error_deg",
      [](auto& o) -> auto& { return o.triangulation.start_max_error_deg; }, AtLeast(0, 89),
      "where the points start bundle adjustment, observations farther from their point than "
      "this angle are not kept (0: Triangulation.max_reprojection_error_px)"));
  t.push_back(Bool(
      "Reregistration.enable", [](auto& o) -> auto& { return o.reregistration.enable; },
      "1: images the triangulated points leave out are placed again from them "
      "(P3P)"));
  t.push_back(Number(
      "Reregistration.max_inlier_ratio",
      [](auto& o) -> auto& { return o.reregistration.max_inlier_ratio; }, AtLeast(0, 1),
      "an image is tried when the fraction of its keypoints on triangulated tracks that "
      "are observations of their points is below this times the median image's"));
  t.push_back(Number(
      "Reregistration.min_num_correspondences",
      [](auto& o) -> auto& { return o.reregistration.min_num_correspondences; }, AtLeast(4),
      "...and it has at least this many such keypoints; a new pose needs as many "
      "inliers"));
  t.push_back(Number(
      "Reregistration.min_inlier_gain",
      [](auto& o) -> auto& { return o.reregistration.min_inlier_gain; }, AtLeast(1),
      "the new pose must have this many times the averaged pose's inliers"));
}

// Bundle adjustment's own settings (`ramap bundle_adjuster` registers these alone).
void AddBundleAdjuster(Table& t) {
  t.push_back(Number(
      "BundleAdjustment.max_num_iterations",
      [](auto& o) -> auto& { return o.bundle_adjustment.max_num_iterations; }, AtLeast(0),
      "Ceres iterations at most"));
  t.push_back(Number(
      "BundleAdjustment.loss_scale_px",
      [](auto& o) -> auto& { return o.bundle_adjustment.loss_scale_px; }, Above(0),
      "the robust loss's scale, pixels"));
  t.push_back(Number(
      "BundleAdjustment.wide_start_loss_factor",
      [](auto& o) -> auto& { return o.bundle_adjustment.wide_start_loss_factor; }, AtLeast(0),
      "where the median error at the start exceeds the loss scale, the first solve's loss is "
      "this many times that median and a second solve follows at the loss scale (0: off)"));
  t.push_back(Number(
      "BundleAdjustment.max_reprojection_error_px",
      [](auto& o) -> auto& { return o.bundle_adjustment.max_reprojection_error_px; }, Above(0),
      "observations farther from their point after BA are detached (a huge value: no "
      "filtering)"));
  t.push_back(Number(
      "BundleAdjustment.min_filtered_fraction_to_solve_again",
      [](auto& o) -> auto& { return o.bundle_adjustment.min_filtered_fraction_to_solve_again; },
      AtLeast(0, 1),
      "BA solves again without the detached observations when they are at least this fraction "
      "of all (0: whenever any was)"));
  t.push_back(Number(
      "BundleAdjustment.function_tolerance",
      [](auto& o) -> auto& { return o.bundle_adjustment.function_tolerance; }, AtLeast(0),
      "Ceres's relative cost decrease to stop at"));
  t.push_back(Number(
      "BundleAdjustment.pose_tolerance_deg",
      [](auto& o) -> auto& { return o.bundle_adjustment.pose_tolerance_deg; }, AtLeast(0),
      "also stop once two successive steps each moved every camera by less than this angle "
      "(0: off)"));
  t.push_back(Number(
      "BundleAdjustment.max_num_points",
      [](auto& o) -> auto& { return o.bundle_adjustment.max_num_points; }, AtLeast(0),
      "points adjusted at most (0: all); every track is triangulated again "
      "after"));
  t.push_back(Number(
      "BundleAdjustment.min_track_length",
      [](auto& o) -> auto& { return o.bundle_adjustment.min_track_length; }, AtLeast(2),
      "points seen in fewer images are adjusted only for images the longer tracks leave with "
      "too few observations (2: every point); every track is triangulated again after"));
  t.push_back(Number(
      "BundleAdjustment.max_observations_per_point",
      [](auto& o) -> auto& { return o.bundle_adjustment.max_observations_per_point; }, AtLeast(0),
      "observations of one point adjusted at most, spread evenly along its track (0: all); "
      "every track is triangulated again after"));
  t.push_back(Bool(
      "BundleAdjustment.refine_focal_length",
      [](auto& o) -> auto& { return o.bundle_adjustment.refine_focal_length; },
      "1: refine each camera's focal length"));
  t.push_back(Bool(
      "BundleAdjustment.refine_principal_point",
      [](auto& o) -> auto& { return o.bundle_adjustment.refine_principal_point; },
      "1: refine each camera's principal point"));
  t.push_back(Bool(
      "BundleAdjustment.refine_guessed_principal_point",
      [](auto& o) -> auto& { return o.bundle_adjustment.refine_guessed_principal_point; },
      "1: a camera without a prior focal length refines its principal point (a guess: "
      "the image's centre) with its focal length"));
  t.push_back(Number(
      "BundleAdjustment.max_principal_point_shift",
      [](auto& o) -> auto& { return o.bundle_adjustment.max_principal_point_shift; }, AtLeast(0),
      "a refined principal point that moves farther (fraction of the image's width or "
      "height) is put back and held, and BA solves again"));
  t.push_back(Bool(
      "BundleAdjustment.refine_extra_params",
      [](auto& o) -> auto& { return o.bundle_adjustment.refine_extra_params; },
      "1: refine distortion coefficients"));
}

void AddRefinement(Table& t) {
  t.push_back(Bool(
      "Mapper.refine", [](auto& o) -> auto& { return o.refine; },
      "1: bundle adjustment after averaging; 0: no final BA (faster; see "
      "Mapper.subset_adjustment)"));
  t.push_back(Bool(
      "Mapper.subset_adjustment", [](auto& o) -> auto& { return o.subset_adjustment; },
      "with Mapper.refine 0, 1: BA on the Mapper.calibration_num_points longest tracks "
      "only, then every track triangulated again; 0: averaging alone"));
  t.push_back(Number(
      "BundleAdjustment.num_rounds", [](auto& o) -> auto& { return o.num_refinement_rounds; },
      AtLeast(1),
      "rounds of bundle adjustment, each followed by every track triangulated "
      "again"));
  t.push_back(Bool(
      "BundleAdjustment.keep_prior_intrinsics",
      [](auto& o) -> auto& { return o.bundle_adjustment.keep_prior_intrinsics; },
      "1: cameras with a known focal length (prior_focal_length 1) keep their focal "
      "length and principal point unless the data prove them wrong"));
  t.push_back(Bool(
      "BundleAdjustment.share_identical_intrinsics",
      [](auto& o) -> auto& { return o.bundle_adjustment.share_identical_intrinsics; },
      "1: cameras with the same model, size, parameters and prior flag are refined "
      "as one"));
  t.push_back(Bool(
      "BundleAdjustment.given_intrinsics_test",
      [](auto& o) -> auto& { return o.given_intrinsics_test.enable; },
      "1: before BA, free given focal lengths (and add distortion to pinhole "
      "cameras) on a subset of the points; keep a change only if it lowers the "
      "reprojection RMSE clearly"));
  t.push_back(Number(
      "BundleAdjustment.given_intrinsics_test_min_rmse_decrease",
      [](auto& o) -> auto& { return o.given_intrinsics_test.min_rmse_decrease; },
      OptionRange{0, false, 1, true}, "the fraction a change must lower its cameras' RMSE by"));
  t.push_back(Number(
      "BundleAdjustment.given_intrinsics_test_focal_tolerance",
      [](auto& o) -> auto& { return o.given_intrinsics_test.focal_tolerance; }, AtLeast(0),
      "a freed focal length within this fraction of the given one confirms it"));
  t.push_back(Number(
      "BundleAdjustment.given_intrinsics_test_max_num_images",
      [](auto& o) -> auto& { return o.given_intrinsics_test.max_num_images; }, AtLeast(0),
      "images each step of the test adjusts at most, the middle run of ids (0: "
      "all)"));
  t.push_back(Number(
      "BundleAdjustment.given_intrinsics_test_num_points",
      [](auto& o) -> auto& { return o.given_intrinsics_test.num_points; }, AtLeast(0),
      "points adjusted in each step of the test (0: all)"));
}

void AddCalibration(Table& t) {
  t.push_back(Number(
      "Mapper.max_focal_change_in_bundle_adjustment",
      [](auto& o) -> auto& { return o.max_focal_change_in_bundle_adjustment; }, AtLeast(0),
      "average again through BA's intrinsics when it moved a focal length by more "
      "(fraction; 0: never), but not one given and proved wrong by the test"));
  t.push_back(Number(
      "Mapper.calibration_num_points", [](auto& o) -> auto& { return o.calibration_num_points; },
      AtLeast(0),
      "points of the first BA when a focal length is still unknown after the view "
      "graph (a second pass follows), and of Mapper.subset_adjustment (0: all)"));
  t.push_back(Number(
      "Mapper.calibration_pass_num_tracks",
      [](auto& o) -> auto& { return o.calibration_pass_num_tracks; }, AtLeast(0),
      "a calibration pass (kept for its intrinsics alone) adjusts at most this many points, "
      "averages translations with at most this many tracks and takes its relative poses "
      "from the five-point solver (0: as the second pass)"));
  t.push_back(Bool(
      "Mapper.calibration_subset_only", [](auto& o) -> auto& { return o.calibration_subset_only; },
      "1: the full BA holds the intrinsics the subset found (0: refines them again)"));
  t.push_back(Bool(
      "ViewGraphCalibration.enable",
      [](auto& o) -> auto& { return o.view_graph_calibration.enable; },
      "1: estimate the focal length of cameras without a prior (prior_focal_length "
      "0) from the verified pairs' fundamental matrices"));
  t.push_back(Number(
      "ViewGraphCalibration.min_num_pairs",
      [](auto& o) -> auto& { return o.view_graph_calibration.min_num_pairs; }, AtLeast(1),
      "a camera needs this many verified pairs to be estimated"));
  t.push_back(Number(
      "ViewGraphCalibration.max_median_cost",
      [](auto& o) -> auto& { return o.view_graph_calibration.max_median_cost; }, Above(0, 1),
      "estimates whose median pair cost is higher are not used"));
}

void AddPosePriors(Table& t) {
  t.push_back(TextOption<MapperOptions>(
      "PosePrior.path", [](auto& o) -> auto& { return o.prior_source.path; },
      "prior file: NAME V1 V2 V3 [SX SY SZ] per line (empty: the database's prior_tx/ty/tz, "
      "where COLMAP stores EXIF GPS)"));
  t.push_back(Choice(
      "PosePrior.type", [](auto& o) -> auto& { return o.prior_source.type; },
      std::vector<std::pair<std::string, std::string>>{
          {"auto", "auto"}, {"wgs84", "wgs84"}, {"enu", "enu"}, {"ecef", "ecef"}, {"xyz", "xyz"}},
      "auto: as the database says (COLMAP 3.10 on), else wgs84 (lat lon alt); enu: "
      "m about PosePrior.origin; ecef: m; xyz: any metric frame"));
  t.push_back(Bool(
      "PosePrior.from_database", [](auto& o) -> auto& { return o.prior_source.from_database; },
      "without PosePrior.path: 1 uses the database's prior positions"));
  t.push_back(TextOption<MapperOptions>(
      "PosePrior.origin", [](auto& o) -> auto& { return o.prior_source.origin; },
      "lat,lon,alt of the ENU frame (empty: the median of the priors)"));
  t.push_back(Number(
      "PosePrior.std_x_m", [](auto& o) -> auto& { return o.prior_source.std_x_m; }, Above(0),
      "standard deviation east (or x), m"));
  t.push_back(Number(
      "PosePrior.std_y_m", [](auto& o) -> auto& { return o.prior_source.std_y_m; }, Above(0),
      "standard deviation north (or y), m"));
  t.push_back(Number(
      "PosePrior.std_z_m", [](auto& o) -> auto& { return o.prior_source.std_z_m; }, Above(0),
      "standard deviation up (or z), m"));
  t.push_back(Number(
      "PosePrior.max_distance_from_origin_m",
      [](auto& o) -> auto& { return o.prior_source.max_distance_from_origin_m; }, Above(0),
      "priors further away are rejected as gross errors"));
  t.push_back(Number(
      "PosePrior.max_alignment_error_m",
      [](auto& o) -> auto& { return o.prior_alignment.max_alignment_error_m; }, AtLeast(0),
      "RANSAC inlier threshold, m (0: 3 x the priors' median 3D standard "
      "deviation)"));
  t.push_back(Number(
      "PosePrior.max_fit_uncertainty_deg",
      [](auto& o) -> auto& { return o.prior_alignment.max_fit_uncertainty_deg; }, Above(0),
      "priors too close together for their noise (about sigma / (spread sqrt N)) "
      "leave the model unregistered"));
  t.push_back(Number(
      "PosePrior.min_num_inliers",
      [](auto& o) -> auto& { return o.prior_alignment.min_num_inliers; }, AtLeast(3),
      "priors a prior alignment needs"));
  t.push_back(Bool(
      "PosePrior.align", [](auto& o) -> auto& { return o.prior_alignment.align; },
      "1: align each model to its priors (0 ignores the priors)"));
  t.push_back(Bool(
      "PosePrior.use_in_translation_averaging",
      [](auto& o) -> auto& { return o.prior_alignment.use_in_translation_averaging; },
      "1: priors as weak rows of translation averaging (fixes scale drift)"));
  t.push_back(Bool(
      "PosePrior.use_in_bundle_adjustment",
      [](auto& o) -> auto& { return o.prior_alignment.use_in_bundle_adjustment; },
      "1: priors as residuals of the bundle adjustment (the final one or the subset's)"));
}

Table BuildMapperOptionTable() {
  Table t;
  AddRelativePose(t);
  t.push_back(Number(
      "Mapper.num_threads", [](auto& o) -> auto& { return o.num_threads; }, AtLeast(1, 256),
      "threads of every stage (bundle adjustment and the BLAS included)"));
  AddRotationAveraging(t);
  AddTranslationSolver(t);
  AddDirectionCheck(t);
  AddTranslationWindows(t);
  AddPairDirections(t);
  AddTriangulation(t);
  AddRefinement(t);
  AddBundleAdjuster(t);
  AddCalibration(t);
  AddPosePriors(t);
  t.push_back(Number(
      "Mapper.min_component_size", [](auto& o) -> auto& { return o.min_component_size; },
      AtLeast(2), "connected components with fewer images are not written"));
  return t;
}

}  // namespace

const OptionTable<MapperOptions>& MapperOptionTable() {
  static const Table table = BuildMapperOptionTable();
  return table;
}

OptionTable<MapperOptions> MapperOptionSections(const std::vector<std::string>& sections,
                                                const std::vector<std::string>& extra) {
  Table subset;
  for (const Declaration& d : MapperOptionTable()) {
    const bool wanted =
        std::find(sections.begin(), sections.end(), d.Section()) != sections.end() ||
        std::find(extra.begin(), extra.end(), d.name) != extra.end();
    if (wanted) subset.push_back(d);
  }
  return subset;
}

void ResolveMapperOptions(MapperOptions* options) {
  CheckOptionValues(MapperOptionTable(), *options);
  options->bundle_adjustment.num_threads = options->num_threads;
  options->translation_averaging.num_threads = options->num_threads;
  options->Check();
}

}  // namespace ramap
