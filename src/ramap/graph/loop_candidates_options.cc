#include <string>
#include <utility>
#include <vector>

#include "ramap/graph/loop_candidates.h"

namespace ramap {

namespace {

using Table = OptionTable<LoopCandidateOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<LoopCandidateOptions>(
      "LoopClosure.max_distance_baselines",
      [](auto& o) -> auto& { return o.max_distance_baselines; }, Above(0),
      "candidate centres within this many median frame-to-frame baselines"));
  t.push_back(NumberOption<LoopCandidateOptions>(
      "LoopClosure.max_view_angle_deg", [](auto& o) -> auto& { return o.max_view_angle_deg; },
      OptionRange{0, true, 180, false}, "candidates look at most this far apart"));
  t.push_back(NumberOption<LoopCandidateOptions>(
      "LoopClosure.min_frame_gap", [](auto& o) -> auto& { return o.min_frame_gap; }, AtLeast(2),
      "candidates are at least this many frames apart"));
  t.push_back(NumberOption<LoopCandidateOptions>(
      "LoopClosure.max_candidates_per_image",
      [](auto& o) -> auto& { return o.max_candidates_per_image; }, AtLeast(1),
      "candidates per image at most"));
}

}  // namespace

const OptionTable<LoopCandidateOptions>& LoopCandidateOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
