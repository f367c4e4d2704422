#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/rotation_averaging.h"

namespace ramap {

namespace {

using Table = OptionTable<RotationAveragingOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.max_l1_iterations", [](auto& o) -> auto& { return o.max_l1_iterations; },
      AtLeast(0), "iterations of the L1 start"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.max_irls_iterations",
      [](auto& o) -> auto& { return o.max_irls_iterations; }, AtLeast(0),
      "iterations of the robust refinement"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.max_pcg_iterations", [](auto& o) -> auto& { return o.max_pcg_iterations; },
      AtLeast(0),
      "IRLS steps reuse the last factorisation for up to this many "
      "conjugate-gradient iterations before refactorising (0: refactorise every "
      "step)"));
  t.push_back(ChoiceOption<RotationAveragingOptions>(
      "RotationAveraging.loss", [](auto& o) -> auto& { return o.loss; },
      std::vector<std::pair<std::string, RobustLoss>>{{"geman_mcclure", RobustLoss::kGemanMcClure},
                                                      {"l1_half", RobustLoss::kL1Half}},
      "the robust loss of the refinement"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.sigma_deg", [](auto& o) -> auto& { return o.sigma_deg; }, Above(0),
      "the loss's scale"));
  t.push_back(ChoiceOption<RotationAveragingOptions>(
      "RotationAveraging.pruning", [](auto& o) -> auto& { return o.pruning_mode; },
      std::vector<std::pair<std::string, PruningThresholdMode>>{
          {"fixed", PruningThresholdMode::kFixedAngle},
          {"duality", PruningThresholdMode::kStrongDualityBound},
          {"adaptive", PruningThresholdMode::kAdaptive}},
      "prune edges above alpha_max as a fixed angle, the strong-duality bound, or "
      "adaptive_multiplier times the median residual"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.alpha_max_deg", [](auto& o) -> auto& { return o.alpha_max_deg; },
      OptionRange{0, true, 180, false}, "the pruning threshold's ceiling"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.adaptive_multiplier",
      [](auto& o) -> auto& { return o.adaptive_multiplier; }, Above(0),
      "adaptive pruning: the threshold in median residuals"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.adaptive_min_deg", [](auto& o) -> auto& { return o.adaptive_min_deg; },
      AtLeast(0), "adaptive pruning: the threshold's floor"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.edge_weight_saturation",
      [](auto& o) -> auto& { return o.edge_weight_saturation; }, AtLeast(0),
      "weighted edges: an edge of n inliers weighs n / (1 + n / (this x the median count)), its "
      "error having a floor more inliers do not lower (0: n)"));
  t.push_back(NumberOption<RotationAveragingOptions>(
      "RotationAveraging.max_pruning_rounds", [](auto& o) -> auto& { return o.max_pruning_rounds; },
      AtLeast(0), "rounds of pruning and solving again"));
  t.push_back(BoolOption<RotationAveragingOptions>(
      "RotationAveraging.certificate", [](auto& o) -> auto& { return o.compute_certificate; },
      "1: check the solution's global optimality"));
  t.push_back(BoolOption<RotationAveragingOptions>(
      "RotationAveraging.certificate_cycle_check",
      [](auto& o) -> auto& { return o.certificate_cycle_check; },
      "skip the certificate's chordal refinement when a triangle of kept edges "
      "already proves it cannot pass"));
}

}  // namespace

const OptionTable<RotationAveragingOptions>& RotationAveragingOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
