#include "ramap/graph/rotation_graph_algorithms.h"

#include <algorithm>
#include <queue>
#include <stdexcept>
#include <string>

#include "ramap/util/disjoint_sets.h"

namespace ramap {
namespace {

bool Kept(const std::vector<bool>& keep, size_t e) { return keep.empty() || keep[e]; }

}  // namespace

std::unordered_map<uint32_t, int> NodeIndex(const RotationGraph& graph) {
  std::unordered_map<uint32_t, int> index;
  index.reserve(graph.node_ids.size());
  for (size_t k = 0; k < graph.node_ids.size(); ++k) {
    if (!index.emplace(graph.node_ids[k], static_cast<int>(k)).second) {
      throw std::invalid_argument("RotationGraph: duplicate node id " +
                                  std::to_string(graph.node_ids[k]));
    }
  }
  for (const RelativeRotationEdge& edge : graph.edges) {
    if (!index.count(edge.i) || !index.count(edge.j) || edge.i == edge.j) {
      throw std::invalid_argument("RotationGraph: edge (" + std::to_string(edge.i) + ", " +
                                  std::to_string(edge.j) +
                                  ") is a self loop or names an unknown node");
    }
  }
  return index;
}

std::vector<int> ConnectedComponents(const RotationGraph& graph, const std::vector<bool>& keep) {
  const auto index = NodeIndex(graph);
  const int n = static_cast<int>(graph.node_ids.size());
  DisjointSets sets(n);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (Kept(keep, e)) sets.Union(index.at(graph.edges[e].i), index.at(graph.edges[e].j));
  }
  std::vector<int> size(n, 0);
  for (int k = 0; k < n; ++k) ++size[sets.Find(k)];
  std::vector<int> roots;
  for (int k = 0; k < n; ++k) {
    if (sets.Find(k) == static_cast<uint32_t>(k)) roots.push_back(k);
  }
  // Largest first; ties by first node (a set's root is its smallest node position) so the
  // labelling is deterministic.
  std::stable_sort(roots.begin(), roots.end(), [&](int a, int b) { return size[a] > size[b]; });
  std::vector<int> label_of_root(n, -1);
  for (size_t r = 0; r < roots.size(); ++r) label_of_root[roots[r]] = static_cast<int>(r);
  std::vector<int> labels(n);
  for (int k = 0; k < n; ++k) labels[k] = label_of_root[sets.Find(k)];
  return labels;
}

std::vector<int> NodeDegrees(const RotationGraph& graph, const std::vector<bool>& keep) {
  const auto index = NodeIndex(graph);
  std::vector<int> degree(graph.node_ids.size(), 0);
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!Kept(keep, e)) continue;
    ++degree[index.at(graph.edges[e].i)];
    ++degree[index.at(graph.edges[e].j)];
  }
  return degree;
}

std::vector<size_t> MaximumSpanningTree(const RotationGraph& graph, const std::vector<bool>& keep) {
  const auto index = NodeIndex(graph);
  std::vector<size_t> order;
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (Kept(keep, e)) order.push_back(e);
  }
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return graph.edges[a].weight > graph.edges[b].weight;
  });
  DisjointSets sets(graph.node_ids.size());
  std::vector<size_t> tree;
  for (size_t e : order) {
    if (sets.Union(index.at(graph.edges[e].i), index.at(graph.edges[e].j))) tree.push_back(e);
  }
  return tree;
}

void PropagateAlongTree(const RotationGraph& graph, const std::vector<size_t>& tree_edges,
                        std::vector<Eigen::Quaterniond>* rotations, std::vector<bool>* known) {
  const auto index = NodeIndex(graph);
  const size_t n = graph.node_ids.size();
  rotations->resize(n, Eigen::Quaterniond::Identity());
  known->resize(n, false);
  // Adjacency of the tree: (neighbour, edge index).
  std::vector<std::vector<std::pair<int, size_t>>> adjacency(n);
  for (size_t e : tree_edges) {
    const int a = index.at(graph.edges[e].i);
    const int b = index.at(graph.edges[e].j);
    adjacency[a].emplace_back(b, e);
    adjacency[b].emplace_back(a, e);
  }
  std::vector<bool>& done = *known;
  std::queue<int> queue;
  for (size_t k = 0; k < n; ++k) {
    if (done[k]) queue.push(static_cast<int>(k));
  }
  auto flood = [&]() {
    while (!queue.empty()) {
      const int a = queue.front();
      queue.pop();
      for (const auto& [b, e] : adjacency[a]) {
        if (done[b]) continue;
        const RelativeRotationEdge& edge = graph.edges[e];
        // R_j = R_ij R_i, R_i = R_ij^T R_j.
        if (index.at(edge.i) == a) {
          (*rotations)[b] = (edge.R_ij * (*rotations)[a]).normalized();
        } else {
          (*rotations)[b] = (edge.R_ij.conjugate() * (*rotations)[a]).normalized();
        }
        done[b] = true;
        queue.push(b);
      }
    }
  };
  flood();
  for (size_t k = 0; k < n; ++k) {
    if (done[k] || adjacency[k].empty()) continue;
    (*rotations)[k] = Eigen::Quaterniond::Identity();
    done[k] = true;
    queue.push(static_cast<int>(k));
    flood();
  }
}

RotationGraph Subgraph(const RotationGraph& graph, const std::vector<bool>& keep,
                       std::vector<size_t>* edge_map) {
  const auto index = NodeIndex(graph);
  std::vector<bool> touched(graph.node_ids.size(), false);
  RotationGraph sub;
  if (edge_map) edge_map->clear();
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!Kept(keep, e)) continue;
    touched[index.at(graph.edges[e].i)] = true;
    touched[index.at(graph.edges[e].j)] = true;
    sub.edges.push_back(graph.edges[e]);
    if (edge_map) edge_map->push_back(e);
  }
  for (size_t k = 0; k < graph.node_ids.size(); ++k) {
    if (touched[k]) sub.node_ids.push_back(graph.node_ids[k]);
  }
  return sub;
}

std::vector<RotationGraph> ComponentSubgraphs(const RotationGraph& graph,
                                              const std::vector<int>& labels) {
  const int num_components =
      labels.empty() ? 0 : *std::max_element(labels.begin(), labels.end()) + 1;
  std::vector<RotationGraph> components(num_components);
  for (size_t k = 0; k < graph.node_ids.size(); ++k)
    components[labels[k]].node_ids.push_back(graph.node_ids[k]);
  const auto index = NodeIndex(graph);
  for (const RelativeRotationEdge& edge : graph.edges)
    components[labels[index.at(edge.i)]].edges.push_back(edge);
  return components;
}

}  // namespace ramap
