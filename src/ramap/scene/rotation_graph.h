// The rotation graph: the relative rotations between cameras that rotation averaging reads, as
// plain data; the mapper's is a view of the view graph's accepted pairs (scene/view_graph.h), each
// edge naming its pair (the algorithms on it are graph/rotation_graph_algorithms.h's).
//
// Convention, used by every rotation-averaging file in ramap: an absolute rotation R_i is
// cam_from_world (COLMAP, x_cam = R_i x_world + t_i); an edge (i, j) holds R_ij = R_j R_i^T, the
// rotation taking camera i's frame to camera j's frame. Gauge: R_i -> R_i G for any rotation G
// leaves every R_ij unchanged.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace ramap {

struct RelativeRotationEdge {
  uint32_t i = 0;                                            // node id (e.g. COLMAP image_id)
  uint32_t j = 0;                                            // node id
  Eigen::Quaterniond R_ij = Eigen::Quaterniond::Identity();  // R_j R_i^T
  double weight = 1.0;  // confidence, e.g. the number of verified inliers; > 0
  // In a view of the mapper's view graph (scene/view_graph.h), the index of the image pair the
  // edge was measured on; 0 in graphs read from elsewhere.
  size_t pair_index = 0;
};

struct RotationGraph {
  std::vector<uint32_t> node_ids;           // distinct ids; edges refer to nodes by id
  std::vector<RelativeRotationEdge> edges;  // no self loops; parallel edges are allowed
};

}  // namespace ramap
