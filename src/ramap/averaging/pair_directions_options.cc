#include <string>
#include <utility>
#include <vector>

#include "ramap/averaging/pair_directions.h"

namespace ramap {

namespace {

using Table = OptionTable<PairDirectionOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.max_num_matches", [](auto& o) -> auto& { return o.max_num_matches; },
      AtLeast(0),
      "a pair's direction from at most this many of its inliers, evenly spaced "
      "(0: all)"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.min_ray_angle_deg", [](auto& o) -> auto& { return o.min_ray_angle_deg; },
      AtLeast(0), "matches whose rays meet at a smaller angle carry no direction"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.num_reweighting_rounds",
      [](auto& o) -> auto& { return o.num_reweighting_rounds; }, AtLeast(0),
      "Cauchy reweighting rounds against wrong matches"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.residual_scale_deg", [](auto& o) -> auto& { return o.residual_scale_deg; },
      Above(0), "Cauchy scale of a match's coplanarity residual"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.min_num_matches", [](auto& o) -> auto& { return o.min_num_matches; },
      AtLeast(2), "fewer usable matches: no direction"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.min_cheirality_ratio", [](auto& o) -> auto& { return o.min_cheirality_ratio; },
      OptionRange{0.5, true, 1, false},
      "share of matches in front of both cameras that settles the sign"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.min_agreeing_share", [](auto& o) -> auto& { return o.min_agreeing_share; },
      AtLeast(0, 1),
      "below this share of matches agreeing with a pair's direction, restart from "
      "sampled two-match directions (0: never; try 0.5 with many wrong matches)"));
  t.push_back(NumberOption<PairDirectionOptions>(
      "PairDirection.num_sampled_starts", [](auto& o) -> auto& { return o.num_sampled_starts; },
      AtLeast(1), "two-match directions the restart tries"));
}

}  // namespace

const OptionTable<PairDirectionOptions>& PairDirectionOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
