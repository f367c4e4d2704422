// Stage 1 of the mapper: which verified pairs become image pairs of the view graph, what they keep
// of their matches, and the error a database without usable pairs gets. (How matches are ranked:
// tests/geometry/pair_correspondences_test.cc.)
#include "ramap/estimators/relative_poses.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "ramap/geometry/rotation.h"
#include "ramap/synthetic/synthetic_scene.h"

namespace ramap {
namespace {

SyntheticScene SmallScene() {
  SyntheticSceneOptions options;
  options.num_images = 8;
  options.num_points = 600;
  options.overlap = 3;
  return BuildSyntheticScene(options);
}

double RotationErrorDeg(const SyntheticScene& scene, const ImagePair& pair) {
  const Eigen::Quaterniond R1 =
      scene.ground_truth.images.at(pair.image_id1).cam_from_world.rotation;
  const Eigen::Quaterniond R2 =
      scene.ground_truth.images.at(pair.image_id2).cam_from_world.rotation;
  return RotationAngleDeg(pair.estimate.rotation, R2 * R1.inverse());
}

TEST(RelativePoses, EveryUsablePairIsEstimatedClose) {
  const SyntheticScene scene = SmallScene();
  const ImageBearings bearings = ComputeBearings(scene.database, "synthetic");
  const std::vector<ImagePair> pairs =
      EstimateRelativePoses(scene.database, bearings, RelativePoseOptions(), 2);
  ASSERT_EQ(pairs.size(), scene.database.two_view_geometries.size());
  for (const ImagePair& pair : pairs) {
    const TwoViewGeometry& geometry =
        scene.database.two_view_geometries.at(ImagePairToPairId(pair.image_id1, pair.image_id2));
    EXPECT_EQ(pair.num_verified_matches, static_cast<int>(geometry.inlier_matches.size()));
    ASSERT_TRUE(pair.accepted()) << pair.estimate.reason;
    // The inliers are kept as a mask over the pair's verified matches.
    ASSERT_EQ(pair.is_inlier.size(), geometry.inlier_matches.size());
    const std::vector<FeatureMatch> inlier_matches = InlierMatches(pair, geometry);
    ASSERT_EQ(inlier_matches.size(), static_cast<size_t>(pair.estimate.num_inliers));
    for (const FeatureMatch& match : inlier_matches) {
      EXPECT_NE(std::find_if(geometry.inlier_matches.begin(), geometry.inlier_matches.end(),
                             [&](const FeatureMatch& m) {
                               return m.point2D_idx1 == match.point2D_idx1 &&
                                      m.point2D_idx2 == match.point2D_idx2;
                             }),
                geometry.inlier_matches.end());
    }
    // 0.5 px noise on a VGA camera with overlapping views: well under a tenth of a degree.
    EXPECT_LT(RotationErrorDeg(scene, pair), 0.1);
  }
  const std::vector<RelativePoseRecord> records = AcceptedRelativePoses(scene.database, pairs);
  ASSERT_EQ(records.size(), pairs.size());
  EXPECT_EQ(records[0].image_name1, scene.database.images.at(pairs[0].image_id1).name);
}

TEST(RelativePoses, UnusableAndThinPairsAreLeftOutAndExplained) {
  SyntheticScene scene = SmallScene();
  auto geometry = scene.database.two_view_geometries.begin();
  geometry->second.config = TwoViewConfig::kPanoramic;
  (++geometry)->second.config = TwoViewConfig::kWatermark;
  (++geometry)->second.inlier_matches.resize(10);
  const size_t total = scene.database.two_view_geometries.size();
  const ImageBearings bearings = ComputeBearings(scene.database, "synthetic");
  RelativePoseOptions options;
  options.min_num_inliers = 15;
  EXPECT_EQ(EstimateRelativePoses(scene.database, bearings, options, 1).size(), total - 3);

  // With every pair so, the error names each kind and its count.
  for (auto& [pair_id, g] : scene.database.two_view_geometries)
    g.config = TwoViewConfig::kPanoramic;
  scene.database.two_view_geometries.begin()->second.config = TwoViewConfig::kDegenerate;
  const std::string why = WhyNoVerifiedPairs(scene.database, 15);
  EXPECT_NE(why.find(std::to_string(total - 1) + " PANORAMIC"), std::string::npos) << why;
  EXPECT_NE(why.find("1 degenerate"), std::string::npos) << why;
  scene.database.two_view_geometries.clear();
  EXPECT_NE(WhyNoVerifiedPairs(scene.database, 15).find("run a matcher first"), std::string::npos);
}

}  // namespace
}  // namespace ramap
