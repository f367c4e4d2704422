#include "ramap/estimators/rotation_folds.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <vector>

#include "ramap/graph/rotation_graph_algorithms.h"

namespace ramap {
namespace {

double LeftOutWeight(const RotationGraph& graph, const RotationAveragingResult& result) {
  double weight = 0.0;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (result.edge_status[e] != EdgeStatus::kKept) weight += graph.edges[e].weight;
  }
  return weight;
}

// The node position with the most edges in `graph`.
size_t BusiestNode(const RotationGraph& graph, const std::vector<bool>& usable) {
  std::vector<int> degree(graph.node_ids.size(), 0);
  const std::unordered_map<uint32_t, int> index = NodeIndex(graph);
  for (const RelativeRotationEdge& edge : graph.edges) {
    ++degree[index.at(edge.i)];
    ++degree[index.at(edge.j)];
  }
  size_t busiest = 0;
  for (size_t k = 0; k < degree.size(); ++k) {
    if (usable[k] && (!usable[busiest] || degree[k] > degree[busiest])) busiest = k;
  }
  return busiest;
}

}  // namespace

RotationSolutionComparison CompareRotationSolutions(const RotationGraph& graph,
                                                    const RotationAveragingResult& first,
                                                    const RotationAveragingResult& second) {
  RotationSolutionComparison comparison;
  std::vector<bool> both(graph.node_ids.size(), false);
  for (size_t k = 0; k < both.size(); ++k) {
    comparison.num_estimated_first += first.estimated[k];
    comparison.num_estimated_second += second.estimated[k];
    both[k] = first.estimated[k] && second.estimated[k];
  }
  comparison.left_out_weight_first = LeftOutWeight(graph, first);
  comparison.left_out_weight_second = LeftOutWeight(graph, second);
  if (std::none_of(both.begin(), both.end(), [](bool b) { return b; })) return comparison;
  // cam_from_world rotations: a gauge change is R -> R G, so R_first^T R_second is one G
  // everywhere the two agree.
  const size_t reference = BusiestNode(graph, both);
  const Eigen::Quaterniond gauge =
      first.rotations[reference].conjugate() * second.rotations[reference];
  for (size_t k = 0; k < both.size(); ++k) {
    if (!both[k]) continue;
    const Eigen::Quaterniond node_gauge = first.rotations[k].conjugate() * second.rotations[k];
    comparison.largest_difference_deg = std::max(comparison.largest_difference_deg,
                                                 node_gauge.angularDistance(gauge) * 180.0 / M_PI);
  }
  return comparison;
}

bool SecondSolutionUnfolds(const RotationSolutionComparison& comparison,
                           double min_difference_deg) {
  return comparison.largest_difference_deg > min_difference_deg &&
         comparison.num_estimated_second >= comparison.num_estimated_first &&
         comparison.left_out_weight_second < comparison.left_out_weight_first;
}

}  // namespace ramap
