// Clusters of a view graph that its pairs fix together, and the images that join them.
//
// Translation averaging fixes an image's position from its pairs' directions to images already
// fixed: two pairs to two fixed images place it (generically), one pair only leaves it anywhere
// along a ray. So a triangle of pairs is fixed up to one common scale, and it grows by every image
// with pairs to two of its images: a cluster (the greedy test of parallel rigidity by triangles;
// Kennedy, Daniilidis, Naroditsky, Taylor, "Identifying maximal rigid components in bearing-based
// localization", IROS 2012, give the exact one). Two clusters joined only through one image (every
// pair between them has that image at one end) share a point, not a scale: nothing in the pairs
// says how large one is against the other. Photos of something else whose pairs verify, joined to
// a scene through one photo that shows both (a poster, a print of the landmark), look like that.
#pragma once

#include <cstdint>
#include <vector>

#include "ramap/scene/rotation_graph.h"

namespace ramap {

// One label per node of `graph` (in node_ids' order): the cluster it belongs to (0, 1, ...,
// largest first), or -1 for a node in no cluster of three or more images. Parallel edges count
// once.
std::vector<int> TriangleClusters(const RotationGraph& graph);

// Between two clusters: the nodes at each end of the pairs that join them.
struct ClusterJoin {
  int cluster1 = 0;
  int cluster2 = 0;
  std::vector<uint32_t> images1;  // distinct node ids in cluster1 with a pair to cluster2
  std::vector<uint32_t> images2;
  int num_pairs = 0;
  // Every pair between them has one image at one end: the clusters' relative scale is free.
  bool through_one_image() const { return images1.size() == 1 || images2.size() == 1; }
};

// The joins between every two clusters of `labels` (TriangleClusters) that have a pair between
// them.
std::vector<ClusterJoin> ClusterJoins(const RotationGraph& graph, const std::vector<int>& labels);

}  // namespace ramap
