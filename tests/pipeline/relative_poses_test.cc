// Stage 1 of the mapper: which verified pairs become image pairs of the view graph, how their
// matches are ranked, and the error a database without usable pairs gets.
#include "ramap/pipeline/relative_poses.h"

#include <gtest/gtest.h>

#include "ramap/geometry/correspondence_sampling.h"
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
    EXPECT_EQ(pair.correspondences.size(), geometry.inlier_matches.size());
    // Ranked by the Sampson error under the stored F: one confidence per match.
    EXPECT_EQ(pair.correspondences.confidence.size(), pair.correspondences.size());
    ASSERT_TRUE(pair.accepted()) << pair.estimate.reason;
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

TEST(RelativePoses, DescriptorRatiosRankTheMatchesWhenAskedFor) {
  SyntheticScene scene = SmallScene();
  TwoViewGeometry& geometry = scene.database.two_view_geometries.begin()->second;
  for (size_t k = 0; k < geometry.inlier_matches.size(); ++k)
    geometry.inlier_ratios.push_back(0.5f + 0.001f * k);
  const ImageBearings bearings = ComputeBearings(scene.database, "synthetic");
  RelativePoseOptions options;
  options.use_descriptor_ratios = true;
  const ImagePair with_ratios = EstimateRelativePoses(scene.database, bearings, options, 1)[0];
  ASSERT_EQ(with_ratios.correspondences.confidence.size(), geometry.inlier_ratios.size());
  EXPECT_FLOAT_EQ(with_ratios.correspondences.confidence[3], geometry.inlier_ratios[3]);
  options.use_descriptor_ratios = false;
  const ImagePair with_sampson = EstimateRelativePoses(scene.database, bearings, options, 1)[0];
  const TwoViewCorrespondences& c = with_sampson.correspondences;
  EXPECT_EQ(c.confidence, SampsonErrors(geometry.F, c.pixels1, c.pixels2));
}

}  // namespace
}  // namespace ramap
