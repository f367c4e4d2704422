// The view graph's pairs: the matches an estimate explains, the weight of a relative rotation, the
// accepted pairs as a graph, and a reason's name for each kind of rejection.
#include "ramap/scene/view_graph.h"

#include <gtest/gtest.h>

#include <set>

namespace ramap {
namespace {

ImagePair Pair(uint32_t id1, uint32_t id2, bool accepted, int num_inliers) {
  ImagePair pair;
  pair.image_id1 = id1;
  pair.image_id2 = id2;
  pair.estimate.success = accepted;
  pair.estimate.num_inliers = num_inliers;
  pair.estimate.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.1 * id1, Eigen::Vector3d::UnitY()));
  return pair;
}

TEST(ViewGraphPairs, InlierMatchesAreTheVerifiedMatchesTheEstimateExplainsInOrder) {
  TwoViewGeometry geometry;
  geometry.inlier_matches = {{0, 10}, {1, 11}, {2, 12}, {3, 13}};
  ImagePair pair = Pair(1, 2, true, 2);
  pair.is_inlier = {true, false, false, true};
  const std::vector<FeatureMatch> matches = InlierMatches(pair, geometry);
  ASSERT_EQ(matches.size(), 2u);
  EXPECT_EQ(matches[0].point2D_idx2, 10u);
  EXPECT_EQ(matches[1].point2D_idx2, 13u);
  // Bits beyond the geometry's matches (a stale pair) name nothing.
  pair.is_inlier = {false, false, false, false, true, true};
  EXPECT_TRUE(InlierMatches(pair, geometry).empty());
}

TEST(ViewGraphPairs, RotationWeightIsTheInlierCountAtLeastOne) {
  EXPECT_EQ(RelativeRotationWeight(250), 250.0);
  EXPECT_EQ(RelativeRotationWeight(1), 1.0);
  EXPECT_EQ(RelativeRotationWeight(0), 1.0);  // a record read from a file that gives none
}

TEST(ViewGraphPairs, AcceptedPairsBecomeEdgesNamingTheirPair) {
  const std::vector<ImagePair> pairs = {Pair(5, 9, true, 40), Pair(1, 5, false, 0),
                                        Pair(2, 5, true, 0), Pair(7, 8, false, 12)};
  const RotationGraph graph = AcceptedRotationGraph(pairs);
  EXPECT_EQ(graph.node_ids, (std::vector<uint32_t>{2, 5, 9}));  // images of accepted pairs only
  ASSERT_EQ(graph.edges.size(), 2u);
  EXPECT_EQ(graph.edges[0].i, 5u);
  EXPECT_EQ(graph.edges[0].j, 9u);
  EXPECT_EQ(graph.edges[0].pair_index, 0u);
  EXPECT_EQ(graph.edges[0].weight, 40.0);
  EXPECT_EQ(graph.edges[0].R_ij.coeffs(), pairs[0].estimate.rotation.coeffs());
  EXPECT_EQ(graph.edges[1].pair_index, 2u);
  EXPECT_EQ(graph.edges[1].weight, 1.0);
  EXPECT_TRUE(AcceptedRotationGraph({}).edges.empty());
}

TEST(ViewGraphPairs, EveryRejectionHasANameOfItsOwn) {
  std::set<std::string> names;
  for (int kind = static_cast<int>(RelativePoseRejection::kNone);
       kind <= static_cast<int>(RelativePoseRejection::kNonFiniteEstimate); ++kind) {
    const std::string name = RelativePoseRejectionName(static_cast<RelativePoseRejection>(kind));
    EXPECT_NE(name, "unknown") << kind;
    EXPECT_TRUE(names.insert(name).second) << "two kinds named '" << name << "'";
  }
  EXPECT_EQ(RelativePoseRejectionName(RelativePoseRejection::kNone), "accepted");
  EXPECT_STREQ(RelativePoseRejectionName(RelativePoseRejection::kTooFewMatches), "too few matches");
}

}  // namespace
}  // namespace ramap
