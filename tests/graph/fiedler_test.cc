#include "ramap/graph/fiedler.h"

#include <gtest/gtest.h>

#include <cmath>

namespace ramap {
namespace {

RotationGraph MakeGraph(int n, const std::vector<std::pair<int, int>>& pairs) {
  RotationGraph graph;
  for (int k = 0; k < n; ++k) graph.node_ids.push_back(100 + k);  // ids need not be 0..n-1
  for (const auto& [a, b] : pairs) {
    RelativeRotationEdge edge;
    edge.i = 100 + a;
    edge.j = 100 + b;
    graph.edges.push_back(edge);
  }
  return graph;
}

RotationGraph Path(int n) {
  std::vector<std::pair<int, int>> pairs;
  for (int k = 0; k + 1 < n; ++k) pairs.emplace_back(k, k + 1);
  return MakeGraph(n, pairs);
}

TEST(Fiedler, PathClosedForm) {
  for (int n : {2, 3, 4, 10, 100, 1000}) {
    // lambda_2 = 2 (1 - cos(pi / n)).
    EXPECT_NEAR(FiedlerValue(Path(n)), 2.0 * (1.0 - std::cos(M_PI / n)), 1e-9) << n;
  }
}

TEST(Fiedler, CycleClosedForm) {
  for (int n : {3, 5, 12, 500}) {
    std::vector<std::pair<int, int>> pairs;
    for (int k = 0; k < n; ++k) pairs.emplace_back(k, (k + 1) % n);
    EXPECT_NEAR(FiedlerValue(MakeGraph(n, pairs)), 2.0 * (1.0 - std::cos(2.0 * M_PI / n)), 1e-9)
        << n;
  }
}

TEST(Fiedler, CompleteGraphIsN) {
  for (int n : {4, 7, 30}) {
    std::vector<std::pair<int, int>> pairs;
    for (int a = 0; a < n; ++a) {
      for (int b = a + 1; b < n; ++b) pairs.emplace_back(a, b);
    }
    EXPECT_NEAR(FiedlerValue(MakeGraph(n, pairs)), n, 1e-9) << n;
  }
}

TEST(Fiedler, WeightedAndParallelEdges) {
  RotationGraph graph = Path(10);
  graph.edges.push_back(graph.edges[3]);  // a parallel edge: ignored unweighted
  EXPECT_NEAR(FiedlerValue(graph), 2.0 * (1.0 - std::cos(M_PI / 10)), 1e-9);
  RotationGraph doubled = Path(10);
  for (auto& edge : doubled.edges) edge.weight = 2.0;
  EXPECT_NEAR(FiedlerValue(doubled, /*weighted=*/true), 4.0 * (1.0 - std::cos(M_PI / 10)), 1e-9);
}

TEST(Fiedler, DisconnectedIsZero) {
  RotationGraph graph = MakeGraph(6, {{0, 1}, {1, 2}, {3, 4}, {4, 5}});
  EXPECT_EQ(FiedlerValue(graph), 0.0);
  std::vector<bool> keep(Path(5).edges.size(), true);
  keep[2] = false;
  EXPECT_EQ(FiedlerValue(Path(5), false, keep), 0.0);
}

TEST(Fiedler, StrongDualityBoundFormula) {
  // Complete graph K_n: lambda_2 = n, d_max = n - 1.
  const double k10 = StrongDualityResidualBound(10.0, 9);
  EXPECT_NEAR(k10, 2.0 * std::asin(std::sqrt(0.25 + 10.0 / 18.0) - 0.5), 1e-15);
  // As n grows the bound tends to 2 asin(sqrt(3)/2 - 1/2) = 42.94 deg, from above.
  const double limit = 2.0 * std::asin(std::sqrt(0.75) - 0.5);
  EXPECT_NEAR(limit * 180.0 / M_PI, 42.94, 0.01);
  EXPECT_GT(k10, limit);
  EXPECT_NEAR(StrongDualityResidualBound(1e6, 1e6 - 1), limit, 1e-6);
  // Monotone in lambda_2, decreasing in d_max; 0 for disconnected graphs.
  EXPECT_LT(StrongDualityResidualBound(0.1, 4), StrongDualityResidualBound(0.2, 4));
  EXPECT_GT(StrongDualityResidualBound(0.2, 4), StrongDualityResidualBound(0.2, 8));
  EXPECT_EQ(StrongDualityResidualBound(0.0, 4), 0.0);
  // A cycle of 3 (= K_3): lambda_2 = 3, d_max = 2: sqrt(1/4 + 3/4) - 1/2 = 1/2, bound 60 deg.
  EXPECT_NEAR(StrongDualityResidualBound(3.0, 2) * 180.0 / M_PI, 60.0, 1e-12);
}

}  // namespace
}  // namespace ramap
