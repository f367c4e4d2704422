// Synthetic relative-view graphs with known ground truth, for tests and benchmarks: cameras
// along a path (a sequence), each linked to its next neighbours, plus loop edges between distant
// cameras, Gaussian rotation noise and a fraction of outlier edges replaced by random rotations.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/util/statistics.h"  // Median, which the rotation tests and benchmark use

namespace ramap {

struct SyntheticRotationGraphOptions {
  int num_nodes = 200;
  // Each camera is linked to the next `forward_neighbours` cameras of the sequence (so to about
  // twice as many nearest neighbours in all).
  int forward_neighbours = 4;
  // Extra edges between cameras at least `loop_min_gap` apart in the sequence.
  int num_loop_edges = 20;
  int loop_min_gap = 20;
  // Step of the random walk of the true rotations between consecutive cameras (degrees).
  double rotation_step_deg = 5.0;
  // Standard deviation of the noise rotation, per axis of its rotation vector (degrees).
  double noise_deg = 2.0;
  // Fraction of edges whose measurement is replaced by a uniformly random rotation.
  double outlier_fraction = 0.0;
  uint32_t seed = 1;
};

struct SyntheticRotationGraph {
  RotationGraph graph;                             // node ids 0..num_nodes-1 in sequence order
  std::vector<Eigen::Quaterniond> true_rotations;  // cam_from_world per node
  std::vector<bool> is_outlier;                    // per edge
};

// Edge weights mimic inlier counts: they fall with the sequence gap; outliers keep the weight of
// the edge they replace (the weight says nothing about them, as in practice).
SyntheticRotationGraph MakeSyntheticRotationGraph(const SyntheticRotationGraphOptions& options);

// Per-node angle (degrees) between estimated and true rotations after the best global gauge
// R_est ~ R_true G (chordal mean, then one reweighting step that discounts outlying nodes).
// Nodes with estimated[k] == false (when given) are skipped.
std::vector<double> AlignedRotationErrorsDeg(
    const std::vector<Eigen::Quaterniond>& estimated_rotations,
    const std::vector<Eigen::Quaterniond>& true_rotations, const std::vector<bool>& estimated = {});

}  // namespace ramap
