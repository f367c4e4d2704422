// Stage 2 of the mapper: the view graph of the accepted relative poses, cut into its connected
// components; each component large enough is reconstructed on its own (mapper/mapper.cc).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "ramap/mapper/stage_log.h"
#include "ramap/scene/features.h"
#include "ramap/scene/rotation_graph.h"
#include "ramap/scene/view_graph.h"

namespace ramap {

// The view graph of the accepted pairs (scene/view_graph.h). Every rejected pair goes to the
// report's dropped edges with its reason, and every image left without an accepted pair gets the
// reason of its rejected ones.
RotationGraph RotationGraphOfAcceptedPairs(const FeatureDatabase& database,
                                           const std::vector<ImagePair>& pairs,
                                           StageReport* report);

// The connected components of `graph`, each cut where two of its parts are joined through one
// image with no track seen on both sides (graph/rigid_clusters.h: their relative scale is free),
// largest first. Those with fewer than `min_size` images are left out and their images get the
// reason in report->image_reasons; the pairs cut go to report->dropped_edges.
std::vector<RotationGraph> ComponentsToReconstruct(const RotationGraph& graph, int min_size,
                                                   const FeatureDatabase& database,
                                                   StageReport* report);

}  // namespace ramap
