#include <string>
#include <vector>

#include "ramap/eval/pose_metrics.h"
#include "ramap/util/error.h"
#include "ramap/util/number_list.h"

namespace ramap {

namespace {

using Options = PoseEvaluationOptions;

// --auc_thresholds: "1,3,5,10", each an angle in (0, 180] degrees.
OptionDeclaration<Options> AucThresholdsOption() {
  OptionDeclaration<Options> d;
  d.name = "auc_thresholds";
  d.type = OptionType::kText;
  d.help = "relative pose AUC thresholds, degrees, comma-separated";
  d.check = [](const std::string& text) -> std::string {
    const std::string problem = "must be a list of angles in (0, 180] degrees, got " + text;
    try {
      const std::vector<double> thresholds = ParseNumberList(text, "--auc_thresholds");
      if (thresholds.empty()) return problem;
      for (const double t : thresholds) {
        if (!(t > 0.0 && t <= 180.0)) return problem;
      }
    } catch (const InputError&) {
      return problem;
    }
    return "";
  };
  d.text = [](const Options& o) {
    std::string text;
    for (const double t : o.auc_thresholds_deg)
      text += (text.empty() ? "" : ",") + FormatOptionNumber(t);
    return text;
  };
  d.store = [](Options& o, const std::string& text) {
    o.auc_thresholds_deg = ParseNumberList(text, "--auc_thresholds");
  };
  return d;
}

OptionTable<Options> BuildTable() {
  OptionTable<Options> t;
  t.push_back(BoolOption<Options>(
      "estimate_scale", [](auto& o) -> auto& { return o.alignment.estimate_scale; },
      "1: Sim(3) alignment; 0: SE(3), for metric reconstructions"));
  t.push_back(BoolOption<Options>(
      "robust_alignment", [](auto& o) -> auto& { return o.alignment.robust; },
      "1: RANSAC over triples of centres, then a refit on the inliers"));
  t.push_back(NumberOption<Options>(
      "robust_alignment_max_error", [](auto& o) -> auto& { return o.alignment.robust_max_error; },
      AtLeast(0), "inlier threshold of the robust alignment, in ground-truth units"));
  t.push_back(AucThresholdsOption());
  t.push_back(NumberOption<Options>(
      "min_baseline", [](auto& o) -> auto& { return o.min_baseline; }, AtLeast(0),
      "pairs with a shorter ground-truth baseline score rotation only"));
  t.push_back(BoolOption<Options>(
      "ordered_pairs", [](auto& o) -> auto& { return o.ordered_pairs; },
      "score both orders of each pair, as COLMAP's benchmark"));
  return t;
}

}  // namespace

const OptionTable<PoseEvaluationOptions>& PoseEvaluationOptionTable() {
  static const OptionTable<PoseEvaluationOptions> table = BuildTable();
  return table;
}

}  // namespace ramap
