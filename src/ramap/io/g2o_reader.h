// Reads the rotation part of g2o files (the SE-Sync / SLAM benchmark files) as a
// ViewGraph. Lines read: VERTEX_SE3:QUAT, EDGE_SE3:QUAT, VERTEX_SE2, EDGE_SE2 (planar
// rotations about z); any other line (comments, FIX, landmarks, ...) is ignored.
//
// g2o stores poses T_k = world_from_body and an edge (i, j) measures T_ij = T_i^{-1} T_j, so its
// rotation is Q_ij = Q_i^T Q_j. In ramap's convention (scene/rotation_graph.h) R_k = Q_k^T is
// cam_from_world (body = camera) and R_ij = R_j R_i^T = Q_j^T Q_i = Q_ij^T: the edge holds the
// inverse of the g2o rotation, and a vertex rotation is the inverse of the g2o quaternion.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <unordered_map>
#include <vector>

#include "ramap/scene/rotation_graph.h"

namespace ramap {

struct G2oPoseGraph {
  // Nodes: every vertex id and every id named by an edge, in order of first appearance.
  // Edge weight: the rotational precision kappa = 3 / (2 trace(Sigma_rot)) (SE-Sync's loader),
  // Sigma_rot the inverse of the rotational 3x3 block of the information matrix; for SE2 the
  // theta information.
  RotationGraph graph;
  // cam_from_world rotations of the VERTEX lines (the file's initial guess), by node id.
  std::unordered_map<uint32_t, Eigen::Quaterniond> vertex_rotations;
  bool planar = false;  // the file holds SE2 lines
};

// Throws InputError(path, "line N: ...") on an unreadable file or a malformed VERTEX/EDGE line.
G2oPoseGraph ReadG2oPoseGraph(const std::string& path);

}  // namespace ramap
