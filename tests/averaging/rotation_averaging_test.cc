#include "ramap/averaging/rotation_averaging.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>

#include "ramap/graph/fiedler.h"
#include "ramap/graph/keyframes.h"
#include "ramap/synthetic/synthetic_rotation_graph.h"
#include "ramap/util/error.h"

namespace ramap {
namespace {

// A sequence of `num_nodes` cameras, each linked to its next `forward_neighbours`, with
// `num_loop_edges` random loops.
SyntheticRotationGraph Sequence(int num_nodes, int forward_neighbours, int num_loop_edges,
                                double noise_deg, double outlier_fraction, uint32_t seed) {
  SyntheticRotationGraphOptions options;
  options.num_nodes = num_nodes;
  options.forward_neighbours = forward_neighbours;
  options.num_loop_edges = num_loop_edges;
  options.noise_deg = noise_deg;
  options.outlier_fraction = outlier_fraction;
  options.seed = seed;
  return MakeSyntheticRotationGraph(options);
}

SyntheticRotationGraph PathWithLoops(double noise_deg, double outlier_fraction, uint32_t seed) {
  return Sequence(200, 8, 30, noise_deg, outlier_fraction, seed);
}

double TrueEdgeErrorDeg(const SyntheticRotationGraph& synthetic, size_t e) {
  const RelativeRotationEdge& edge = synthetic.graph.edges[e];
  return EdgeResidualDeg(edge, synthetic.true_rotations[edge.i], synthetic.true_rotations[edge.j]);
}

TEST(RotationAveraging, ExactRecoveryWithoutNoise) {
  const SyntheticRotationGraph synthetic = PathWithLoops(0.0, 0.0, 3);
  const RotationAveragingResult result = AverageRotations(synthetic.graph, {});
  ASSERT_EQ(result.rotations.size(), synthetic.true_rotations.size());
  for (bool estimated : result.estimated) EXPECT_TRUE(estimated);
  const std::vector<double> errors =
      AlignedRotationErrorsDeg(result.rotations, synthetic.true_rotations);
  double max_error = 0.0;
  for (double error : errors) max_error = std::max(max_error, error);
  EXPECT_LT(max_error * M_PI / 180.0, 1e-9);
  EXPECT_TRUE(result.pruned_edges.empty());
  EXPECT_TRUE(result.certificate.certified);
}

TEST(RotationAveraging, RejectsBadOptions) {
  RotationAveragingOptions options;
  options.sigma_deg = 0.0;
  EXPECT_THROW(options.Check(), InputError);
  EXPECT_THROW(AverageRotations(PathWithLoops(1.0, 0.0, 1).graph, options), InputError);
}

// Median error of the robust solver versus the chordal optimum of the graph with the outliers
// removed by an oracle (the noise-only optimum). The robust solver cannot beat that reference by
// much (it sees the same inliers), and should not lose much to it while the noise is well below
// the loss scale: Geman-McClure with sigma = 5 deg weights inliers at residuals of ~1-3 deg
// almost uniformly (weight > 0.5), and an outlier that survives pruning keeps a weight below
// (sigma^2 / (r^2 + sigma^2))^2 < 0.04 for r > 2 sigma. We allow a factor 1.25 for noise up to
// 2 deg. At 5 deg per-axis noise the inlier residual angles (~8 deg) exceed sigma, so the loss
// down-weights good edges unevenly and loses statistical efficiency: we allow a factor 1.75 there
// (measured 1.54-1.57). 0.05 deg absolute slack covers the medians' sampling noise.
struct NoiseCase {
  double noise_deg;
  double outlier_fraction;
};

// "noise_2deg_outliers_10pct": the case as ctest lists it.
std::string CaseName(const NoiseCase& noise) {
  std::ostringstream name;
  name << "noise_" << noise.noise_deg << "deg_outliers_"
       << std::lround(100 * noise.outlier_fraction) << "pct";
  std::string text = name.str();
  std::replace(text.begin(), text.end(), '.', 'p');
  return text;
}

void PrintTo(const NoiseCase& noise, std::ostream* out) { *out << CaseName(noise); }

class RotationAveragingNoise : public ::testing::TestWithParam<NoiseCase> {};

TEST_P(RotationAveragingNoise, CloseToInlierOnlyChordalOptimum) {
  const NoiseCase c = GetParam();
  const SyntheticRotationGraph synthetic =
      PathWithLoops(c.noise_deg, c.outlier_fraction, 7 + static_cast<uint32_t>(c.noise_deg * 10));
  const RotationAveragingResult result = AverageRotations(synthetic.graph, {});
  int estimated = 0;
  for (bool e : result.estimated) estimated += e;
  EXPECT_GE(estimated, 195);
  const double median = Median(
      AlignedRotationErrorsDeg(result.rotations, synthetic.true_rotations, result.estimated));

  RotationGraph inliers = synthetic.graph;
  inliers.edges.clear();
  for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
    if (!synthetic.is_outlier[e]) inliers.edges.push_back(synthetic.graph.edges[e]);
  }
  const ChordalAveragingResult reference = AverageRotationsChordal(inliers);
  const double reference_median = Median(
      AlignedRotationErrorsDeg(reference.rotations, synthetic.true_rotations, reference.estimated));
  const double factor = c.noise_deg <= 2.0 ? 1.25 : 1.75;
  EXPECT_LT(median, factor * reference_median + 0.05)
      << "noise " << c.noise_deg << " outliers " << c.outlier_fraction << ": ours " << median
      << " deg, inlier-only chordal " << reference_median << " deg";
  std::cout << "noise " << c.noise_deg << " outliers " << c.outlier_fraction << ": ours " << median
            << " deg, inlier-only chordal " << reference_median << " deg, ratio "
            << median / reference_median << "\n";
  EXPECT_GT(median, 0.5 * reference_median);

  // Every outlier whose measurement is off by more than alpha_max must have been pruned. The
  // residual seen by the solver is the true error plus the errors of the two node estimates,
  // which are of the order of the per-axis noise: outliers within 3 noise sigmas of alpha_max
  // may legitimately fall on either side.
  const RotationAveragingOptions defaults;
  const double margin_deg = 3.0 * c.noise_deg;
  int outliers_above = 0;
  for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
    if (!synthetic.is_outlier[e] ||
        TrueEdgeErrorDeg(synthetic, e) <= defaults.alpha_max_deg + margin_deg) {
      continue;
    }
    ++outliers_above;
    EXPECT_NE(result.edge_status[e], EdgeStatus::kKept)
        << "outlier edge " << e << " true error " << TrueEdgeErrorDeg(synthetic, e) << " residual "
        << result.edge_residuals_deg[e];
  }
  if (c.outlier_fraction > 0) EXPECT_GT(outliers_above, 0);
  // Pruned edges record their residual above the threshold.
  for (const PrunedEdge& pruned : result.pruned_edges) {
    if (pruned.reason == EdgeStatus::kPrunedResidual) {
      EXPECT_GT(pruned.residual_deg, pruned.threshold_deg);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    RotationAveraging, RotationAveragingNoise,
    ::testing::Values(NoiseCase{0.5, 0.0}, NoiseCase{0.5, 0.1}, NoiseCase{0.5, 0.3},
                      NoiseCase{2.0, 0.0}, NoiseCase{2.0, 0.1}, NoiseCase{2.0, 0.3},
                      NoiseCase{5.0, 0.0}, NoiseCase{5.0, 0.1}, NoiseCase{5.0, 0.3}),
    [](const ::testing::TestParamInfo<NoiseCase>& info) { return CaseName(info.param); });

// The bound grows with algebraic connectivity: a well connected graph (each camera linked to its
// 12 successors and 400 loop edges) at 0.2 deg noise is certified.
SyntheticRotationGraph CertifiableGraph() {
  SyntheticRotationGraphOptions options;
  options.num_nodes = 150;
  options.forward_neighbours = 12;
  options.num_loop_edges = 400;
  options.noise_deg = 0.2;
  options.seed = 11;
  return MakeSyntheticRotationGraph(options);
}

TEST(RotationAveraging, CertificateOnLowNoiseGraphMatchesChordalOptimum) {
  const SyntheticRotationGraph synthetic = CertifiableGraph();
  const RotationAveragingResult result = AverageRotations(synthetic.graph, {});
  const RotationCertificate& certificate = result.certificate;
  ASSERT_TRUE(certificate.computed);
  EXPECT_TRUE(certificate.certified)
      << "max residual " << certificate.max_residual_deg << " bound " << certificate.bound_deg;
  EXPECT_NEAR(certificate.fiedler_value, FiedlerValue(synthetic.graph), 1e-9);
  EXPECT_NEAR(
      certificate.bound_deg,
      StrongDualityResidualBound(certificate.fiedler_value, certificate.max_degree) * 180.0 / M_PI,
      1e-12);
  // A certified solution is the global chordal optimum: the plain chordal solver cannot do better.
  const ChordalAveragingResult chordal = AverageRotationsChordal(synthetic.graph);
  const double certified_cost = ChordalCost(synthetic.graph, certificate.rotations);
  const double chordal_cost = ChordalCost(synthetic.graph, chordal.rotations);
  EXPECT_NEAR(certified_cost, chordal_cost, 1e-9 * chordal_cost + 1e-12);
  // The robust solution is not the chordal stationary point, so its chordal cost is not lower.
  EXPECT_GE(ChordalCost(synthetic.graph, result.rotations), certified_cost * (1 - 1e-12));
}

TEST(RotationAveraging, HighNoiseIsNotCertified) {
  // A sparse path-like graph has a tiny Fiedler value, so its bound is far below 20 deg noise.
  const SyntheticRotationGraph synthetic = PathWithLoops(20.0, 0.0, 5);
  RotationAveragingOptions options;
  options.max_pruning_rounds = 0;
  const RotationAveragingResult result = AverageRotations(synthetic.graph, options);
  EXPECT_FALSE(result.certificate.certified);
  EXPECT_GT(result.certificate.max_residual_deg, result.certificate.bound_deg);
}

// The triangle check may only skip refinements that could not have certified: on a graph that is
// certified and on one that is not, the answer is the same with and without it, and only the
// uncertifiable one skips its refinement.
TEST(RotationAveraging, CycleCheckSkipsOnlyRefinementsThatCannotCertify) {
  for (const SyntheticRotationGraph& synthetic :
       {CertifiableGraph(), PathWithLoops(20.0, 0.0, 5)}) {
    RotationAveragingOptions options;
    options.max_pruning_rounds = 0;
    const RotationCertificate checked = AverageRotations(synthetic.graph, options).certificate;
    options.certificate_cycle_check = false;
    const RotationCertificate refined = AverageRotations(synthetic.graph, options).certificate;
    EXPECT_EQ(checked.certified, refined.certified);
    EXPECT_EQ(checked.refinement_skipped, !refined.certified);
    EXPECT_FALSE(refined.refinement_skipped);
    if (checked.refinement_skipped) {
      EXPECT_EQ(checked.iterations, 0);
      EXPECT_GT(checked.cycle_residual_lower_bound_deg, checked.bound_deg);
      // The bound holds for the chordal stationary point the refinement would have reached.
      EXPECT_GE(refined.max_residual_deg, checked.cycle_residual_lower_bound_deg);
    }
  }
}

TEST(RotationAveraging, StrongDualityPruningModeUsesTheBound) {
  const SyntheticRotationGraph synthetic = PathWithLoops(2.0, 0.1, 21);
  RotationAveragingOptions options;
  options.pruning_mode = PruningThresholdMode::kStrongDualityBound;
  const RotationAveragingResult result = AverageRotations(synthetic.graph, options);
  ASSERT_FALSE(result.pruned_edges.empty());
  EXPECT_LE(result.pruning_rounds, options.max_pruning_rounds);
  for (const PrunedEdge& pruned : result.pruned_edges) {
    if (pruned.reason != EdgeStatus::kPrunedResidual) continue;
    EXPECT_LT(pruned.threshold_deg, 45.0);
    EXPECT_GT(pruned.residual_deg, pruned.threshold_deg);
  }
}

TEST(RotationAveraging, WindowsThenGlobalMatchesGlobal) {
  const SyntheticRotationGraph synthetic = Sequence(150, 6, 30, 2.0, 0.1, 9);
  KeyframeOptions keyframe_options;
  keyframe_options.keyframe_interval = 30;
  const Keyframes keyframes = SelectKeyframes(synthetic.graph.node_ids, keyframe_options);
  const RotationAveragingResult windowed =
      AverageRotationsInWindows(synthetic.graph, keyframes, {});
  const RotationAveragingResult global = AverageRotations(synthetic.graph, {});
  EXPECT_GT(windowed.timings.windows, 0.0);
  const double windowed_median = Median(
      AlignedRotationErrorsDeg(windowed.rotations, synthetic.true_rotations, windowed.estimated));
  const double global_median = Median(
      AlignedRotationErrorsDeg(global.rotations, synthetic.true_rotations, global.estimated));
  EXPECT_NEAR(windowed_median, global_median, 0.1 * global_median);
}

// IRLS steps solved by conjugate gradients on an earlier factor reach the rotations that
// refactorising at every step reaches, with fewer factorisations. Many random loops make the
// factor costly (fill), as a long drive's loops do: only then are conjugate gradients tried.
TEST(RotationAveraging, ConjugateGradientStepsMatchRefactorising) {
  const SyntheticRotationGraph synthetic = Sequence(400, 8, 4000, 2.0, 0.1, 21);
  RotationAveragingOptions refactorise;
  refactorise.max_pcg_iterations = 0;
  refactorise.compute_certificate = false;
  RotationAveragingOptions pcg = refactorise;
  pcg.max_pcg_iterations = 40;
  const RotationAveragingResult direct = AverageRotations(synthetic.graph, refactorise);
  const RotationAveragingResult iterated = AverageRotations(synthetic.graph, pcg);
  ASSERT_EQ(direct.estimated, iterated.estimated);
  ASSERT_EQ(direct.edge_status, iterated.edge_status);
  double max_difference_deg = 0.0;
  for (size_t k = 0; k < direct.rotations.size(); ++k) {
    max_difference_deg =
        std::max(max_difference_deg,
                 direct.rotations[k].angularDistance(iterated.rotations[k]) * 180 / M_PI);
  }
  EXPECT_LT(max_difference_deg, 1e-4);
  EXPECT_LT(iterated.factorizations, direct.factorizations);
  EXPECT_GE(direct.factorizations, direct.l1_iterations + direct.irls_iterations);
  std::cout << "factorisations: " << direct.factorizations << " refactorising, "
            << iterated.factorizations << " with conjugate gradients; max difference "
            << max_difference_deg << " deg\n";
}

// Weak edges (a twentieth of the others' inlier counts) that are a few degrees off, under the
// robust loss's scale so that IRLS alone keeps them at full weight, as weak far-apart pairs come
// out on real drives: weighting by the counts keeps them from bending the sequence.
TEST(RotationAveraging, EdgeWeightsDiscountWeakEdges) {
  SyntheticRotationGraph synthetic = PathWithLoops(0.1, 0.0, 5);
  const Eigen::Quaterniond bias(Eigen::AngleAxisd(3.0 * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  int num_weak = 0;
  for (RelativeRotationEdge& edge : synthetic.graph.edges) {
    if (edge.j - edge.i < static_cast<uint32_t>(SyntheticRotationGraphOptions().loop_min_gap)) {
      continue;
    }
    edge.R_ij = bias * edge.R_ij;
    edge.weight /= 20.0;
    ++num_weak;
  }
  ASSERT_GE(num_weak, 25);
  RotationAveragingOptions unweighted;
  RotationAveragingOptions weighted;
  weighted.use_edge_weights = true;
  const RotationAveragingResult plain = AverageRotations(synthetic.graph, unweighted);
  const RotationAveragingResult by_weight = AverageRotations(synthetic.graph, weighted);
  const double plain_median =
      Median(AlignedRotationErrorsDeg(plain.rotations, synthetic.true_rotations, plain.estimated));
  const double weighted_median = Median(
      AlignedRotationErrorsDeg(by_weight.rotations, synthetic.true_rotations, by_weight.estimated));
  EXPECT_LT(weighted_median, 0.5 * plain_median)
      << "unweighted " << plain_median << " deg, weighted " << weighted_median << " deg";
}

// A drive without loops: every pair a little biased the same way (its geometry, shared along the
// road), short pairs with many more inliers than long ones. Weighted by inlier counts, the short
// pairs' bias integrates frame by frame; saturated weights let the long pairs hold it back
// (median error 1.15 -> 0.72 deg here).
TEST(RotationAveraging, SaturatedEdgeWeightsLimitTheDriftOfABiasedSequence) {
  SyntheticRotationGraph synthetic = Sequence(300, 10, 0, 0.15, 0.0, 11);
  const Eigen::Quaterniond bias(Eigen::AngleAxisd(0.05 * M_PI / 180.0, Eigen::Vector3d::UnitY()));
  for (RelativeRotationEdge& edge : synthetic.graph.edges) {
    const double gap = edge.j - edge.i;
    edge.R_ij = bias * edge.R_ij;
    edge.weight = 300.0 / (gap * gap);
  }
  RotationAveragingOptions linear;
  linear.use_edge_weights = true;
  linear.edge_weight_saturation = 0.0;
  RotationAveragingOptions saturated = linear;
  saturated.edge_weight_saturation = RotationAveragingOptions().edge_weight_saturation;
  ASSERT_GT(saturated.edge_weight_saturation, 0.0);
  const RotationAveragingResult by_count = AverageRotations(synthetic.graph, linear);
  const RotationAveragingResult by_saturated = AverageRotations(synthetic.graph, saturated);
  const double linear_median = Median(
      AlignedRotationErrorsDeg(by_count.rotations, synthetic.true_rotations, by_count.estimated));
  const double saturated_median = Median(AlignedRotationErrorsDeg(
      by_saturated.rotations, synthetic.true_rotations, by_saturated.estimated));
  EXPECT_LT(saturated_median, 0.8 * linear_median)
      << "inlier counts " << linear_median << " deg, saturated " << saturated_median << " deg";
}

TEST(RotationAveraging, DisconnectedNodesAreReported) {
  SyntheticRotationGraph synthetic = PathWithLoops(1.0, 0.0, 2);
  synthetic.graph.node_ids.push_back(1000);
  synthetic.graph.node_ids.push_back(1001);
  RelativeRotationEdge island;
  island.i = 1000;
  island.j = 1001;
  synthetic.graph.edges.push_back(island);
  const RotationAveragingResult result = AverageRotations(synthetic.graph, {});
  EXPECT_FALSE(result.estimated[200]);
  EXPECT_FALSE(result.estimated[201]);
  EXPECT_EQ(result.edge_status.back(), EdgeStatus::kPrunedDisconnected);
  EXPECT_TRUE(std::isnan(result.edge_residuals_deg.back()));
}

TEST(RotationAveraging, ChordalCostOfExactRotationsIsZero) {
  const SyntheticRotationGraph synthetic = PathWithLoops(0.0, 0.0, 4);
  EXPECT_NEAR(ChordalCost(synthetic.graph, synthetic.true_rotations), 0.0, 1e-20);
  // One edge off by angle a costs ||I - R||_F^2 = 8 sin^2(a / 2).
  SyntheticRotationGraph perturbed = synthetic;
  perturbed.graph.edges[0].R_ij =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY())) *
      perturbed.graph.edges[0].R_ij;
  EXPECT_NEAR(ChordalCost(perturbed.graph, synthetic.true_rotations),
              8.0 * std::pow(std::sin(0.15), 2), 1e-12);
  const ChordalAveragingResult exact = AverageRotationsChordal(synthetic.graph);
  const std::vector<double> errors =
      AlignedRotationErrorsDeg(exact.rotations, synthetic.true_rotations);
  for (double error : errors) EXPECT_LT(error, 1e-9);
}

}  // namespace
}  // namespace ramap

namespace ramap {
namespace {

// With a short L1 phase, one node of this graph is left ~155 deg off before pruning; all of its
// inlier edges then exceed alpha_max. Re-initialising such suspect nodes from their neighbours'
// consensus must recover it instead of stranding it on an outlier edge.
TEST(RotationAveraging, SuspectNodesAreReinitialisedNotStranded) {
  const SyntheticRotationGraph synthetic = PathWithLoops(0.5, 0.3, 12);
  RotationAveragingOptions options;
  options.max_l1_iterations = 5;
  options.l1_inner_iterations = 10;
  auto outliers_kept_above = [&](const RotationAveragingResult& result) {
    int count = 0;
    for (size_t e = 0; e < synthetic.graph.edges.size(); ++e) {
      count += synthetic.is_outlier[e] && result.edge_status[e] == EdgeStatus::kKept &&
               TrueEdgeErrorDeg(synthetic, e) > options.alpha_max_deg + 1.5;
    }
    return count;
  };
  const RotationAveragingResult result = AverageRotations(synthetic.graph, options);
  EXPECT_EQ(outliers_kept_above(result), 0);
  EXPECT_LT(Median(AlignedRotationErrorsDeg(result.rotations, synthetic.true_rotations,
                                            result.estimated)),
            0.5);
  options.reinitialize_suspect_nodes = false;
  const RotationAveragingResult plain = AverageRotations(synthetic.graph, options);
  std::cout << "re-initialised nodes: " << result.reinitialized_nodes.size()
            << "; outliers above alpha_max kept without re-initialisation: "
            << outliers_kept_above(plain) << "\n";
}

}  // namespace
}  // namespace ramap

namespace ramap {
namespace {

TEST(RotationAveraging, L1HalfLossAlsoRejectsOutliers) {
  const SyntheticRotationGraph synthetic = PathWithLoops(2.0, 0.1, 31);
  RotationAveragingOptions options;
  options.loss = RobustLoss::kL1Half;
  const RotationAveragingResult l_half = AverageRotations(synthetic.graph, options);
  const RotationAveragingResult geman_mcclure = AverageRotations(synthetic.graph, {});
  const double l_half_median = Median(
      AlignedRotationErrorsDeg(l_half.rotations, synthetic.true_rotations, l_half.estimated));
  const double gm_median = Median(AlignedRotationErrorsDeg(
      geman_mcclure.rotations, synthetic.true_rotations, geman_mcclure.estimated));
  // Both losses see the same inliers; l1/2 is less efficient on Gaussian noise than a redescending
  // loss but within a small factor, and far below the 2 deg per-axis noise of single edges.
  EXPECT_LT(l_half_median, 1.5 * gm_median);
  EXPECT_LT(l_half_median, 2.0);
}

}  // namespace
}  // namespace ramap
