// A graph of relative rotations between cameras (the input of rotation averaging) and the graph
// utilities the averaging needs: connected components, a maximum spanning tree and the rotations
// obtained by chaining relative rotations along it (the usual initialisation, Chatterjee & Govindu,
// "Efficient and robust large-scale rotation averaging", ICCV 2013).
//
// Convention, used by every rotation-averaging file in ramap: an absolute rotation R_i is
// cam_from_world (COLMAP, x_cam = R_i x_world + t_i); an edge (i, j) holds R_ij = R_j R_i^T, the
// rotation taking camera i's frame to camera j's frame. Gauge: R_i -> R_i G for any rotation G
// leaves every R_ij unchanged.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace ramap {

struct RelativeRotationEdge {
  uint32_t i = 0;                                            // node id (e.g. COLMAP image_id)
  uint32_t j = 0;                                            // node id
  Eigen::Quaterniond R_ij = Eigen::Quaterniond::Identity();  // R_j R_i^T
  double weight = 1.0;  // confidence, e.g. the number of verified inliers; > 0
};

struct RotationGraph {
  std::vector<uint32_t> node_ids;           // distinct ids; edges refer to nodes by id
  std::vector<RelativeRotationEdge> edges;  // no self loops; parallel edges are allowed
};

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

}  // namespace ramap
