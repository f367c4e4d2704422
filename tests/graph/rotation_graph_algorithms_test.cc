// The view-graph utilities on small hand-made graphs whose answers can be read off.
#include "ramap/graph/rotation_graph_algorithms.h"

#include <gtest/gtest.h>

#include <stdexcept>

#include "ramap/geometry/rotation.h"

namespace ramap {
namespace {

Eigen::Quaterniond AboutZ(double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kDegToRad, Eigen::Vector3d::UnitZ()));
}

// Two components: a triangle 10-20-30 (edge weights 5, 1, 3) and a pair 40-50; node 60 alone.
RotationGraph TwoComponents() {
  RotationGraph graph;
  graph.node_ids = {10, 20, 30, 40, 50, 60};
  graph.edges = {{10, 20, AboutZ(10), 5.0},
                 {20, 30, AboutZ(20), 1.0},
                 {10, 30, AboutZ(30), 3.0},
                 {40, 50, AboutZ(40), 1.0}};
  return graph;
}

TEST(RotationGraph, NodeIndexRejectsUnknownNodesSelfLoopsAndDuplicates) {
  RotationGraph graph = TwoComponents();
  EXPECT_EQ(NodeIndex(graph).at(30), 2);
  graph.edges.push_back({10, 99, AboutZ(0), 1.0});
  EXPECT_THROW(NodeIndex(graph), std::invalid_argument);
  graph.edges.back() = {20, 20, AboutZ(0), 1.0};
  EXPECT_THROW(NodeIndex(graph), std::invalid_argument);
  graph.edges.pop_back();
  graph.node_ids.push_back(10);
  EXPECT_THROW(NodeIndex(graph), std::invalid_argument);
}

TEST(RotationGraph, ComponentsAreLabelledLargestFirst) {
  const RotationGraph graph = TwoComponents();
  const std::vector<int> labels = ConnectedComponents(graph);
  EXPECT_EQ(labels, (std::vector<int>{0, 0, 0, 1, 1, 2}));
  // Without the pair's edge, 40 and 50 fall apart into components of one, labelled by their first
  // node after the triangle: 40, 50, 60.
  const std::vector<int> kept = ConnectedComponents(graph, {true, true, true, false});
  EXPECT_EQ(kept, (std::vector<int>{0, 0, 0, 1, 2, 3}));
  // Equal sizes, interleaved: {1, 4} holds the first node, so it is component 0.
  RotationGraph pairs;
  pairs.node_ids = {1, 2, 3, 4};
  pairs.edges = {{1, 4, AboutZ(1), 1.0}, {2, 3, AboutZ(1), 1.0}};
  EXPECT_EQ(ConnectedComponents(pairs), (std::vector<int>{0, 1, 1, 0}));
  EXPECT_EQ(NodeDegrees(graph), (std::vector<int>{2, 2, 2, 1, 1, 0}));
  EXPECT_EQ(NodeDegrees(graph, {false, true, true, true}), (std::vector<int>{1, 1, 2, 1, 1, 0}));
}

TEST(RotationGraph, SpanningTreeKeepsTheHeaviestEdgesAndPropagatesRotations) {
  const RotationGraph graph = TwoComponents();
  // The triangle's tree is its two heaviest edges (5 and 3); the pair's edge joins 40 and 50.
  std::vector<size_t> tree = MaximumSpanningTree(graph);
  std::sort(tree.begin(), tree.end());
  EXPECT_EQ(tree, (std::vector<size_t>{0, 2, 3}));

  // From node 10 at identity: R_20 = R(10 deg), R_30 = R(30 deg) along the tree (not 10 + 20 via
  // the light edge; here both agree, so check the pair's component too).
  std::vector<Eigen::Quaterniond> rotations(6, Eigen::Quaterniond::Identity());
  std::vector<bool> known = {true, false, false, false, false, false};
  PropagateAlongTree(graph, tree, &rotations, &known);
  EXPECT_EQ(known, (std::vector<bool>{true, true, true, true, true, false}));
  EXPECT_LT(RotationAngleDeg(rotations[1], AboutZ(10)), 1e-9);
  EXPECT_LT(RotationAngleDeg(rotations[2], AboutZ(30)), 1e-9);
  // The pair has no known node: it starts from its first node (identity) and chains the edge.
  EXPECT_LT(RotationAngleDeg(rotations[3], Eigen::Quaterniond::Identity()), 1e-9);
  EXPECT_LT(RotationAngleDeg(rotations[4], AboutZ(40)), 1e-9);
}

TEST(RotationGraph, SubgraphKeepsTheTouchedNodesAndMapsEdges) {
  const RotationGraph graph = TwoComponents();
  std::vector<size_t> edge_map;
  const RotationGraph sub = Subgraph(graph, {false, true, false, true}, &edge_map);
  EXPECT_EQ(sub.node_ids, (std::vector<uint32_t>{20, 30, 40, 50}));
  ASSERT_EQ(sub.edges.size(), 2u);
  EXPECT_EQ(edge_map, (std::vector<size_t>{1, 3}));
  EXPECT_EQ(sub.edges[0].i, 20u);
  EXPECT_EQ(sub.edges[1].j, 50u);
}

}  // namespace
}  // namespace ramap
