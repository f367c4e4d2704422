// MakeSyntheticRotationGraph and AlignedRotationErrorsDeg: the graph's edges, weights, noise and
// outliers as the options say, and rotation errors measured after the best global gauge.
#include "ramap/synthetic/synthetic_rotation_graph.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace ramap {
namespace {

double AngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b) * 180.0 / M_PI;
}

SyntheticRotationGraphOptions Options(double noise_deg, double outlier_fraction) {
  SyntheticRotationGraphOptions options;
  options.num_nodes = 120;
  options.forward_neighbours = 4;
  options.num_loop_edges = 15;
  options.loop_min_gap = 30;
  options.noise_deg = noise_deg;
  options.outlier_fraction = outlier_fraction;
  options.seed = 7;
  return options;
}

TEST(SyntheticRotationGraph, SequenceEdgesAndLoopEdgesAsAsked) {
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(Options(1.0, 0.0));
  ASSERT_EQ(synthetic.graph.node_ids.size(), 120u);
  for (uint32_t k = 0; k < 120; ++k) EXPECT_EQ(synthetic.graph.node_ids[k], k);
  EXPECT_EQ(synthetic.true_rotations.size(), 120u);
  ASSERT_EQ(synthetic.is_outlier.size(), synthetic.graph.edges.size());
  std::set<std::pair<uint32_t, uint32_t>> edges;
  int num_loop_edges = 0;
  for (const RelativeRotationEdge& edge : synthetic.graph.edges) {
    ASSERT_LT(edge.i, edge.j);
    EXPECT_TRUE(edges.insert({edge.i, edge.j}).second) << "edge " << edge.i << " " << edge.j;
    const uint32_t gap = edge.j - edge.i;
    if (gap > 4) {
      EXPECT_GE(gap, 30u);
      ++num_loop_edges;
    }
    // Weights mimic inlier counts falling with the gap.
    EXPECT_DOUBLE_EQ(edge.weight, 1000.0 / (1.0 + gap));
  }
  // Each camera with its next four: 4 per node but the last four nodes' 3 + 2 + 1 + 0.
  EXPECT_EQ(static_cast<int>(edges.size()) - num_loop_edges, 116 * 4 + 3 + 2 + 1);
  EXPECT_EQ(num_loop_edges, 15);
}

TEST(SyntheticRotationGraph, WithoutNoiseEdgesAreTheTrueRelativeRotations) {
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(Options(0.0, 0.0));
  for (const RelativeRotationEdge& edge : synthetic.graph.edges) {
    const Eigen::Quaterniond exact =
        synthetic.true_rotations[edge.j] * synthetic.true_rotations[edge.i].conjugate();
    EXPECT_LT(AngleDeg(edge.R_ij, exact), 1e-9);  // rounding of two quaternion products
  }
}

TEST(SyntheticRotationGraph, StepsAndNoiseHaveTheirSizes) {
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(Options(2.0, 0.0));
  // Steps: rotation vectors of sigma step / sqrt(3) per axis, so an RMS angle of the step (5 deg);
  // over 119 steps the sample RMS has a relative spread of 1 / sqrt(2 * 3 * 119) = 3.7%: 15% is
  // four of them.
  double sum_squared = 0;
  for (size_t k = 1; k < synthetic.true_rotations.size(); ++k) {
    sum_squared +=
        std::pow(AngleDeg(synthetic.true_rotations[k], synthetic.true_rotations[k - 1]), 2);
  }
  EXPECT_NEAR(std::sqrt(sum_squared / 119), 5.0, 0.75);
  // Noise: 2 deg per axis of the rotation vector, an RMS angle of 2 sqrt(3) = 3.46 deg; over 485
  // edges the relative spread is 1.9%, and 10% is five of them.
  sum_squared = 0;
  for (const RelativeRotationEdge& edge : synthetic.graph.edges) {
    const Eigen::Quaterniond exact =
        synthetic.true_rotations[edge.j] * synthetic.true_rotations[edge.i].conjugate();
    sum_squared += std::pow(AngleDeg(edge.R_ij, exact), 2);
  }
  EXPECT_NEAR(std::sqrt(sum_squared / synthetic.graph.edges.size()), 2.0 * std::sqrt(3.0), 0.35);
}

TEST(SyntheticRotationGraph, OutliersAreRandomRotationsOfTheEdgesTheyReplace) {
  const SyntheticRotationGraph clean = MakeSyntheticRotationGraph(Options(1.0, 0.0));
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(Options(1.0, 0.3));
  ASSERT_EQ(synthetic.graph.edges.size(), clean.graph.edges.size());
  int num_outliers = 0;
  int num_far = 0;
  for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
    const RelativeRotationEdge& edge = synthetic.graph.edges[e];
    // The weight says nothing about an outlier: that of the edge it replaces.
    EXPECT_EQ(edge.weight, clean.graph.edges[e].weight);
    const double error = AngleDeg(
        edge.R_ij, synthetic.true_rotations[edge.j] * synthetic.true_rotations[edge.i].conjugate());
    if (synthetic.is_outlier[e]) {
      ++num_outliers;
      if (error > 20.0) ++num_far;
    } else {
      // Noise of 1 deg per axis: beyond 6 deg is a 1-in-10^6 draw.
      EXPECT_LT(error, 6.0);
    }
  }
  // ~500 edges at 0.3: the count's standard deviation is 10 edges, 2%; 5 sigmas either way.
  const double fraction = static_cast<double>(num_outliers) / synthetic.graph.edges.size();
  EXPECT_NEAR(fraction, 0.3, 0.1);
  // A uniformly random rotation is within 20 deg of a given one with probability 0.7%.
  EXPECT_GT(num_far, 0.95 * num_outliers);
}

TEST(SyntheticRotationGraph, SameSeedSameGraphAndBadOptionsRefused) {
  const SyntheticRotationGraph a = MakeSyntheticRotationGraph(Options(1.0, 0.1));
  const SyntheticRotationGraph b = MakeSyntheticRotationGraph(Options(1.0, 0.1));
  ASSERT_EQ(a.graph.edges.size(), b.graph.edges.size());
  for (size_t e = 0; e < a.graph.edges.size(); ++e) {
    EXPECT_EQ(a.graph.edges[e].R_ij.coeffs(), b.graph.edges[e].R_ij.coeffs());
  }
  SyntheticRotationGraphOptions one_node = Options(1.0, 0.0);
  one_node.num_nodes = 1;
  EXPECT_THROW(MakeSyntheticRotationGraph(one_node), std::invalid_argument);
  SyntheticRotationGraphOptions fraction = Options(1.0, 1.5);
  EXPECT_THROW(MakeSyntheticRotationGraph(fraction), std::invalid_argument);
}

TEST(SyntheticRotationGraph, AlignedErrorsIgnoreTheGlobalGaugeAndDiscountAnOutlyingNode) {
  const SyntheticRotationGraph synthetic = MakeSyntheticRotationGraph(Options(1.0, 0.0));
  const Eigen::Quaterniond gauge(Eigen::AngleAxisd(2.0, Eigen::Vector3d(1, 3, -2).normalized()));
  std::vector<Eigen::Quaterniond> estimated;
  for (const Eigen::Quaterniond& rotation : synthetic.true_rotations) {
    estimated.push_back(rotation * gauge);
  }
  for (const double error : AlignedRotationErrorsDeg(estimated, synthetic.true_rotations)) {
    EXPECT_LT(error, 1e-6);  // exact up to rounding
  }
  // Node 10 turned by 10 degrees: it alone carries the error, the others' gauge is found again
  // (the reweighting leaves its pull on the others' at a few thousandths of a degree).
  estimated[10] =
      Eigen::Quaterniond(Eigen::AngleAxisd(10.0 * M_PI / 180, Eigen::Vector3d::UnitZ())) *
      estimated[10];
  const std::vector<double> errors = AlignedRotationErrorsDeg(estimated, synthetic.true_rotations);
  ASSERT_EQ(errors.size(), 120u);
  EXPECT_NEAR(errors[10], 10.0, 0.01);
  for (size_t k = 0; k < errors.size(); ++k) {
    if (k != 10) EXPECT_LT(errors[k], 0.01) << "node " << k;
  }
  // Nodes not estimated are left out (here the outlying one).
  std::vector<bool> mask(120, true);
  mask[10] = false;
  const std::vector<double> masked =
      AlignedRotationErrorsDeg(estimated, synthetic.true_rotations, mask);
  ASSERT_EQ(masked.size(), 119u);
  for (const double error : masked) EXPECT_LT(error, 1e-6);
}

}  // namespace
}  // namespace ramap
