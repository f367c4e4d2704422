// Stage 3 of the mapper on one connected view graph: keyframe windows first for sequences, the
// whole graph at once for unordered collections (DESIGN.md steps 2 and 3). Shared by `ramap
// mapper` and `ramap rotation_averager`.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/graph/keyframes.h"
#include "ramap/graph/rotation_graph.h"
#include "ramap/io/relative_pose_file.h"

namespace ramap {

struct RotationStageResult {
  RotationAveragingResult rotations;
  int num_keyframes = 0;   // 0 for unordered input
  int num_loop_edges = 0;  // edges joining frames of no common keyframe window
};

// `capture_order` lists node ids in capture order (ids not in the graph are ignored); it is only
// used when `sequential`.
RotationStageResult AverageViewGraphRotations(const RotationGraph& graph,
                                              const std::vector<uint32_t>& capture_order,
                                              bool sequential, const KeyframeOptions& pose_graph,
                                              const RotationAveragingOptions& options);

// The weight of a relative rotation in averaging: its number of inliers (at least 1, for records
// read from a file that gives none).
double RelativeRotationWeight(int num_inliers);

// The rotation graph of relative pose records, its nodes numbered 0, 1, ... by image name in order
// of first appearance (`names`, by node); the first record of two images counts.
RotationGraph RotationGraphOfRecords(const std::vector<RelativePoseRecord>& records,
                                     std::vector<std::string>* names);

}  // namespace ramap
