#include <string>
#include <utility>
#include <vector>

#include "ramap/jobs/loop_closure.h"

namespace ramap {

namespace {

using Table = OptionTable<LoopClosureOptions>;

void Declare(Table& t) {
  t.push_back(NumberOption<LoopClosureOptions>(
      "LoopClosure.max_bridge_pairs", [](auto& o) -> auto& { return o.max_bridge_pairs; },
      AtLeast(0),
      "when the first solve splits, pairs between two models screened to join them (0: off)"));
}

}  // namespace

const OptionTable<LoopClosureOptions>& LoopClosureOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    AppendOptions(
        LoopCandidateOptionTable(), [](auto& o) -> auto& { return o.candidates; }, &t);
    return t;
  }();
  return table;
}

}  // namespace ramap
