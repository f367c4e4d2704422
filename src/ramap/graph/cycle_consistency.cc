#include "ramap/graph/cycle_consistency.h"

#include <algorithm>
#include <cmath>

#include "ramap/geometry/rotation.h"

namespace ramap {
namespace {

// One oriented neighbour: the relative rotation taking the node's frame to the neighbour's
// (R_neighbour = R * R_node).
struct Neighbour {
  int node = 0;
  Eigen::Quaterniond R;
};

// Per node position, its kept neighbours sorted by position, parallel edges collapsed.
std::vector<std::vector<Neighbour>> SortedNeighbours(const RotationGraph& graph,
                                                     const std::vector<bool>& keep,
                                                     const std::vector<bool>& active) {
  const auto index = NodeIndex(graph);
  std::vector<std::vector<Neighbour>> neighbours(graph.node_ids.size());
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    if (!keep[e]) continue;
    const RelativeRotationEdge& edge = graph.edges[e];
    const int i = index.at(edge.i);
    const int j = index.at(edge.j);
    if (!active[i] || !active[j]) continue;
    neighbours[i].push_back({j, edge.R_ij});
    neighbours[j].push_back({i, edge.R_ij.conjugate()});
  }
  for (std::vector<Neighbour>& list : neighbours) {
    std::stable_sort(list.begin(), list.end(),
                     [](const Neighbour& x, const Neighbour& y) { return x.node < y.node; });
    list.erase(std::unique(list.begin(), list.end(),
                           [](const Neighbour& x, const Neighbour& y) { return x.node == y.node; }),
               list.end());
  }
  return neighbours;
}

}  // namespace

TriangleCycleBound TriangleCycleResidualBound(const RotationGraph& graph,
                                              const std::vector<bool>& keep,
                                              const std::vector<bool>& active,
                                              double stop_above_deg) {
  const std::vector<std::vector<Neighbour>> neighbours = SortedNeighbours(graph, keep, active);
  TriangleCycleBound bound;
  // Each triangle a < b < c once: walk b over a's larger neighbours, then merge the two sorted
  // lists above b.
  for (size_t a = 0; a < neighbours.size(); ++a) {
    const std::vector<Neighbour>& from_a = neighbours[a];
    for (const Neighbour& ab : from_a) {
      if (ab.node <= int(a)) continue;
      const std::vector<Neighbour>& from_b = neighbours[ab.node];
      auto it_a = std::upper_bound(from_a.begin(), from_a.end(), ab.node,
                                   [](int node, const Neighbour& x) { return node < x.node; });
      auto it_b = std::upper_bound(from_b.begin(), from_b.end(), ab.node,
                                   [](int node, const Neighbour& x) { return node < x.node; });
      while (it_a != from_a.end() && it_b != from_b.end()) {
        if (it_a->node < it_b->node) {
          ++it_a;
        } else if (it_b->node < it_a->node) {
          ++it_b;
        } else {
          // a -> b -> c, then back from c to a: R_ac^T (R_bc R_ab) is the identity when consistent.
          const double cycle_deg = RotationAngleDeg(it_a->R, it_b->R * ab.R);
          ++bound.triangles_checked;
          bound.residual_lower_bound_deg =
              std::max(bound.residual_lower_bound_deg, cycle_deg / 3.0);
          if (bound.residual_lower_bound_deg > stop_above_deg) return bound;
          ++it_a;
          ++it_b;
        }
      }
    }
  }
  return bound;
}

}  // namespace ramap
