#include <string>
#include <utility>
#include <vector>

#include "ramap/estimators/reregistration.h"

namespace ramap {

namespace {

using Table = OptionTable<ReregistrationOptions>;

void Declare(Table& t) {
  t.push_back(BoolOption<ReregistrationOptions>(
      "Reregistration.enable", [](auto& o) -> auto& { return o.enable; },
      "1: images the triangulated points leave out are placed again from them "
      "(P3P)"));
  t.push_back(NumberOption<ReregistrationOptions>(
      "Reregistration.max_inlier_ratio", [](auto& o) -> auto& { return o.max_inlier_ratio; },
      AtLeast(0, 1),
      "an image is tried when the fraction of its keypoints on triangulated tracks that "
      "are observations of their points is below this times the median image's"));
  t.push_back(NumberOption<ReregistrationOptions>(
      "Reregistration.min_num_correspondences",
      [](auto& o) -> auto& { return o.min_num_correspondences; }, AtLeast(4),
      "...and it has at least this many such keypoints; a new pose needs as many "
      "inliers"));
  t.push_back(NumberOption<ReregistrationOptions>(
      "Reregistration.min_inlier_gain", [](auto& o) -> auto& { return o.min_inlier_gain; },
      AtLeast(1), "the new pose must have this many times the averaged pose's inliers"));
}

}  // namespace

const OptionTable<ReregistrationOptions>& ReregistrationOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
