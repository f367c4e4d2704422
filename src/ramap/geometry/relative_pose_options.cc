#include <string>
#include <utility>
#include <vector>

#include "ramap/geometry/relative_pose.h"

namespace ramap {

namespace {

using Table = OptionTable<RelativePoseOptions>;

void DeclarePart1(Table& t) {
  std::vector<std::pair<std::string, CorrespondenceSampler>> samplers;
  for (const char* name : {"grid", "random", "roi", "ransac5"}) {
    samplers.emplace_back(name, CorrespondenceSamplerFromName(name));
  }
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.min_num_inliers", [](auto& o) -> auto& { return o.min_num_inliers; },
      AtLeast(6), "pairs with fewer verified matches are not used"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.grid_cols", [](auto& o) -> auto& { return o.grid_cols; }, AtLeast(1, 100),
      "columns of the grid the six matches are drawn from"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.grid_rows", [](auto& o) -> auto& { return o.grid_rows; }, AtLeast(1, 100),
      "rows of the grid the six matches are drawn from"));
  t.push_back(ChoiceOption<RelativePoseOptions>(
      "RelativePose.sampler", [](auto& o) -> auto& { return o.sampler; }, samplers,
      "how the matches of a pair's relative rotation are drawn"));
  t.push_back(BoolOption<RelativePoseOptions>(
      "RelativePose.use_descriptor_ratios",
      [](auto& o) -> auto& { return o.use_descriptor_ratios; },
      "1: grid selection ranks matches by ramap's stored descriptor ratio, not "
      "Sampson error"));
  t.push_back(BoolOption<RelativePoseOptions>(
      "RelativePose.nister_five_point", [](auto& o) -> auto& { return o.nister_five_point; },
      "1: candidates of each five of the six matches from Nister's essential "
      "matrix, not Kneip's rotation-only solver"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_inlier_ratio",
      [](auto& o) -> auto& { return o.confident_inlier_ratio; }, AtLeast(0),
      "stop solving five-point candidates once one explains this fraction of 50 "
      "matches (pairs of at least confident_min_matches; above 1: never)"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_max_rms_error_px",
      [](auto& o) -> auto& { return o.confident_max_rms_error_px; }, AtLeast(0),
      "...and whose inliers there have at most this RMS epipolar error (after one "
      "refinement on them)"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_narrow_view_deg",
      [](auto& o) -> auto& { return o.confident_narrow_view_deg; }, AtLeast(0),
      "matches spread less than this (RMS angle to their mean bearing) are a "
      "narrow view..."));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_narrow_view_rms_error_px",
      [](auto& o) -> auto& { return o.confident_narrow_view_rms_error_px; }, AtLeast(0),
      "...whose confident candidates must meet this error bound instead"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_min_matches",
      [](auto& o) -> auto& { return o.confident_min_matches; }, AtLeast(0),
      "pairs with fewer matches always solve every candidate"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.confident_noise_sample",
      [](auto& o) -> auto& { return o.confident_noise_sample; }, AtLeast(0),
      "pairs estimated first with every candidate to scale the confident error "
      "bound to the keypoints' noise (0: the bound as given)"));
}

void DeclarePart2(Table& t) {
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.max_epipolar_error_px",
      [](auto& o) -> auto& { return o.max_epipolar_error_px; }, Above(0),
      "inlier threshold, pixels"));
  t.push_back(NumberOption<RelativePoseOptions>(
      "RelativePose.pure_rotation_parallax_px",
      [](auto& o) -> auto& { return o.pure_rotation_parallax_px; }, AtLeast(0),
      "pairs whose matches move less than this are a pure rotation"));
}

}  // namespace

const OptionTable<RelativePoseOptions>& RelativePoseOptionTable() {
  static const Table table = [] {
    Table t;
    DeclarePart1(t);
    DeclarePart2(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
