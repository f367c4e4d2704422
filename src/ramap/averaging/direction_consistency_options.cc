#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/direction_consistency.h"

namespace ramap {

namespace {

using Table = OptionTable<DirectionConsistencyOptions>;

void Declare(Table& t) {
  t.push_back(ChoiceOption<DirectionConsistencyOptions>(
      "TranslationAveraging.direction_check", [](auto& o) -> auto& { return o.mode; },
      std::vector<std::pair<std::string, DirectionCheckMode>>{
          {"off", DirectionCheckMode::kOff},
          {"fixed", DirectionCheckMode::kFixed},
          {"adaptive", DirectionCheckMode::kAdaptive}},
      "reject pair directions their short cycles do not support, above "
      "direction_max_residual_deg (fixed) or above direction_threshold_multiplier "
      "times the median cycle residual (adaptive)"));
  t.push_back(NumberOption<DirectionConsistencyOptions>(
      "TranslationAveraging.direction_threshold_multiplier",
      [](auto& o) -> auto& { return o.threshold_multiplier; }, Above(0),
      "adaptive: the threshold in median residuals"));
  t.push_back(NumberOption<DirectionConsistencyOptions>(
      "TranslationAveraging.direction_min_threshold_deg",
      [](auto& o) -> auto& { return o.min_threshold_deg; }, AtLeast(0),
      "adaptive: the threshold's floor"));
  t.push_back(NumberOption<DirectionConsistencyOptions>(
      "TranslationAveraging.direction_max_residual_deg",
      [](auto& o) -> auto& { return o.max_residual_deg; }, OptionRange{0, true, 180, false},
      "fixed: the threshold; adaptive: its ceiling"));
  t.push_back(NumberOption<DirectionConsistencyOptions>(
      "TranslationAveraging.direction_min_num_cycles",
      [](auto& o) -> auto& { return o.min_num_cycles; }, AtLeast(1),
      "pairs closing fewer cycles are not tested"));
}

}  // namespace

const OptionTable<DirectionConsistencyOptions>& DirectionConsistencyOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
