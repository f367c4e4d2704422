// The graph utilities rotation averaging needs on a graph of relative rotations
// (scene/rotation_graph.h, which states the rotation convention and gauge): connected
// components, a maximum spanning tree and the rotations obtained by chaining relative rotations
// along it (the usual initialisation, Chatterjee & Govindu, "Efficient and robust large-scale
// rotation averaging", ICCV 2013).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "ramap/scene/rotation_graph.h"

namespace ramap {

// node id -> position in graph.node_ids. Throws std::invalid_argument on duplicate ids or edges
// naming unknown nodes or self loops.
std::unordered_map<uint32_t, int> NodeIndex(const RotationGraph& graph);

// Component label (0, 1, ...) per node position, using only the edges with keep[e] (all when
// `keep` is empty). Labels are ordered by decreasing component size: label 0 is the largest.
std::vector<int> ConnectedComponents(const RotationGraph& graph,
                                     const std::vector<bool>& keep = {});

// Number of kept edges at each node position.
std::vector<int> NodeDegrees(const RotationGraph& graph, const std::vector<bool>& keep = {});

// Indices of the edges of a maximum-weight spanning forest (Kruskal), among edges with keep[e].
std::vector<size_t> MaximumSpanningTree(const RotationGraph& graph,
                                        const std::vector<bool>& keep = {});

// Rotations per node position from chaining R_j = R_ij R_i along the given tree edges. Nodes with
// known[k] keep rotations[k]; the others are reached by breadth-first search from the known ones
// (from the first node of each component when none is known). On return known[k] is true for
// every node that received a rotation.
void PropagateAlongTree(const RotationGraph& graph, const std::vector<size_t>& tree_edges,
                        std::vector<Eigen::Quaterniond>* rotations, std::vector<bool>* known);

// The graph of the edges with keep[e] and the nodes they touch (in graph.node_ids order);
// `edge_map` (optional) receives, per new edge, its index in `graph`.
RotationGraph Subgraph(const RotationGraph& graph, const std::vector<bool>& keep,
                       std::vector<size_t>* edge_map);

// One graph per component label of `labels` (as ConnectedComponents gives them, per node
// position): its nodes in graph.node_ids order and its edges in graph.edges order.
std::vector<RotationGraph> ComponentSubgraphs(const RotationGraph& graph,
                                              const std::vector<int>& labels);

}  // namespace ramap
