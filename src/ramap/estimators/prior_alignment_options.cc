#include <string>
#include <utility>
#include <vector>

#include "ramap/estimators/prior_alignment.h"

namespace ramap {

namespace {

using Table = OptionTable<PriorAlignmentOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<PriorAlignmentOptions>(
      "PosePrior.max_alignment_error_m", [](auto& o) -> auto& { return o.max_alignment_error_m; },
      AtLeast(0),
      "RANSAC inlier threshold, m (0: 3 x the priors' median 3D standard "
      "deviation)"));
  t.push_back(NumberOption<PriorAlignmentOptions>(
      "PosePrior.max_fit_uncertainty_deg",
      [](auto& o) -> auto& { return o.max_fit_uncertainty_deg; }, Above(0),
      "priors too close together for their noise (about sigma / (spread sqrt N)) "
      "leave the model unregistered"));
  t.push_back(NumberOption<PriorAlignmentOptions>(
      "PosePrior.min_num_inliers", [](auto& o) -> auto& { return o.min_num_inliers; }, AtLeast(3),
      "priors a prior alignment needs"));
  t.push_back(BoolOption<PriorAlignmentOptions>(
      "PosePrior.align", [](auto& o) -> auto& { return o.align; },
      "1: align each model to its priors (0 ignores the priors)"));
  t.push_back(BoolOption<PriorAlignmentOptions>(
      "PosePrior.use_in_translation_averaging",
      [](auto& o) -> auto& { return o.use_in_translation_averaging; },
      "1: priors as weak rows of translation averaging (fixes scale drift)"));
  t.push_back(BoolOption<PriorAlignmentOptions>(
      "PosePrior.use_in_bundle_adjustment",
      [](auto& o) -> auto& { return o.use_in_bundle_adjustment; },
      "1: priors as residuals of the bundle adjustment (the final one or the subset's)"));
}

}  // namespace

const OptionTable<PriorAlignmentOptions>& PriorAlignmentOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
