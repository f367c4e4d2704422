#include "mapper_options.h"

#include "options.h"
#include "ramap/util/error.h"

namespace ramap::cli {

void AddRelativePoseOptions(CLI::App& app, MapperOptions* o, MapperOptionText* text) {
  app.add_option("--RelativePose.min_num_inliers", o->relative_pose.min_num_inliers,
                 "pairs with fewer verified matches are not used")
      ->capture_default_str()
      ->check(AtLeast(6));
  app.add_option("--RelativePose.grid_cols", o->relative_pose.grid_cols)
      ->capture_default_str()
      ->check(AtLeast(1, 100));
  app.add_option("--RelativePose.grid_rows", o->relative_pose.grid_rows)
      ->capture_default_str()
      ->check(AtLeast(1, 100));
  app.add_option("--RelativePose.sampler", text->sampler, "grid|random|roi|ransac5")
      ->capture_default_str();
  app.add_option("--RelativePose.use_descriptor_ratios", o->relative_pose.use_descriptor_ratios,
                 "1: grid selection ranks matches by ramap's stored descriptor ratio, not Sampson "
                 "error")
      ->capture_default_str();
  app.add_option("--RelativePose.nister_five_point", o->relative_pose.nister_five_point,
                 "1: candidates of each five of the six matches from Nister's essential "
                 "matrix, not Kneip's rotation-only solver (faster; see README)")
      ->capture_default_str();
  app.add_option("--RelativePose.confident_inlier_ratio", o->relative_pose.confident_inlier_ratio,
                 "stop solving five-point candidates once one explains this fraction of 50 "
                 "matches (pairs of at least confident_min_matches; above 1: never)")
      ->capture_default_str();
  app.add_option("--RelativePose.confident_max_rms_error_px",
                 o->relative_pose.confident_max_rms_error_px,
                 "...and whose inliers there have at most this RMS epipolar error (after one "
                 "refinement on them)")
      ->capture_default_str();
  app.add_option("--RelativePose.confident_narrow_view_deg",
                 o->relative_pose.confident_narrow_view_deg,
                 "matches spread less than this (RMS angle to their mean bearing) are a narrow "
                 "view...")
      ->capture_default_str();
  app.add_option("--RelativePose.confident_narrow_view_rms_error_px",
                 o->relative_pose.confident_narrow_view_rms_error_px,
                 "...whose confident candidates must meet this error bound instead")
      ->capture_default_str();
  app.add_option("--RelativePose.confident_min_matches", o->relative_pose.confident_min_matches)
      ->capture_default_str();
  app.add_option("--RelativePose.confident_noise_sample", o->relative_pose.confident_noise_sample,
                 "pairs estimated first with every candidate to scale the confident error bound "
                 "to the keypoints' noise (0: the bound as given)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RelativePose.max_epipolar_error_px", o->relative_pose.max_epipolar_error_px,
                 "pixels")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--RelativePose.pure_rotation_parallax_px",
                 o->relative_pose.pure_rotation_parallax_px, "pixels")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Mapper.num_threads", o->num_threads)
      ->capture_default_str()
      ->check(AtLeast(1, 256));
}

void AddRotationAveragingOptions(CLI::App& app, MapperOptions* o, MapperOptionText* text) {
  app.add_option("--PoseGraph.sequential", text->sequential,
                 "auto|1|0: keyframe windows for sequences, one view graph for collections")
      ->capture_default_str();
  app.add_option("--PoseGraph.keyframe_interval", o->pose_graph.keyframe_interval)
      ->capture_default_str()
      ->check(AtLeast(1));
  // Rotation averaging (stage 3).
  RotationAveragingOptions& ra = o->rotation_averaging;
  app.add_option("--RotationAveraging.max_l1_iterations", ra.max_l1_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RotationAveraging.max_irls_iterations", ra.max_irls_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RotationAveraging.max_pcg_iterations", ra.max_pcg_iterations,
                 "IRLS steps reuse the last factorisation for up to this many conjugate-gradient "
                 "iterations before refactorising (0: refactorise every step)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RotationAveraging.loss", text->loss, "geman_mcclure|l1_half")
      ->capture_default_str();
  app.add_option("--RotationAveraging.sigma_deg", ra.sigma_deg)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--RotationAveraging.pruning", text->pruning,
                 "fixed|duality|adaptive: prune above alpha_max as a fixed angle, the "
                 "strong-duality bound, or adaptive_multiplier times the median residual")
      ->capture_default_str();
  app.add_option("--RotationAveraging.alpha_max_deg", ra.alpha_max_deg)
      ->capture_default_str()
      ->check(NumberCheck(0, true, 180, false));
  app.add_option("--RotationAveraging.adaptive_multiplier", ra.adaptive_multiplier,
                 "adaptive pruning: the threshold in median residuals")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--RotationAveraging.adaptive_min_deg", ra.adaptive_min_deg,
                 "adaptive pruning: the threshold's floor (its ceiling: alpha_max_deg)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RotationAveraging.max_pruning_rounds", ra.max_pruning_rounds)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--RotationAveraging.certificate", ra.compute_certificate)->capture_default_str();
  app.add_option("--RotationAveraging.certificate_cycle_check", ra.certificate_cycle_check,
                 "skip the certificate's chordal refinement when a triangle of kept edges "
                 "already proves it cannot pass")
      ->capture_default_str();
  app.add_option("--RotationAveraging.edge_weights", text->edge_weights,
                 "auto|1|0: weight edges by their inlier counts (auto: when every camera's "
                 "focal length is known)")
      ->capture_default_str();
}

namespace {

// Translation averaging (stage 4).
// Which pair directions translation averaging uses (averaging/direction_consistency.h).
void AddDirectionCheckOptions(CLI::App& app, MapperOptions* o, MapperOptionText* text) {
  DirectionConsistencyOptions& check = o->direction_consistency;
  app.add_option("--TranslationAveraging.direction_check", text->direction_check,
                 "off|fixed|adaptive: reject pair directions their short cycles do not support, "
                 "above direction_max_residual_deg (fixed) or above direction_threshold_multiplier "
                 "times the median cycle residual (adaptive)")
      ->capture_default_str();
  app.add_option("--TranslationAveraging.direction_threshold_multiplier",
                 check.threshold_multiplier, "adaptive: the threshold in median residuals")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--TranslationAveraging.direction_min_threshold_deg", check.min_threshold_deg,
                 "adaptive: the threshold's floor")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.direction_max_residual_deg", check.max_residual_deg,
                 "fixed: the threshold; adaptive: its ceiling")
      ->capture_default_str()
      ->check(NumberCheck(0, true, 180, false));
  app.add_option("--TranslationAveraging.direction_min_num_cycles", check.min_num_cycles,
                 "pairs closing fewer cycles are not tested")
      ->capture_default_str()
      ->check(AtLeast(1));
}

void AddTranslationAveragingOptions(CLI::App& app, MapperOptions* o, MapperOptionText* text) {
  TranslationAveragingOptions& ta = o->translation_averaging;
  app.add_option("--TranslationAveraging.min_triangulation_angle_deg",
                 ta.min_triangulation_angle_deg)
      ->capture_default_str()
      ->check(Above(0, 90));
  AddDirectionCheckOptions(app, o, text);
  app.add_option("--TranslationAveraging.max_rejection_rounds", ta.max_rejection_rounds,
                 "solve again without the rows the solution marks as outliers, this many times "
                 "(0: never)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.rejection_multiplier", ta.rejection_multiplier,
                 "outliers: residuals above this many times the system's median residual")
      ->capture_default_str()
      ->check(Above(1));
  app.add_option("--TranslationAveraging.rejection_min_angle_deg", ta.rejection_min_angle_deg,
                 "a pair row is an outlier only when its direction is missed by more than this")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.max_num_tracks", ta.max_num_tracks)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--TranslationAveraging.min_tracks_per_image", ta.min_tracks_per_image,
                 "past max_num_tracks, tracks are still used while a camera has fewer (0: off)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.solver", text->translation_solver, "irls|admm")
      ->capture_default_str();
  app.add_option("--TranslationAveraging.max_irls_iterations", ta.max_irls_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.irls_cost_tolerance", ta.irls_cost_tolerance,
                 "stop IRLS when a step lowers its objective by less (0: off)")
      ->capture_default_str();
  app.add_option(
      "--TranslationAveraging.irls_extrapolation", ta.irls_extrapolation,
      "IRLS steps taken this many times over when that lowers the objective more (1: plain)");
  app.add_option("--TranslationAveraging.max_pcg_iterations", ta.max_pcg_iterations,
                 "IRLS steps reuse the last factorisation for up to this many conjugate-gradient "
                 "iterations before refactorising (0: refactorise every step)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.max_admm_iterations", ta.max_admm_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.admm_rho", ta.admm_rho)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--TranslationAveraging.pair_constraint_weight", ta.pair_constraint_weight)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--TranslationAveraging.admm_adaptive_rho", ta.admm_adaptive_rho)
      ->capture_default_str();
}

// Translation averaging in windows (long sequences).
void AddTranslationWindowOptions(CLI::App& app, MapperOptions* o) {
  WindowedTranslationOptions& windows = o->translation_windows;
  app.add_option("--TranslationAveraging.window_min_num_images", windows.min_num_images,
                 "sequences of at least this many images are solved in windows joined by their "
                 "shared frames and loops (0: never)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.window_frames", windows.window_frames, "frames per window")
      ->capture_default_str()
      ->check(AtLeast(3));
  app.add_option("--TranslationAveraging.window_overlap_frames", windows.overlap_frames,
                 "frames each window shares with the next (>= 2, below window_frames)")
      ->capture_default_str()
      ->check(AtLeast(2));
  app.add_option("--TranslationAveraging.window_irls_cost_tolerance", windows.irls_cost_tolerance,
                 "a window's IRLS stops when a step lowers its objective by less (0: off)")
      ->capture_default_str()
      ->check(AtLeast(0));
  WindowAlignmentOptions& alignment = windows.alignment;
  app.add_option("--TranslationAveraging.window_max_num_iterations", alignment.max_num_iterations,
                 "Ceres iterations placing the windows by their loops (0: the chain of shared "
                 "frames alone)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--TranslationAveraging.window_direction_sigma_rad", alignment.direction_sigma_rad,
                 "noise of a direction between windows; larger angles are weighed as their size")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--TranslationAveraging.window_huber_overlap_residuals",
                 alignment.huber_overlap_residuals,
                 "shared-frame residuals past this many times the chain's median are weighed as "
                 "their size")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--TranslationAveraging.window_max_directions_per_pair",
                 alignment.max_directions_per_window_pair,
                 "directions used per pair of windows at most (0: all)")
      ->capture_default_str()
      ->check(AtLeast(0));
}

// The pair directions that translation averaging takes (stage 4).
void AddPairDirectionOptions(CLI::App& app, MapperOptions* o) {
  PairDirectionOptions& directions = o->pair_direction;
  app.add_option("--PairDirection.max_num_matches", directions.max_num_matches,
                 "a pair's direction from at most this many of its inliers, evenly spaced (0: all)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--PairDirection.min_ray_angle_deg", directions.min_ray_angle_deg,
                 "matches whose rays meet at a smaller angle carry no direction")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--PairDirection.num_reweighting_rounds", directions.num_reweighting_rounds,
                 "Cauchy reweighting rounds against wrong matches")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--PairDirection.residual_scale_deg", directions.residual_scale_deg,
                 "Cauchy scale of a match's coplanarity residual")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--PairDirection.min_num_matches", directions.min_num_matches,
                 "fewer usable matches: no direction")
      ->capture_default_str()
      ->check(AtLeast(2));
  app.add_option("--PairDirection.min_cheirality_ratio", directions.min_cheirality_ratio,
                 "share of matches in front of both cameras that settles the sign, in (0.5, 1]")
      ->capture_default_str();
  app.add_option("--PairDirection.min_agreeing_share", directions.min_agreeing_share,
                 "below this share of matches agreeing with a pair's direction, restart from "
                 "sampled two-match directions (0: never; try 0.5 with many wrong matches)")
      ->capture_default_str();
  app.add_option("--PairDirection.num_sampled_starts", directions.num_sampled_starts,
                 "two-match directions the restart tries")
      ->capture_default_str();
}

// Structure (stage 5).
void AddTriangulationOptions(CLI::App& app, MapperOptions* o) {
  app.add_option("--Triangulation.max_reprojection_error_px",
                 o->structure.max_reprojection_error_px)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--Triangulation.min_triangulation_angle_deg",
                 o->structure.min_triangulation_angle_deg)
      ->capture_default_str()
      ->check(AtLeast(0, 90));
  ReregistrationOptions& again = o->reregistration;
  app.add_option("--Reregistration.enable", again.enable,
                 "1: images the triangulated points leave out are placed again from them (P3P)")
      ->capture_default_str();
  app.add_option("--Reregistration.max_inlier_ratio", again.max_inlier_ratio,
                 "an image is tried when fewer of its keypoints on triangulated tracks are "
                 "observations of their points")
      ->capture_default_str()
      ->check(AtLeast(0, 1));
  app.add_option("--Reregistration.min_inlier_gain", again.min_inlier_gain,
                 "the new pose must have this many times the averaged pose's inliers")
      ->capture_default_str()
      ->check(AtLeast(1));
}

// What bundle adjustment does with the intrinsics a user gave.
void AddGivenIntrinsicsOptions(CLI::App& app, MapperOptions* o) {
  BundleAdjustmentOptions& ba = o->bundle_adjustment;
  app.add_option("--BundleAdjustment.keep_prior_intrinsics", ba.keep_prior_intrinsics,
                 "1: cameras with a known focal length (prior_focal_length 1) keep their "
                 "focal length and principal point unless the data prove them wrong")
      ->capture_default_str();
  app.add_option("--BundleAdjustment.share_identical_intrinsics", ba.share_identical_intrinsics,
                 "1: cameras with the same model, size, parameters and prior flag are refined as "
                 "one")
      ->capture_default_str();
  GivenIntrinsicsTestOptions& test = o->given_intrinsics_test;
  app.add_option("--BundleAdjustment.given_intrinsics_test", test.enable,
                 "1: after BA, free given focal lengths (and add distortion to pinhole cameras) "
                 "on a subset of the points; keep a change only if it lowers the reprojection "
                 "RMSE clearly")
      ->capture_default_str();
  app.add_option("--BundleAdjustment.given_intrinsics_test_min_rmse_decrease",
                 test.min_rmse_decrease, "the fraction a change must lower its cameras' RMSE by")
      ->capture_default_str()
      ->check(NumberCheck(0, false, 1, true));
  app.add_option("--BundleAdjustment.given_intrinsics_test_focal_tolerance", test.focal_tolerance,
                 "a freed focal length within this fraction of the given one confirms it")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--BundleAdjustment.given_intrinsics_test_max_num_images", test.max_num_images,
                 "images each step of the test adjusts at most, the middle run of ids (0: all)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--BundleAdjustment.given_intrinsics_test_num_points", test.num_points,
                 "points adjusted in each step of the test (0: all)")
      ->capture_default_str()
      ->check(AtLeast(0));
}

// Refinement (stage 6): bundle adjustment, with the intrinsics.
void AddBundleAdjustmentOptions(CLI::App& app, MapperOptions* o) {
  app.add_option("--Mapper.refine", o->refine,
                 "1: bundle adjustment after averaging; 0: averaging alone (faster)")
      ->capture_default_str();
  AddBundleAdjusterOptions(app, &o->bundle_adjustment);
  app.add_option("--BundleAdjustment.num_rounds", o->num_refinement_rounds,
                 "rounds of bundle adjustment, each followed by every track triangulated again")
      ->capture_default_str()
      ->check(AtLeast(1));
  AddGivenIntrinsicsOptions(app, o);
}

}  // namespace

void AddBundleAdjusterOptions(CLI::App& app, BundleAdjustmentOptions* options) {
  BundleAdjustmentOptions& ba = *options;
  app.add_option("--BundleAdjustment.max_num_iterations", ba.max_num_iterations)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--BundleAdjustment.loss_scale_px", ba.loss_scale_px)
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--BundleAdjustment.function_tolerance", ba.function_tolerance)
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--BundleAdjustment.max_num_points", ba.max_num_points,
                 "points adjusted at most (0: all); every track is triangulated again after")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--BundleAdjustment.refine_focal_length", ba.refine_focal_length,
                 "1: refine each camera's focal length")
      ->capture_default_str();
  app.add_option("--BundleAdjustment.refine_principal_point", ba.refine_principal_point)
      ->capture_default_str();
  app.add_option("--BundleAdjustment.refine_extra_params", ba.refine_extra_params,
                 "1: refine distortion coefficients")
      ->capture_default_str();
}

namespace {

// Self-calibration: the view graph before averaging, and the passes through BA's intrinsics.
void AddCalibrationOptions(CLI::App& app, MapperOptions* o) {
  app.add_option("--Mapper.max_focal_change_in_bundle_adjustment",
                 o->max_focal_change_in_bundle_adjustment,
                 "average again through BA's intrinsics when it moved a focal length by more "
                 "(fraction; 0: never)")
      ->capture_default_str()
      ->check(AtLeast(0));
  app.add_option("--Mapper.calibration_num_points", o->calibration_num_points,
                 "points of the first BA when a focal length is still unknown after the view "
                 "graph (a second pass follows; 0: all)")
      ->capture_default_str()
      ->check(AtLeast(0));
  ViewGraphCalibrationOptions& calibration = o->view_graph_calibration;
  app.add_option("--ViewGraphCalibration.enable", calibration.enable,
                 "1: estimate the focal length of cameras without a prior (prior_focal_length 0) "
                 "from the verified pairs' fundamental matrices")
      ->capture_default_str();
  app.add_option("--ViewGraphCalibration.min_num_pairs", calibration.min_num_pairs)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--ViewGraphCalibration.max_median_cost", calibration.max_median_cost)
      ->capture_default_str()
      ->check(Above(0, 1));
}

}  // namespace

void AddMapperOptions(CLI::App& app, MapperOptions* o, MapperOptionText* text) {
  AddRelativePoseOptions(app, o, text);
  AddRotationAveragingOptions(app, o, text);
  AddTranslationAveragingOptions(app, o, text);
  AddTranslationWindowOptions(app, o);
  AddPairDirectionOptions(app, o);
  AddTriangulationOptions(app, o);
  AddBundleAdjustmentOptions(app, o);
  AddCalibrationOptions(app, o);
  app.add_option("--Mapper.min_component_size", o->min_component_size)
      ->capture_default_str()
      ->check(AtLeast(2));
}

namespace {

// The value of an "auto|1|0" option; throws InputError naming `option` on anything else.
template <typename Choice>
Choice AutoOnOff(const std::string& option, const std::string& text, Choice when_auto,
                 Choice when_on, Choice when_off) {
  if (text == "auto") return when_auto;
  if (text == "1") return when_on;
  if (text == "0") return when_off;
  throw InputError(option, "'" + text + "' is not auto, 1 or 0");
}

}  // namespace

void FinishMapperOptions(const MapperOptionText& text, MapperOptions* options) {
  options->order = AutoOnOff("--PoseGraph.sequential", text.sequential, InputOrder::kAuto,
                             InputOrder::kSequential, InputOrder::kUnordered);
  options->relative_pose.sampler = CorrespondenceSamplerFromName(text.sampler);
  if (text.loss == "geman_mcclure") {
    options->rotation_averaging.loss = RobustLoss::kGemanMcClure;
  } else if (text.loss == "l1_half") {
    options->rotation_averaging.loss = RobustLoss::kL1Half;
  } else {
    throw InputError("--RotationAveraging.loss",
                     "'" + text.loss + "' is not geman_mcclure or l1_half");
  }
  if (text.pruning == "fixed") {
    options->rotation_averaging.pruning_mode = PruningThresholdMode::kFixedAngle;
  } else if (text.pruning == "duality") {
    options->rotation_averaging.pruning_mode = PruningThresholdMode::kStrongDualityBound;
  } else if (text.pruning == "adaptive") {
    options->rotation_averaging.pruning_mode = PruningThresholdMode::kAdaptive;
  } else {
    throw InputError("--RotationAveraging.pruning",
                     "'" + text.pruning + "' is not fixed, duality or adaptive");
  }
  options->rotation_edge_weights =
      AutoOnOff("--RotationAveraging.edge_weights", text.edge_weights, EdgeWeighting::kAuto,
                EdgeWeighting::kOn, EdgeWeighting::kOff);
  if (text.direction_check == "off") {
    options->direction_consistency.mode = DirectionCheckMode::kOff;
  } else if (text.direction_check == "fixed") {
    options->direction_consistency.mode = DirectionCheckMode::kFixed;
  } else if (text.direction_check == "adaptive") {
    options->direction_consistency.mode = DirectionCheckMode::kAdaptive;
  } else {
    throw InputError("--TranslationAveraging.direction_check",
                     "'" + text.direction_check + "' is not off, fixed or adaptive");
  }
  if (text.translation_solver == "irls") {
    options->translation_averaging.solver = TranslationSolver::kIrls;
  } else if (text.translation_solver == "admm") {
    options->translation_averaging.solver = TranslationSolver::kAdmm;
  } else {
    throw InputError("--TranslationAveraging.solver",
                     "'" + text.translation_solver + "' is not irls or admm");
  }
  options->bundle_adjustment.num_threads = options->num_threads;
  try {
    options->Check();
  } catch (const std::invalid_argument& error) {
    throw InputError("mapper options", error.what());
  }
}

namespace {

// summary.json's options.TranslationAveraging: the one-system solver's and the windows'.
nlohmann::json TranslationAveragingToJson(const MapperOptions& o) {
  const TranslationAveragingOptions& ta = o.translation_averaging;
  const WindowedTranslationOptions& windows = o.translation_windows;
  const DirectionConsistencyOptions& check = o.direction_consistency;
  const char* check_mode = check.mode == DirectionCheckMode::kOff     ? "off"
                           : check.mode == DirectionCheckMode::kFixed ? "fixed"
                                                                      : "adaptive";
  return {{"direction_check", check_mode},
          {"direction_threshold_multiplier", check.threshold_multiplier},
          {"direction_min_threshold_deg", check.min_threshold_deg},
          {"direction_max_residual_deg", check.max_residual_deg},
          {"direction_min_num_cycles", check.min_num_cycles},
          {"max_rejection_rounds", ta.max_rejection_rounds},
          {"rejection_multiplier", ta.rejection_multiplier},
          {"rejection_min_angle_deg", ta.rejection_min_angle_deg},
          {"min_triangulation_angle_deg", ta.min_triangulation_angle_deg},
          {"max_num_tracks", ta.max_num_tracks},
          {"min_tracks_per_image", ta.min_tracks_per_image},
          {"solver", ta.solver == TranslationSolver::kIrls ? "irls" : "admm"},
          {"max_irls_iterations", ta.max_irls_iterations},
          {"irls_cost_tolerance", ta.irls_cost_tolerance},
          {"irls_extrapolation", ta.irls_extrapolation},
          {"max_pcg_iterations", ta.max_pcg_iterations},
          {"max_admm_iterations", ta.max_admm_iterations},
          {"admm_rho", ta.admm_rho},
          {"pair_constraint_weight", ta.pair_constraint_weight},
          {"window_min_num_images", windows.min_num_images},
          {"window_frames", windows.window_frames},
          {"window_overlap_frames", windows.overlap_frames},
          {"window_irls_cost_tolerance", windows.irls_cost_tolerance},
          {"window_max_num_iterations", windows.alignment.max_num_iterations},
          {"window_direction_sigma_rad", windows.alignment.direction_sigma_rad},
          {"window_huber_overlap_residuals", windows.alignment.huber_overlap_residuals},
          {"window_max_directions_per_pair", windows.alignment.max_directions_per_window_pair}};
}

nlohmann::json BundleAdjustmentToJson(const MapperOptions& o) {
  const BundleAdjustmentOptions& ba = o.bundle_adjustment;
  return {{"refine_focal_length", ba.refine_focal_length},
          {"refine_principal_point", ba.refine_principal_point},
          {"refine_extra_params", ba.refine_extra_params},
          {"keep_prior_intrinsics", ba.keep_prior_intrinsics},
          {"share_identical_intrinsics", ba.share_identical_intrinsics},
          {"given_intrinsics_test", o.given_intrinsics_test.enable},
          {"given_intrinsics_test_min_rmse_decrease", o.given_intrinsics_test.min_rmse_decrease},
          {"given_intrinsics_test_focal_tolerance", o.given_intrinsics_test.focal_tolerance},
          {"given_intrinsics_test_num_points", o.given_intrinsics_test.num_points},
          {"given_intrinsics_test_max_num_images", o.given_intrinsics_test.max_num_images},
          {"num_rounds", o.num_refinement_rounds},
          {"max_num_iterations", ba.max_num_iterations},
          {"loss_scale_px", ba.loss_scale_px},
          {"max_num_points", ba.max_num_points},
          {"function_tolerance", ba.function_tolerance}};
}

}  // namespace

nlohmann::json MapperOptionsToJson(const MapperOptions& o) {
  const RotationAveragingOptions& ra = o.rotation_averaging;
  return {
      {"RelativePose",
       {{"min_num_inliers", o.relative_pose.min_num_inliers},
        {"grid_cols", o.relative_pose.grid_cols},
        {"grid_rows", o.relative_pose.grid_rows},
        {"sampler", CorrespondenceSamplerName(o.relative_pose.sampler)},
        {"max_epipolar_error_px", o.relative_pose.max_epipolar_error_px},
        {"use_descriptor_ratios", o.relative_pose.use_descriptor_ratios},
        {"nister_five_point", o.relative_pose.nister_five_point},
        {"confident_inlier_ratio", o.relative_pose.confident_inlier_ratio},
        {"confident_max_rms_error_px", o.relative_pose.confident_max_rms_error_px},
        {"confident_narrow_view_deg", o.relative_pose.confident_narrow_view_deg},
        {"confident_narrow_view_rms_error_px", o.relative_pose.confident_narrow_view_rms_error_px},
        {"confident_min_matches", o.relative_pose.confident_min_matches},
        {"confident_noise_sample", o.relative_pose.confident_noise_sample},
        {"pure_rotation_parallax_px", o.relative_pose.pure_rotation_parallax_px}}},
      {"PoseGraph",
       {{"sequential", o.order == InputOrder::kAuto         ? "auto"
                       : o.order == InputOrder::kSequential ? "1"
                                                            : "0"},
        {"keyframe_interval", o.pose_graph.keyframe_interval}}},
      {"RotationAveraging",
       {{"max_l1_iterations", ra.max_l1_iterations},
        {"max_irls_iterations", ra.max_irls_iterations},
        {"max_pcg_iterations", ra.max_pcg_iterations},
        {"loss", ra.loss == RobustLoss::kGemanMcClure ? "geman_mcclure" : "l1_half"},
        {"sigma_deg", ra.sigma_deg},
        {"pruning", ra.pruning_mode == PruningThresholdMode::kFixedAngle ? "fixed"
                    : ra.pruning_mode == PruningThresholdMode::kAdaptive ? "adaptive"
                                                                         : "duality"},
        {"alpha_max_deg", ra.alpha_max_deg},
        {"adaptive_multiplier", ra.adaptive_multiplier},
        {"adaptive_min_deg", ra.adaptive_min_deg},
        {"max_pruning_rounds", ra.max_pruning_rounds},
        {"certificate", ra.compute_certificate},
        {"certificate_cycle_check", ra.certificate_cycle_check},
        {"edge_weights", o.rotation_edge_weights == EdgeWeighting::kAuto ? "auto"
                         : o.rotation_edge_weights == EdgeWeighting::kOn ? "1"
                                                                         : "0"}}},
      {"TranslationAveraging", TranslationAveragingToJson(o)},
      {"PairDirection",
       {{"max_num_matches", o.pair_direction.max_num_matches},
        {"min_ray_angle_deg", o.pair_direction.min_ray_angle_deg},
        {"num_reweighting_rounds", o.pair_direction.num_reweighting_rounds},
        {"residual_scale_deg", o.pair_direction.residual_scale_deg},
        {"min_num_matches", o.pair_direction.min_num_matches},
        {"min_cheirality_ratio", o.pair_direction.min_cheirality_ratio},
        {"min_agreeing_share", o.pair_direction.min_agreeing_share},
        {"num_sampled_starts", o.pair_direction.num_sampled_starts}}},
      {"Triangulation",
       {{"max_reprojection_error_px", o.structure.max_reprojection_error_px},
        {"min_triangulation_angle_deg", o.structure.min_triangulation_angle_deg}}},
      {"Reregistration",
       {{"enable", o.reregistration.enable},
        {"max_inlier_ratio", o.reregistration.max_inlier_ratio},
        {"min_num_correspondences", o.reregistration.min_num_correspondences},
        {"min_inlier_gain", o.reregistration.min_inlier_gain}}},
      {"Mapper",
       {{"refine", o.refine},
        {"min_component_size", o.min_component_size},
        {"num_threads", o.num_threads},
        {"max_focal_change_in_bundle_adjustment", o.max_focal_change_in_bundle_adjustment},
        {"calibration_num_points", o.calibration_num_points}}},
      {"ViewGraphCalibration",
       {{"enable", o.view_graph_calibration.enable},
        {"min_num_pairs", o.view_graph_calibration.min_num_pairs},
        {"max_median_cost", o.view_graph_calibration.max_median_cost}}},
      {"BundleAdjustment", BundleAdjustmentToJson(o)},
  };
}

void AddLoopClosureOptions(CLI::App& app, bool* close_loops, LoopClosureOptions* options) {
  LoopCandidateOptions& loops = options->candidates;
  app.add_option("--LoopClosure.enable", *close_loops,
                 "1: after sequential matching, match the pairs a first solve puts close, solve "
                 "again")
      ->capture_default_str();
  app.add_option("--LoopClosure.max_distance_baselines", loops.max_distance_baselines,
                 "candidate centres within this many median frame-to-frame baselines")
      ->capture_default_str()
      ->check(Above(0));
  app.add_option("--LoopClosure.max_view_angle_deg", loops.max_view_angle_deg)
      ->capture_default_str()
      ->check(NumberCheck(0, true, 180, false));
  app.add_option("--LoopClosure.min_frame_gap", loops.min_frame_gap,
                 "candidates are at least this many frames apart")
      ->capture_default_str()
      ->check(AtLeast(2));
  app.add_option("--LoopClosure.max_candidates_per_image", loops.max_candidates_per_image)
      ->capture_default_str()
      ->check(AtLeast(1));
  app.add_option("--LoopClosure.max_bridge_pairs", options->max_bridge_pairs,
                 "when the first solve splits, pairs between two models screened to join them "
                 "(0: off)")
      ->capture_default_str()
      ->check(AtLeast(0));
}

}  // namespace ramap::cli
