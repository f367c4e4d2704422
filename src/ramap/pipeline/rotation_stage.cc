#include "ramap/pipeline/rotation_stage.h"

#include <algorithm>
#include <map>
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

double RelativeRotationWeight(int num_inliers) {
  return static_cast<double>(std::max(num_inliers, 1));
}

RotationGraph RotationGraphOfRecords(const std::vector<RelativePoseRecord>& records,
                                     std::vector<std::string>* names) {
  std::map<std::string, uint32_t> ids;
  auto id_of = [&](const std::string& name) {
    auto [it, inserted] = ids.emplace(name, static_cast<uint32_t>(names->size()));
    if (inserted) names->push_back(name);
    return it->second;
  };
  RotationGraph graph;
  for (const RelativePoseRecord& r : records) {
    graph.edges.push_back({id_of(r.image_name1), id_of(r.image_name2), r.rotation,
                           RelativeRotationWeight(r.num_inliers)});
  }
  for (uint32_t k = 0; k < names->size(); ++k) graph.node_ids.push_back(k);
  return graph;
}

}  // namespace ramap
