// A ring of views around a landmark whose back looks like its front (estimators/rotation_folds.h):
// its true solution and the fold along the symmetry compared. The mapper end to end on such
// scenes: tests/mapper/symmetric_pairs_test.cc.
#include "ramap/estimators/rotation_folds.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ramap {
namespace {

constexpr int kNumViews = 48;

Eigen::Quaterniond AboutY(double angle_rad) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitY()));
}

// cam_from_world of view k, turned 360 / kNumViews degrees further about y than view k - 1.
Eigen::Quaterniond TrueRotation(int k) { return AboutY(2.0 * M_PI * k / kNumViews); }

// The ring: each view paired with the next three (900 inliers each), and 21 symmetric pairs
// between views about half a turn apart (200 inliers each), measured as if the second view were
// turned half a turn about the landmark's axis: R_j S R_i^T with S = AboutY(pi).
RotationGraph SymmetricRing() {
  RotationGraph graph;
  for (int k = 0; k < kNumViews; ++k) graph.node_ids.push_back(k);
  for (int i = 0; i < kNumViews; ++i) {
    for (int step = 1; step <= 3; ++step) {
      const int j = (i + step) % kNumViews;
      graph.edges.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(j),
                             TrueRotation(j) * TrueRotation(i).conjugate(), 900.0});
    }
  }
  for (int n = 0; n < 21; ++n) {
    const int i = (n * 7) % kNumViews;
    const int j = (i + kNumViews / 2 - 3 + n % 7) % kNumViews;
    graph.edges.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(j),
                           TrueRotation(j) * AboutY(M_PI) * TrueRotation(i).conjugate(), 200.0});
  }
  return graph;
}

// The true solution, all edges kept but the symmetric ones.
RotationAveragingResult TrueSolution(const RotationGraph& graph) {
  RotationAveragingResult result;
  result.node_ids = graph.node_ids;
  for (int k = 0; k < kNumViews; ++k) result.rotations.push_back(TrueRotation(k));
  result.estimated.assign(kNumViews, true);
  for (const RelativeRotationEdge& edge : graph.edges) {
    result.edge_status.push_back(edge.weight < 500 ? EdgeStatus::kPrunedResidual
                                                   : EdgeStatus::kKept);
  }
  return result;
}

// The fold: views 12-35 (the far side) turned half a turn about the axis onto the near side, in
// a gauge of their own (the whole solution turned by 10 degrees), so that the symmetric pairs
// agree with it and the ring's pairs across the two seams (at 11-12 and 35-36) do not.
RotationAveragingResult FoldedSolution(const RotationGraph& graph) {
  RotationAveragingResult result = TrueSolution(graph);
  const auto far_side = [](uint32_t k) { return k >= 12 && k < 36; };
  for (int k = 0; k < kNumViews; ++k) {
    if (far_side(k)) result.rotations[k] = result.rotations[k] * AboutY(M_PI);
    result.rotations[k] = result.rotations[k] * AboutY(10.0 * M_PI / 180.0);
  }
  for (size_t e = 0; e < graph.edges.size(); ++e) {
    const RelativeRotationEdge& edge = graph.edges[e];
    const bool consistent = (far_side(edge.i) == far_side(edge.j)) == (edge.weight > 500);
    result.edge_status[e] = consistent ? EdgeStatus::kKept : EdgeStatus::kPrunedResidual;
  }
  return result;
}

TEST(RotationFolds, TheSolutionLeavingOutFewerInliersUnfoldsTheOther) {
  const RotationGraph graph = SymmetricRing();
  const RotationAveragingResult truth = TrueSolution(graph);
  const RotationAveragingResult folded = FoldedSolution(graph);
  const RotationSolutionComparison comparison = CompareRotationSolutions(graph, folded, truth);
  EXPECT_EQ(comparison.num_estimated_first, kNumViews);
  EXPECT_EQ(comparison.num_estimated_second, kNumViews);
  EXPECT_NEAR(comparison.largest_difference_deg, 180.0, 1e-6);
  // The fold leaves out the ring's pairs across its two seams (1 + 2 + 3 at each) and the one
  // symmetric pair with both views on one side of them; the truth, the 21 symmetric pairs.
  EXPECT_DOUBLE_EQ(comparison.left_out_weight_first, 12 * 900.0 + 1 * 200.0);
  EXPECT_DOUBLE_EQ(comparison.left_out_weight_second, 21 * 200.0);
  EXPECT_TRUE(SecondSolutionUnfolds(comparison, 20.0));
  // The other way round the truth is kept, and two solutions that agree are never swapped.
  EXPECT_FALSE(SecondSolutionUnfolds(CompareRotationSolutions(graph, truth, folded), 20.0));
  EXPECT_FALSE(SecondSolutionUnfolds(CompareRotationSolutions(graph, truth, truth), 20.0));
  // Nor for a solution that estimates fewer views.
  RotationAveragingResult partial = truth;
  partial.estimated[5] = false;
  EXPECT_FALSE(SecondSolutionUnfolds(CompareRotationSolutions(graph, folded, partial), 20.0));
}

}  // namespace
}  // namespace ramap
