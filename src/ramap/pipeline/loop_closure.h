// Loop closure for image-list input matched sequentially: the loop candidates of a first solve
// (graph/loop_candidates.h: positions close) are matched and verified (enough inliers), so that a
// second solve has the loop edges in its pose graph.
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "ramap/features/feature_matching.h"
#include "ramap/graph/loop_candidates.h"
#include "ramap/pipeline/mapper.h"

namespace ramap {

struct LoopClosureSummary {
  int num_candidates = 0;
  int num_verified = 0;            // candidates that got a two-view geometry: the loop edges
  std::vector<std::string> loops;  // "NAME1 NAME2: N inliers"
  double seconds = 0.0;
};

// Candidates in every model of `first`, matched and verified into `database` (descriptors needed).
LoopClosureSummary MatchLoopCandidates(const MapperResult& first,
                                       const LoopCandidateOptions& options,
                                       const FeatureMatchingOptions& matching,
                                       FeatureDatabase* database, std::ostream* progress = nullptr);

}  // namespace ramap
