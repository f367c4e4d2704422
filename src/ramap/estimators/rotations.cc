#include "ramap/estimators/rotations.h"

#include <algorithm>
#include <map>
#include <set>

#include "ramap/util/timer.h"

namespace ramap {

bool AllFocalLengthsKnown(const FeatureDatabase& database) {
  return std::all_of(database.cameras.begin(), database.cameras.end(),
                     [](const auto& entry) { return entry.second.has_prior_focal_length; });
}

bool UseRotationEdgeWeights(EdgeWeighting weighting, bool focal_lengths_known) {
  if (weighting != EdgeWeighting::kAuto) return weighting == EdgeWeighting::kOn;
  return focal_lengths_known;
}

bool UseRotationEdgeWeights(EdgeWeighting weighting, const FeatureDatabase& database) {
  return UseRotationEdgeWeights(weighting, AllFocalLengthsKnown(database));
}

RotationStageResult AverageGraphRotations(const RotationGraph& graph,
                                          const std::vector<uint32_t>& capture_order,
                                          bool sequential, const KeyframeOptions& view_graph,
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
  const Keyframes keyframes = SelectKeyframes(frames, view_graph);
  result.num_keyframes = static_cast<int>(keyframes.keyframe_ids.size());
  const std::vector<EdgeKind> kinds = ClassifyEdges(graph, keyframes);
  result.num_loop_edges = static_cast<int>(std::count(kinds.begin(), kinds.end(), EdgeKind::kLoop));
  result.rotations = AverageRotationsInWindows(graph, keyframes, options);
  return result;
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

RecordRotations AverageRecordRotations(const std::vector<RelativePoseRecord>& records,
                                       InputOrder order, const KeyframeOptions& view_graph,
                                       const RotationAveragingOptions& options) {
  RecordRotations result;
  const RotationGraph graph = RotationGraphOfRecords(records, &result.names);
  result.num_edges = static_cast<int>(graph.edges.size());
  std::vector<uint32_t> capture_order;
  for (const size_t k : CaptureOrder(result.names))
    capture_order.push_back(static_cast<uint32_t>(k));
  result.sequential = IsSequentialInput(order, result.names);
  Timer timer;
  result.stage =
      AverageGraphRotations(graph, capture_order, result.sequential, view_graph, options);
  result.seconds = timer.ElapsedSeconds();
  const RotationAveragingResult& averaged = result.stage.rotations;
  for (size_t k = 0; k < averaged.node_ids.size(); ++k) {
    if (averaged.estimated[k])
      result.rotations.push_back({result.names[averaged.node_ids[k]], averaged.rotations[k]});
  }
  std::sort(
      result.rotations.begin(), result.rotations.end(),
      [](const RotationRecord& a, const RotationRecord& b) { return a.image_name < b.image_name; });
  return result;
}

}  // namespace ramap
