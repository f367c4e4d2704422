// Rotation averaging of a whole view graph: keyframe windows first for sequences, the whole graph
// at once for unordered collections (docs/architecture.md, stages 2 and 3). Shared by the mapper
// (mapper/component_rotations.h) and `ramap rotation_averager`.
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/graph/keyframes.h"
#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/io/relative_pose_file.h"
#include "ramap/scene/image_order.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// Whether rotation averaging weights each edge by its pair's inlier count (IRLS weights times the
// count; RotationAveragingOptions::use_edge_weights).
enum class EdgeWeighting {
  // On when every camera's focal length is known (prior_focal_length 1), off otherwise: the
  // weights help averaging alone through the true intrinsics and hurt it through focal lengths
  // the view graph estimated, and change little with BA (docs/benchmark-history.md, "Edges
  // weighted by their inlier counts").
  kAuto,
  kOn,
  kOff,
};

struct RotationStageResult {
  RotationAveragingResult rotations;
  int num_keyframes = 0;   // 0 for unordered input
  int num_loop_edges = 0;  // edges joining frames of no common keyframe window
};

// Whether rotation averaging weights its edges by inlier counts: as `weighting` says, or with
// kAuto when every camera of `database` has a known focal length (prior_focal_length 1): weights
// help averaging through true intrinsics and hurt it through estimated ones (EdgeWeighting).
bool UseRotationEdgeWeights(EdgeWeighting weighting, const FeatureDatabase& database);
// The same for input whose focal lengths are known or not (relative poses read from a file carry
// no cameras: not known).
bool UseRotationEdgeWeights(EdgeWeighting weighting, bool focal_lengths_known);

// Whether every camera of `database` has a known focal length (prior_focal_length 1).
bool AllFocalLengthsKnown(const FeatureDatabase& database);

// `capture_order` lists node ids in capture order (ids not in the graph are ignored); it is only
// used when `sequential`.
RotationStageResult AverageGraphRotations(const RotationGraph& graph,
                                          const std::vector<uint32_t>& capture_order,
                                          bool sequential, const KeyframeOptions& view_graph,
                                          const RotationAveragingOptions& options);

// The view graph of relative pose records, its nodes numbered 0, 1, ... by image name in order
// of first appearance (`names`, by node); the first record of two images counts.
RotationGraph RotationGraphOfRecords(const std::vector<RelativePoseRecord>& records,
                                     std::vector<std::string>* names);

// `ramap rotation_averager` on relative pose records: their graph (RotationGraphOfRecords), in
// capture order of the names when `order` makes them a sequence, averaged as the mapper does.
struct RecordRotations {
  std::vector<std::string> names;  // by node id
  int num_edges = 0;
  bool sequential = false;
  RotationStageResult stage;
  std::vector<RotationRecord> rotations;  // the estimated ones, by image name
  double seconds = 0.0;                   // averaging alone
};
RecordRotations AverageRecordRotations(const std::vector<RelativePoseRecord>& records,
                                       InputOrder order, const KeyframeOptions& view_graph,
                                       const RotationAveragingOptions& options);

}  // namespace ramap
