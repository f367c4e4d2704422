#include "ramap/graph/keyframes.h"

#include <gtest/gtest.h>

#include "ramap/graph/rotation_graph_algorithms.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

TEST(Keyframes, EveryNFramesWithLastFrame) {
  std::vector<uint32_t> frames;
  for (uint32_t k = 0; k < 71; ++k) frames.push_back(10 + k);
  KeyframeOptions options;
  options.keyframe_interval = 30;
  const Keyframes keyframes = SelectKeyframes(frames, options);
  EXPECT_EQ(keyframes.keyframe_ids, (std::vector<uint32_t>{10, 40, 70, 80}));
  ASSERT_EQ(keyframes.windows.size(), 3u);
  EXPECT_EQ(keyframes.windows[0].frames.size(), 31u);
  EXPECT_EQ(keyframes.windows[0].frames.front(), 10u);
  EXPECT_EQ(keyframes.windows[0].frames.back(), 40u);
  EXPECT_EQ(keyframes.windows[2].first_keyframe, 70u);
  EXPECT_EQ(keyframes.windows[2].second_keyframe, 80u);
  EXPECT_EQ(keyframes.windows[2].frames.size(), 11u);
}

TEST(Keyframes, ExactMultipleAndTinySequences) {
  KeyframeOptions options;
  options.keyframe_interval = 5;
  EXPECT_EQ(SelectKeyframes({0, 1, 2, 3, 4, 5}, options).keyframe_ids,
            (std::vector<uint32_t>{0, 5}));
  const Keyframes one = SelectKeyframes({7}, options);
  EXPECT_EQ(one.keyframe_ids, (std::vector<uint32_t>{7}));
  EXPECT_TRUE(one.windows.empty());
  EXPECT_TRUE(SelectKeyframes({}, options).keyframe_ids.empty());
  options.keyframe_interval = 0;
  EXPECT_THROW(SelectKeyframes({0, 1}, options), InputError);
}

TEST(Keyframes, ClassifiesLocalAndLoopEdges) {
  std::vector<uint32_t> frames;
  for (uint32_t k = 0; k < 20; ++k) frames.push_back(k);
  KeyframeOptions options;
  options.keyframe_interval = 5;
  const Keyframes keyframes = SelectKeyframes(frames, options);  // 0 5 10 15 19
  RotationGraph graph;
  graph.node_ids = frames;
  auto add = [&](uint32_t i, uint32_t j) {
    RelativeRotationEdge edge;
    edge.i = i;
    edge.j = j;
    graph.edges.push_back(edge);
  };
  add(1, 4);    // inside window 0
  add(5, 10);   // both keyframes of window 1
  add(4, 6);    // windows 0 and 1 share only frame 5
  add(0, 19);   // loop
  add(10, 14);  // window 2
  add(5, 3);    // keyframe 5 belongs to windows 0 and 1
  const std::vector<EdgeKind> kinds = ClassifyEdges(graph, keyframes);
  EXPECT_EQ(kinds, (std::vector<EdgeKind>{EdgeKind::kLocal, EdgeKind::kLocal, EdgeKind::kLoop,
                                          EdgeKind::kLoop, EdgeKind::kLocal, EdgeKind::kLocal}));
}

TEST(Keyframes, ViewGraphComponentsAndSpanningTree) {
  RotationGraph graph;
  graph.node_ids = {0, 1, 2, 3, 4, 5};
  auto add = [&](uint32_t i, uint32_t j, double w) {
    RelativeRotationEdge edge;
    edge.i = i;
    edge.j = j;
    edge.weight = w;
    edge.R_ij =
        Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * (i + 1) + 0.01 * j, Eigen::Vector3d::UnitX()));
    graph.edges.push_back(edge);
  };
  add(0, 1, 5);
  add(1, 2, 1);
  add(0, 2, 3);
  add(3, 4, 2);
  const std::vector<int> labels = ConnectedComponents(graph);
  EXPECT_EQ(labels, (std::vector<int>{0, 0, 0, 1, 1, 2}));
  const std::vector<size_t> tree = MaximumSpanningTree(graph);
  EXPECT_EQ(tree, (std::vector<size_t>{0, 2, 3}));  // the weight-1 edge closes a cycle
  std::vector<Eigen::Quaterniond> rotations;
  std::vector<bool> known;
  PropagateAlongTree(graph, tree, &rotations, &known);
  EXPECT_EQ(known, (std::vector<bool>{true, true, true, true, true, false}));
  // Tree edges are satisfied exactly: R_j = R_ij R_i.
  for (size_t e : tree) {
    const auto& edge = graph.edges[e];
    EXPECT_LT(rotations[edge.j].angularDistance(edge.R_ij * rotations[edge.i]), 1e-12);
  }
}

}  // namespace
}  // namespace ramap
