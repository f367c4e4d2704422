#include <string>
#include <utility>
#include <vector>

#include "ramap/graph/keyframes.h"

namespace ramap {

namespace {

using Table = OptionTable<KeyframeOptions>;

void Declare(Table& t) {
  t.push_back(FormerlyNamed(
      NumberOption<KeyframeOptions>(
          "ViewGraph.keyframe_interval", [](auto& o) -> auto& { return o.keyframe_interval; },
          AtLeast(1), "frames between keyframes of a sequence"),
      "PoseGraph.keyframe_interval"));
}

}  // namespace

const OptionTable<KeyframeOptions>& KeyframeOptionTable() {
  static const Table table = [] {
    Table t;
    Declare(t);
    return t;
  }();
  return table;
}

}  // namespace ramap
