#include <string>
#include <utility>
#include <vector>

#include "ramap/estimators/view_graph_calibration.h"

namespace ramap {

namespace {

using Table = OptionTable<ViewGraphCalibrationOptions>;

void Declare(Table& t) {
  t.push_back(BoolOption<ViewGraphCalibrationOptions>(
      "ViewGraphCalibration.enable", [](auto& o) -> auto& { return o.enable; },
      "1: estimate the focal length of cameras without a prior (prior_focal_length "
      "0) from the verified pairs' fundamental matrices"));
  t.push_back(BoolOption<ViewGraphCalibrationOptions>(
      "ViewGraphCalibration.test_given_focal_lengths",
      [](auto& o) -> auto& { return o.test_given_focal_lengths; },
      "1: estimate given focal lengths too (EXIF's, or prior_focal_length 1) and replace one the "
      "pairs prove wrong; untested when --BundleAdjustment.refine_focal_length is 0"));
  t.push_back(NumberOption<ViewGraphCalibrationOptions>(
      "ViewGraphCalibration.given_focal_tolerance",
      [](auto& o) -> auto& { return o.given_focal_tolerance; }, AtLeast(0),
      "a trusted estimate further than this fraction from a given focal length replaces it"));
  t.push_back(NumberOption<ViewGraphCalibrationOptions>(
      "ViewGraphCalibration.min_num_pairs", [](auto& o) -> auto& { return o.min_num_pairs; },
      AtLeast(1), "a camera needs this many verified pairs to be estimated"));
  t.push_back(NumberOption<ViewGraphCalibrationOptions>(
      "ViewGraphCalibration.max_median_cost", [](auto& o) -> auto& { return o.max_median_cost; },
      Above(0, 1), "estimates whose median pair cost is higher are not used"));
}

}  // namespace

const OptionTable<ViewGraphCalibrationOptions>& ViewGraphCalibrationOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
