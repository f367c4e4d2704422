#include "ramap/scene/view_graph.h"

#include <algorithm>
#include <set>

namespace ramap {

const char* RelativePoseRejectionName(RelativePoseRejection rejection) {
  switch (rejection) {
    case RelativePoseRejection::kNone:
      return "accepted";
    case RelativePoseRejection::kInvalidInput:
      return "invalid input";
    case RelativePoseRejection::kUnknownFocalLength:
      return "focal length unknown";
    case RelativePoseRejection::kTooFewMatches:
      return "too few matches";
    case RelativePoseRejection::kTooLittleSpread:
      return "too little spread (one grid cell or collinear)";
    case RelativePoseRejection::kNoMotion:
      return "no motion between the images";
    case RelativePoseRejection::kPureRotationTooFewInliers:
      return "pure rotation with too few inliers";
    case RelativePoseRejection::kNoHypothesis:
      return "no rotation hypothesis";
    case RelativePoseRejection::kTooFewInliers:
      return "too few inliers";
    case RelativePoseRejection::kRefinementDiverged:
      return "refinement diverged";
    case RelativePoseRejection::kLowInlierRatio:
      return "inlier ratio below min_inlier_ratio";
    case RelativePoseRejection::kNonFiniteEstimate:
      return "non-finite estimate";
  }
  return "unknown";
}

std::vector<FeatureMatch> InlierMatches(const ImagePair& pair, const TwoViewGeometry& geometry) {
  std::vector<FeatureMatch> matches;
  matches.reserve(pair.estimate.num_inliers);
  for (size_t k = 0; k < pair.is_inlier.size() && k < geometry.inlier_matches.size(); ++k) {
    if (pair.is_inlier[k]) matches.push_back(geometry.inlier_matches[k]);
  }
  return matches;
}

double RelativeRotationWeight(int num_inliers) {
  return static_cast<double>(std::max(num_inliers, 1));
}

RotationGraph AcceptedRotationGraph(const std::vector<ImagePair>& pairs) {
  RotationGraph graph;
  std::set<uint32_t> nodes;
  for (size_t k = 0; k < pairs.size(); ++k) {
    const ImagePair& pair = pairs[k];
    if (!pair.accepted()) continue;
    graph.edges.push_back({pair.image_id1, pair.image_id2, pair.estimate.rotation,
                           RelativeRotationWeight(pair.estimate.num_inliers), k});
    nodes.insert({pair.image_id1, pair.image_id2});
  }
  graph.node_ids.assign(nodes.begin(), nodes.end());
  return graph;
}

}  // namespace ramap
