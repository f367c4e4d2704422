// The triangle bound on hand-made triangles whose cycle angle can be read off, and its defining
// property on random graphs: no rotation assignment has a smaller largest residual.
#include "ramap/graph/cycle_consistency.h"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "ramap/averaging/rotation_averaging.h"
#include "ramap/geometry/rotation.h"
#include "ramap/synthetic/synthetic_rotation_graph.h"

namespace ramap {
namespace {

constexpr double kNoStop = std::numeric_limits<double>::infinity();

Eigen::Quaterniond AboutZ(double degrees) {
  return Eigen::Quaterniond(Eigen::AngleAxisd(degrees * kDegToRad, Eigen::Vector3d::UnitZ()));
}

// 10 -> 20 by 10 deg and 20 -> 30 by 20 deg about z, closed by 10 -> 30 at 30 + `closing_error`.
RotationGraph Triangle(double closing_error_deg) {
  RotationGraph graph;
  graph.node_ids = {10, 20, 30};
  graph.edges = {{10, 20, AboutZ(10), 1.0},
                 {20, 30, AboutZ(20), 1.0},
                 {10, 30, AboutZ(30 + closing_error_deg), 1.0}};
  return graph;
}

TEST(TriangleCycleBound, ReadsTheCycleAngleOfATriangle) {
  const std::vector<bool> all_active(3, true);
  const TriangleCycleBound bound =
      TriangleCycleResidualBound(Triangle(6.0), {true, true, true}, all_active, kNoStop);
  EXPECT_EQ(bound.triangles_checked, 1u);
  EXPECT_NEAR(bound.residual_lower_bound_deg, 2.0, 1e-9);
  // The same triangle with the closing edge stored the other way round.
  RotationGraph reversed = Triangle(6.0);
  reversed.edges[2] = {30, 10, AboutZ(36).conjugate(), 1.0};
  EXPECT_NEAR(TriangleCycleResidualBound(reversed, {true, true, true}, all_active, kNoStop)
                  .residual_lower_bound_deg,
              2.0, 1e-9);
  // A dropped edge or an inactive node leaves no triangle.
  EXPECT_EQ(TriangleCycleResidualBound(Triangle(6.0), {true, false, true}, all_active, kNoStop)
                .triangles_checked,
            0u);
  EXPECT_EQ(
      TriangleCycleResidualBound(Triangle(6.0), {true, true, true}, {true, true, false}, kNoStop)
          .triangles_checked,
      0u);
}

// 60 nodes along a path, each linked to its next 5, 2 deg noise.
SyntheticRotationGraph NoisyPath(int num_loop_edges, double outlier_fraction, uint32_t seed) {
  SyntheticRotationGraphOptions options;
  options.num_nodes = 60;
  options.forward_neighbours = 5;
  options.num_loop_edges = num_loop_edges;
  options.noise_deg = 2.0;
  options.outlier_fraction = outlier_fraction;
  options.seed = seed;
  return MakeSyntheticRotationGraph(options);
}

// The bound over the whole graph, every edge kept and every node active, stopping above
// `stop_above_deg`.
TriangleCycleBound WholeGraphBound(const RotationGraph& graph, double stop_above_deg) {
  return TriangleCycleResidualBound(graph, std::vector<bool>(graph.edges.size(), true),
                                    std::vector<bool>(graph.node_ids.size(), true), stop_above_deg);
}

// The true rotations and averaged ones on a noisy graph with outliers: each leaves some edge
// with a residual at least the bound, which must also be positive (the noise closes no triangle).
TEST(TriangleCycleBound, NoAssignmentHasASmallerLargestResidual) {
  const SyntheticRotationGraph synthetic = NoisyPath(20, 0.05, 7);
  const TriangleCycleBound bound = WholeGraphBound(synthetic.graph, kNoStop);
  EXPECT_GT(bound.triangles_checked, 100u);
  EXPECT_GT(bound.residual_lower_bound_deg, 0.5);

  auto max_residual_deg = [&](const std::vector<Eigen::Quaterniond>& rotations) {
    double largest = 0.0;
    for (const RelativeRotationEdge& edge : synthetic.graph.edges) {
      largest = std::max(largest, EdgeResidualDeg(edge, rotations[edge.i], rotations[edge.j]));
    }
    return largest;
  };
  EXPECT_GE(max_residual_deg(synthetic.true_rotations), bound.residual_lower_bound_deg);
  // Averaged rotations try to make every residual small; they cannot beat the bound either.
  EXPECT_GE(max_residual_deg(AverageRotations(synthetic.graph, {}).rotations),
            bound.residual_lower_bound_deg);
}

TEST(TriangleCycleBound, StopsAtTheFirstTriangleAboveTheThreshold) {
  const SyntheticRotationGraph synthetic = NoisyPath(0, 0.0, 3);
  const TriangleCycleBound all = WholeGraphBound(synthetic.graph, kNoStop);
  const TriangleCycleBound stopped = WholeGraphBound(synthetic.graph, 0.0);
  EXPECT_EQ(stopped.triangles_checked, 1u);
  EXPECT_LT(stopped.triangles_checked, all.triangles_checked);
  EXPECT_LE(stopped.residual_lower_bound_deg, all.residual_lower_bound_deg);
}

}  // namespace
}  // namespace ramap
