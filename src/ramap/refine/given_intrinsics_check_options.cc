#include <string>
#include <utility>
#include <vector>

#include "ramap/refine/given_intrinsics_check.h"

namespace ramap {

namespace {

using Table = OptionTable<GivenIntrinsicsTestOptions>;

void Declare(Table& t) {
  t.push_back(BoolOption<GivenIntrinsicsTestOptions>(
      "BundleAdjustment.given_intrinsics_test", [](auto& o) -> auto& { return o.enable; },
      "1: before BA, free given focal lengths (and add distortion to pinhole "
      "cameras) on a subset of the points; keep a change only if it lowers the "
      "reprojection RMSE clearly"));
  t.push_back(NumberOption<GivenIntrinsicsTestOptions>(
      "BundleAdjustment.given_intrinsics_test_min_rmse_decrease",
      [](auto& o) -> auto& { return o.min_rmse_decrease; }, OptionRange{0, false, 1, true},
      "the fraction a change must lower its cameras' RMSE by"));
  t.push_back(NumberOption<GivenIntrinsicsTestOptions>(
      "BundleAdjustment.given_intrinsics_test_focal_tolerance",
      [](auto& o) -> auto& { return o.focal_tolerance; }, AtLeast(0),
      "a freed focal length within this fraction of the given one confirms it"));
  t.push_back(NumberOption<GivenIntrinsicsTestOptions>(
      "BundleAdjustment.given_intrinsics_test_max_num_images",
      [](auto& o) -> auto& { return o.max_num_images; }, AtLeast(0),
      "images each step of the test adjusts at most, the middle run of ids (0: "
      "all)"));
  t.push_back(NumberOption<GivenIntrinsicsTestOptions>(
      "BundleAdjustment.given_intrinsics_test_num_points",
      [](auto& o) -> auto& { return o.num_points; }, AtLeast(0),
      "points adjusted in each step of the test (0: all)"));
}

}  // namespace

const OptionTable<GivenIntrinsicsTestOptions>& GivenIntrinsicsTestOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
