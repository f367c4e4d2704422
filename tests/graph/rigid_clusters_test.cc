// Clusters a view graph's pairs fix together, and the joins between them (graph/rigid_clusters.h).
#include "ramap/graph/rigid_clusters.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <utility>
#include <vector>

namespace ramap {
namespace {

RotationGraph Graph(const std::vector<std::pair<uint32_t, uint32_t>>& pairs) {
  RotationGraph graph;
  std::vector<uint32_t> ids;
  for (const auto& [i, j] : pairs) {
    for (const uint32_t id : {i, j})
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
    RelativeRotationEdge edge;
    edge.i = i;
    edge.j = j;
    graph.edges.push_back(edge);
  }
  std::sort(ids.begin(), ids.end());
  graph.node_ids = ids;
  return graph;
}

// Every pair among `ids`.
void AddClique(const std::vector<uint32_t>& ids, std::vector<std::pair<uint32_t, uint32_t>>* out) {
  for (size_t a = 0; a < ids.size(); ++a)
    for (size_t b = a + 1; b < ids.size(); ++b) out->emplace_back(ids[a], ids[b]);
}

TEST(RigidClusters, TwoCliquesJoinedThroughOneImageAreTwoClustersWithAFreeScale) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  AddClique({1, 2, 3, 4, 5}, &pairs);
  AddClique({11, 12, 13, 14}, &pairs);
  // Image 5 shows both: it has pairs to 11, 12 and 13 (never two images on its own side).
  for (const uint32_t other : {11u, 12u, 13u}) pairs.emplace_back(5, other);
  const RotationGraph graph = Graph(pairs);
  const std::vector<int> labels = TriangleClusters(graph);
  ASSERT_EQ(labels.size(), 9u);
  std::set<int> first(labels.begin(), labels.begin() + 5), second(labels.begin() + 5, labels.end());
  ASSERT_EQ(first.size(), 1u);
  ASSERT_EQ(second.size(), 1u);
  EXPECT_NE(*first.begin(), *second.begin());
  EXPECT_EQ(*first.begin(), 0);  // the larger one
  const std::vector<ClusterJoin> joins = ClusterJoins(graph, labels);
  ASSERT_EQ(joins.size(), 1u);
  EXPECT_EQ(joins[0].num_pairs, 3);
  EXPECT_TRUE(joins[0].through_one_image());
}

TEST(RigidClusters, PairsBetweenTwoImagesOnEachSideFixTheScale) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  AddClique({1, 2, 3, 4}, &pairs);
  AddClique({11, 12, 13, 14}, &pairs);
  pairs.emplace_back(3, 11);
  pairs.emplace_back(4, 12);
  const RotationGraph graph = Graph(pairs);
  const std::vector<int> labels = TriangleClusters(graph);
  const std::vector<ClusterJoin> joins = ClusterJoins(graph, labels);
  // 11 and 12 each have one pair into the first clique: two clusters, joined at two images a side.
  ASSERT_EQ(joins.size(), 1u);
  EXPECT_FALSE(joins[0].through_one_image());
}

TEST(RigidClusters, AChainHasNoTriangleAndSoNoCluster) {
  const RotationGraph graph = Graph({{1, 2}, {2, 3}, {3, 4}, {4, 5}});
  for (const int label : TriangleClusters(graph)) EXPECT_EQ(label, -1);
  EXPECT_TRUE(ClusterJoins(graph, TriangleClusters(graph)).empty());
}

TEST(RigidClusters, ASequencesWindowsAreOneCluster) {
  std::vector<std::pair<uint32_t, uint32_t>> pairs;
  for (uint32_t i = 1; i <= 40; ++i)
    for (uint32_t k = 1; k <= 3 && i + k <= 40; ++k) pairs.emplace_back(i, i + k);
  for (const int label : TriangleClusters(Graph(pairs))) EXPECT_EQ(label, 0);
}

}  // namespace
}  // namespace ramap
