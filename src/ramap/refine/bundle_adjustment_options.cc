#include <string>
#include <utility>
#include <vector>

#include "ramap/refine/bundle_adjustment.h"

namespace ramap {

namespace {

using Table = OptionTable<BundleAdjustmentOptions>;

void DeclarePart1(Table& t) {
  t.push_back(ColmapNamed(NumberOption<BundleAdjustmentOptions>(
                              "BundleAdjustment.max_num_iterations",
                              [](auto& o) -> auto& { return o.max_num_iterations; }, AtLeast(0),
                              "Ceres iterations at most"),
                          {"Mapper.ba_global_max_num_iterations"}));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.loss_scale_px", [](auto& o) -> auto& { return o.loss_scale_px; }, Above(0),
      "the robust loss's scale, pixels"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.wide_start_loss_factor",
      [](auto& o) -> auto& { return o.wide_start_loss_factor; }, AtLeast(0),
      "where the median error at the start exceeds the loss scale, the first solve's loss is "
      "this many times that median and a second solve follows at the loss scale (0: off)"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.max_reprojection_error_px",
      [](auto& o) -> auto& { return o.max_reprojection_error_px; }, Above(0),
      "observations farther from their point after BA are detached (a huge value: no "
      "filtering)"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.min_filtered_fraction_to_solve_again",
      [](auto& o) -> auto& { return o.min_filtered_fraction_to_solve_again; }, AtLeast(0, 1),
      "BA solves again without the detached observations when they are at least this fraction "
      "of all (0: whenever any was)"));
  t.push_back(ColmapNamed(NumberOption<BundleAdjustmentOptions>(
                              "BundleAdjustment.function_tolerance",
                              [](auto& o) -> auto& { return o.function_tolerance; }, AtLeast(0),
                              "Ceres's relative cost decrease to stop at"),
                          {"Mapper.ba_global_function_tolerance"}));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.pose_tolerance_deg", [](auto& o) -> auto& { return o.pose_tolerance_deg; },
      AtLeast(0),
      "also stop once two successive steps each moved every camera by less than this angle "
      "(0: off)"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.max_num_points", [](auto& o) -> auto& { return o.max_num_points; },
      AtLeast(0),
      "points adjusted at most (0: all); every track is triangulated again "
      "after"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.min_track_length", [](auto& o) -> auto& { return o.min_track_length; },
      AtLeast(2),
      "points seen in fewer images are adjusted only for images the longer tracks leave with "
      "too few observations (2: every point); every track is triangulated again after"));
  // A point adjusted through one observation constrains nothing.
  t.push_back(AlsoChecked(
      NumberOption<BundleAdjustmentOptions>(
          "BundleAdjustment.max_observations_per_point",
          [](auto& o) -> auto& { return o.max_observations_per_point; }, AtLeast(0),
          "observations of one point adjusted at most, spread evenly along its track (0: all); "
          "every track is triangulated again after"),
      [](const std::string& text) -> std::string {
        return text == "1" ? "must be 0 or >= 2, got 1" : "";
      }));
  t.push_back(ColmapNamed(BoolOption<BundleAdjustmentOptions>(
                              "BundleAdjustment.refine_focal_length",
                              [](auto& o) -> auto& { return o.refine_focal_length; },
                              "1: refine each camera's focal length"),
                          {"Mapper.ba_refine_focal_length"}));
  t.push_back(ColmapNamed(BoolOption<BundleAdjustmentOptions>(
                              "BundleAdjustment.refine_principal_point",
                              [](auto& o) -> auto& { return o.refine_principal_point; },
                              "1: refine each camera's principal point"),
                          {"Mapper.ba_refine_principal_point"}));
}

void DeclarePart2(Table& t) {
  t.push_back(BoolOption<BundleAdjustmentOptions>(
      "BundleAdjustment.refine_guessed_principal_point",
      [](auto& o) -> auto& { return o.refine_guessed_principal_point; },
      "1: a camera without a prior focal length refines its principal point (a guess: "
      "the image's centre) with its focal length"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.max_principal_point_shift",
      [](auto& o) -> auto& { return o.max_principal_point_shift; }, AtLeast(0),
      "a refined guessed principal point that moves farther (fraction of the image's width "
      "or height) is tested: BA solves again with it held where it started"));
  t.push_back(NumberOption<BundleAdjustmentOptions>(
      "BundleAdjustment.min_principal_point_error_decrease",
      [](auto& o) -> auto& { return o.min_principal_point_error_decrease; }, AtLeast(0, 1),
      "...and keeps the move only where it lowers its camera's median reprojection error by "
      "this fraction (1: never; a cropped photo's principal point lies far off the centre)"));
  t.push_back(ColmapNamed(BoolOption<BundleAdjustmentOptions>(
                              "BundleAdjustment.refine_extra_params",
                              [](auto& o) -> auto& { return o.refine_extra_params; },
                              "1: refine distortion coefficients"),
                          {"Mapper.ba_refine_extra_params"}));
  t.push_back(BoolOption<BundleAdjustmentOptions>(
      "BundleAdjustment.keep_prior_intrinsics",
      [](auto& o) -> auto& { return o.keep_prior_intrinsics; },
      "1: cameras with a known focal length (prior_focal_length 1) keep their focal "
      "length and principal point unless the data prove them wrong"));
  t.push_back(BoolOption<BundleAdjustmentOptions>(
      "BundleAdjustment.share_identical_intrinsics",
      [](auto& o) -> auto& { return o.share_identical_intrinsics; },
      "1: cameras with the same model, size, parameters and prior flag are refined "
      "as one"));
}

}  // namespace

const OptionTable<BundleAdjustmentOptions>& BundleAdjustmentOptionTable() {
  static const Table table = [] {
    Table t;
    DeclarePart1(t);
    DeclarePart2(t);
    // COLMAP's options of this step that have no meaning here.
    t.push_back(
        IgnoredColmapOption<BundleAdjustmentOptions>("Mapper.ba_use_gpu", "ramap runs on the CPU"));
    t.push_back(IgnoredColmapOption<BundleAdjustmentOptions>("Mapper.ba_gpu_index",
                                                             "ramap runs on the CPU"));
    return t;
  }();
  return table;
}

}  // namespace ramap
