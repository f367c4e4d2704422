#include "ramap/mapper/components.h"

#include <set>

#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/mapper/mapper_state.h"

namespace ramap {

RotationGraph RotationGraphOfAcceptedPairs(const FeatureDatabase& database,
                                           const std::vector<ImagePair>& pairs,
                                           StageReport* report) {
  RotationGraph graph = AcceptedRotationGraph(pairs);
  const std::set<uint32_t> nodes(graph.node_ids.begin(), graph.node_ids.end());
  for (const ImagePair& pair : pairs) {
    if (pair.accepted()) continue;
    report->dropped_edges.push_back({PairName(database, pair.image_id1, pair.image_id2),
                                     "relative pose rejected: " + pair.estimate.reason});
    for (const uint32_t id : {pair.image_id1, pair.image_id2}) {
      if (!nodes.count(id))
        report->image_reasons[id] = "every relative pose rejected (" + pair.estimate.reason + ")";
    }
  }
  return graph;
}

std::vector<RotationGraph> ComponentsToReconstruct(const RotationGraph& graph, int min_size,
                                                   std::map<uint32_t, std::string>* image_reasons) {
  std::vector<RotationGraph> kept;
  for (RotationGraph& component : ComponentSubgraphs(graph, ConnectedComponents(graph))) {
    const int size = static_cast<int>(component.node_ids.size());
    if (size >= min_size) {
      kept.push_back(std::move(component));
      continue;
    }
    for (const uint32_t id : component.node_ids) {
      (*image_reasons)[id] = "in a component of " + std::to_string(size) +
                             " images (< Mapper.min_component_size " + std::to_string(min_size) +
                             ")";
    }
  }
  return kept;
}

}  // namespace ramap
