// Stage 2 of the mapper: the accepted pairs become the view graph (each edge naming its pair),
// rejected pairs and the images they leave alone are explained, and components too small to
// reconstruct are set aside with their reason.
#include "ramap/mapper/components.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

ImagePair Pair(uint32_t id1, uint32_t id2, bool accepted, int num_inliers = 50) {
  ImagePair pair;
  pair.image_id1 = id1;
  pair.image_id2 = id2;
  pair.estimate.success = accepted;
  pair.estimate.num_inliers = num_inliers;
  if (!accepted) pair.estimate.reason = "too few inliers (3 < 15)";
  return pair;
}

FeatureDatabase Images(uint32_t count) {
  FeatureDatabase database;
  for (uint32_t id = 1; id <= count; ++id) database.images[id].name = "im" + std::to_string(id);
  return database;
}

TEST(Components, AcceptedPairsAreTheGraphAndRejectedOnesAreExplained) {
  const FeatureDatabase database = Images(5);
  // 4-5 rejected: 5 has no other pair; 1-4 rejected but 4 is joined through 3-4.
  const std::vector<ImagePair> pairs = {Pair(1, 2, true, 80), Pair(1, 4, false), Pair(2, 3, true),
                                        Pair(3, 4, true), Pair(4, 5, false)};
  StageReport report;
  const RotationGraph graph = RotationGraphOfAcceptedPairs(database, pairs, &report);
  const std::map<uint32_t, std::string>& reasons = report.image_reasons;
  EXPECT_EQ(graph.node_ids, (std::vector<uint32_t>{1, 2, 3, 4}));
  ASSERT_EQ(graph.edges.size(), 3u);
  EXPECT_EQ(graph.edges[0].pair_index, 0u);
  EXPECT_EQ(graph.edges[0].weight, 80.0);
  EXPECT_EQ(graph.edges[1].pair_index, 2u);
  EXPECT_EQ(graph.edges[2].pair_index, 3u);
  ASSERT_EQ(report.dropped_edges.size(), 2u);
  EXPECT_EQ(report.dropped_edges[0].what, "im1 im4");
  EXPECT_EQ(report.dropped_edges[0].reason, "relative pose rejected: too few inliers (3 < 15)");
  ASSERT_EQ(reasons.size(), 1u);
  EXPECT_EQ(reasons.at(5), "every relative pose rejected (too few inliers (3 < 15))");
}

TEST(Components, SmallComponentsAreSetAsideLargestFirst) {
  const FeatureDatabase database = Images(9);
  const std::vector<ImagePair> pairs = {Pair(1, 2, true), Pair(6, 7, true), Pair(7, 8, true),
                                        Pair(8, 9, true), Pair(2, 3, true), Pair(4, 5, true)};
  StageReport report;
  const RotationGraph graph = RotationGraphOfAcceptedPairs(database, pairs, &report);
  std::map<uint32_t, std::string>& reasons = report.image_reasons;
  const std::vector<RotationGraph> components =
      ComponentsToReconstruct(graph, 3, database, &report);
  ASSERT_EQ(components.size(), 2u);
  EXPECT_EQ(components[0].node_ids, (std::vector<uint32_t>{6, 7, 8, 9}));
  EXPECT_EQ(components[1].node_ids, (std::vector<uint32_t>{1, 2, 3}));
  ASSERT_EQ(components[1].edges.size(), 2u);
  EXPECT_EQ(components[1].edges[1].pair_index, 4u);  // the pair 2-3, fifth in the view graph
  EXPECT_EQ(reasons.at(4), "in a component of 2 images (< Mapper.min_component_size 3)");
  EXPECT_EQ(reasons.count(1), 0u);
}

}  // namespace
}  // namespace ramap
