#include "ramap/pipeline/rotation_stage.h"

#include <algorithm>
#include <set>

namespace ramap {

RotationStageResult AverageViewGraphRotations(const RotationGraph& graph,
                                              const std::vector<uint32_t>& capture_order,
                                              bool sequential, const KeyframeOptions& pose_graph,
                                              const RotationAveragingOptions& options) {
  RotationStageResult result;
  if (!sequential) {
    result.rotations = AverageRotations(graph, options);
    return result;
  }
  const std::set<uint32_t> members(graph.node_ids.begin(), graph.node_ids.end());
  std::vector<uint32_t> frames;
  for (const uint32_t id : capture_order) {
    if (members.count(id)) frames.push_back(id);
  }
  const Keyframes keyframes = SelectKeyframes(frames, pose_graph);
  result.num_keyframes = static_cast<int>(keyframes.keyframe_ids.size());
  const std::vector<EdgeKind> kinds = ClassifyEdges(graph, keyframes);
  result.num_loop_edges = static_cast<int>(std::count(kinds.begin(), kinds.end(), EdgeKind::kLoop));
  result.rotations = AverageRotationsInWindows(graph, keyframes, options);
  return result;
}

}  // namespace ramap
