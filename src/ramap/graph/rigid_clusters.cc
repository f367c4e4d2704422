#include "ramap/graph/rigid_clusters.h"

#include <algorithm>
#include <map>
#include <set>
#include <unordered_map>
#include <utility>

#include "ramap/graph/rotation_graph_algorithms.h"

namespace ramap {
namespace {

std::vector<std::set<int>> Neighbours(const RotationGraph& graph) {
  const std::unordered_map<uint32_t, int> index = NodeIndex(graph);
  std::vector<std::set<int>> neighbours(graph.node_ids.size());
  for (const RelativeRotationEdge& edge : graph.edges) {
    const int a = index.at(edge.i), b = index.at(edge.j);
    neighbours[a].insert(b);
    neighbours[b].insert(a);
  }
  return neighbours;
}

// The densest triangle among the unassigned nodes: from the node with the most unassigned
// neighbours, its neighbour sharing the most of them, and one they share. Empty when none.
std::vector<int> SeedTriangle(const std::vector<std::set<int>>& neighbours,
                              const std::vector<int>& labels) {
  auto free_degree = [&](int node) {
    int degree = 0;
    for (const int other : neighbours[node]) degree += labels[other] == -1;
    return degree;
  };
  std::vector<int> order;
  for (size_t node = 0; node < neighbours.size(); ++node)
    if (labels[node] == -1) order.push_back(static_cast<int>(node));
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return free_degree(a) > free_degree(b); });
  for (const int first : order) {
    int best_second = -1;
    std::vector<int> best_shared;
    for (const int second : neighbours[first]) {
      if (labels[second] != -1) continue;
      std::vector<int> shared;
      for (const int third : neighbours[second]) {
        if (third != first && labels[third] == -1 && neighbours[first].count(third))
          shared.push_back(third);
      }
      if (shared.size() > best_shared.size()) {
        best_shared = shared;
        best_second = second;
      }
    }
    if (best_second >= 0) return {first, best_second, best_shared.front()};
  }
  return {};
}

}  // namespace

std::vector<int> TriangleClusters(const RotationGraph& graph) {
  const std::vector<std::set<int>> neighbours = Neighbours(graph);
  std::vector<int> labels(graph.node_ids.size(), -1);
  std::vector<std::vector<int>> clusters;
  for (;;) {
    const std::vector<int> seed = SeedTriangle(neighbours, labels);
    if (seed.empty()) break;
    const int label = static_cast<int>(clusters.size());
    std::vector<int> members = seed;
    for (const int node : seed) labels[node] = label;
    // Grow by every image with pairs to two members, until none is left.
    std::vector<int> links(graph.node_ids.size(), 0);
    std::vector<int> frontier = seed;
    while (!frontier.empty()) {
      std::vector<int> next;
      for (const int member : frontier) {
        for (const int other : neighbours[member]) {
          if (labels[other] != -1) continue;
          if (++links[other] == 2) {
            labels[other] = label;
            members.push_back(other);
            next.push_back(other);
          }
        }
      }
      frontier = std::move(next);
    }
    clusters.push_back(std::move(members));
  }
  // Largest first.
  std::vector<int> order(clusters.size());
  for (size_t k = 0; k < order.size(); ++k) order[k] = static_cast<int>(k);
  std::stable_sort(order.begin(), order.end(),
                   [&](int a, int b) { return clusters[a].size() > clusters[b].size(); });
  std::vector<int> rank(clusters.size());
  for (size_t k = 0; k < order.size(); ++k) rank[order[k]] = static_cast<int>(k);
  for (int& label : labels)
    if (label >= 0) label = rank[label];
  return labels;
}

std::vector<ClusterJoin> ClusterJoins(const RotationGraph& graph, const std::vector<int>& labels) {
  const std::unordered_map<uint32_t, int> index = NodeIndex(graph);
  std::map<std::pair<int, int>, std::pair<std::set<uint32_t>, std::set<uint32_t>>> ends;
  std::map<std::pair<int, int>, int> counts;
  for (const RelativeRotationEdge& edge : graph.edges) {
    int a = labels[index.at(edge.i)], b = labels[index.at(edge.j)];
    uint32_t image_a = edge.i, image_b = edge.j;
    if (a < 0 || b < 0 || a == b) continue;
    if (a > b) {
      std::swap(a, b);
      std::swap(image_a, image_b);
    }
    ends[{a, b}].first.insert(image_a);
    ends[{a, b}].second.insert(image_b);
    ++counts[{a, b}];
  }
  std::vector<ClusterJoin> joins;
  for (const auto& [clusters, images] : ends) {
    ClusterJoin join;
    join.cluster1 = clusters.first;
    join.cluster2 = clusters.second;
    join.images1.assign(images.first.begin(), images.first.end());
    join.images2.assign(images.second.begin(), images.second.end());
    join.num_pairs = counts.at(clusters);
    joins.push_back(join);
  }
  return joins;
}

}  // namespace ramap
