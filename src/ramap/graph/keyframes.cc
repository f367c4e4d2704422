#include "ramap/graph/keyframes.h"

#include <stdexcept>
#include <unordered_map>

#include "ramap/util/option_check.h"

namespace ramap {

void KeyframeOptions::Check() const { CheckOptionValues(KeyframeOptionTable(), *this); }

Keyframes SelectKeyframes(const std::vector<uint32_t>& frames_in_order,
                          const KeyframeOptions& options) {
  options.Check();
  Keyframes result;
  const size_t n = frames_in_order.size();
  if (n == 0) return result;
  std::vector<size_t> positions;
  for (size_t p = 0; p < n; p += options.keyframe_interval) positions.push_back(p);
  if (positions.back() != n - 1) positions.push_back(n - 1);
  for (size_t p : positions) result.keyframe_ids.push_back(frames_in_order[p]);
  for (size_t k = 0; k + 1 < positions.size(); ++k) {
    KeyframeWindow window;
    window.first_keyframe = frames_in_order[positions[k]];
    window.second_keyframe = frames_in_order[positions[k + 1]];
    window.frames.assign(frames_in_order.begin() + positions[k],
                         frames_in_order.begin() + positions[k + 1] + 1);
    result.windows.push_back(std::move(window));
  }
  return result;
}

std::vector<EdgeKind> ClassifyEdges(const RotationGraph& graph, const Keyframes& keyframes) {
  // Windows overlap only in their keyframes: a frame belongs to windows w_first..w_last.
  std::unordered_map<uint32_t, std::pair<int, int>> window_range;
  for (size_t w = 0; w < keyframes.windows.size(); ++w) {
    for (uint32_t id : keyframes.windows[w].frames) {
      auto [it, inserted] = window_range.emplace(id, std::make_pair(int(w), int(w)));
      if (!inserted) it->second.second = static_cast<int>(w);
    }
  }
  std::vector<EdgeKind> kinds;
  kinds.reserve(graph.edges.size());
  for (const RelativeRotationEdge& edge : graph.edges) {
    const auto a = window_range.find(edge.i);
    const auto b = window_range.find(edge.j);
    const bool share = a != window_range.end() && b != window_range.end() &&
                       a->second.first <= b->second.second && b->second.first <= a->second.second;
    kinds.push_back(share ? EdgeKind::kLocal : EdgeKind::kLoop);
  }
  return kinds;
}

}  // namespace ramap
