// Verification and matching of image pairs on synthetic scenes with known truth: the verified
// inliers hold every true match and the pair's true pose, unknown focal lengths give F instead of
// E, too few inliers give a degenerate pair, descriptor ratios follow their inliers, and matching
// replaces the given pairs only; preemptive screening keeps the pairs that share features.
#include "ramap/features/feature_matching.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// A noise-free 12-frame line with 20% wrong matches, its camera's focal length known.
SyntheticScene Line(bool focal_known = true) {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kLine, 12);
  options.num_points = 800;
  options.outlier_ratio = 0.2;
  options.camera.has_prior_focal_length = focal_known;
  return BuildSyntheticScene(options);
}

std::set<std::pair<uint32_t, uint32_t>> AsSet(const std::vector<FeatureMatch>& matches) {
  std::set<std::pair<uint32_t, uint32_t>> set;
  for (const FeatureMatch& match : matches) set.insert({match.point2D_idx1, match.point2D_idx2});
  return set;
}

// cam2_from_cam1 of images id1 and id2 in the truth.
Rigid3d TruePose(const SyntheticScene& scene, uint32_t id1, uint32_t id2) {
  return scene.ground_truth.images.at(id2).cam_from_world *
         scene.ground_truth.images.at(id1).cam_from_world.Inverse();
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

// Distance (px) of a match's second keypoint from the epipolar line F gives its first.
double EpipolarDistancePx(const SyntheticScene& scene, const TwoViewGeometry& geometry,
                          uint32_t id1, uint32_t id2, const FeatureMatch& match) {
  const Eigen::Vector2d x1 = scene.database.keypoints.at(id1).xy(match.point2D_idx1);
  const Eigen::Vector2d x2 = scene.database.keypoints.at(id2).xy(match.point2D_idx2);
  const Eigen::Vector3d line = geometry.F * x1.homogeneous();
  return std::abs(x2.homogeneous().dot(line)) / line.head<2>().norm();
}

TwoViewGeometry Verify(const SyntheticScene& scene, uint32_t id1, uint32_t id2,
                       const std::vector<FeatureMatch>& matches,
                       const FeatureMatchingOptions& options = FeatureMatchingOptions(),
                       const std::vector<float>& ratios = {}) {
  const FeatureDatabase& database = scene.database;
  return VerifyMatches(id1, id2, database.cameras.at(1), database.cameras.at(1),
                       database.keypoints.at(id1), database.keypoints.at(id2), matches, options,
                       ratios);
}

TEST(FeatureMatching, VerifiedInliersHoldEveryTrueMatchAndThePairsPose) {
  const SyntheticScene scene = Line();
  const uint64_t pair_id = ImagePairToPairId(3, 4);
  const std::vector<FeatureMatch>& raw = scene.database.matches.at(pair_id);
  const std::set<std::pair<uint32_t, uint32_t>> truth =
      AsSet(scene.database.two_view_geometries.at(pair_id).inlier_matches);
  ASSERT_LT(truth.size(), raw.size());  // there are wrong matches to reject

  const TwoViewGeometry geometry = Verify(scene, 3, 4, raw);
  EXPECT_EQ(geometry.image_id1, 3u);
  EXPECT_EQ(geometry.image_id2, 4u);
  EXPECT_EQ(geometry.config, TwoViewConfig::kCalibrated);
  const std::set<std::pair<uint32_t, uint32_t>> inliers = AsSet(geometry.inlier_matches);
  for (const auto& match : truth) EXPECT_TRUE(inliers.count(match)) << "true match lost";
  // A wrong match passes when it happens to lie within 4 px of its epipolar line: a few percent
  // of them, never most.
  EXPECT_LT(inliers.size() - truth.size(), 0.1 * (raw.size() - truth.size()) + 1);

  // The pose: the few wrong matches within 4 px of their epipolar line pull it a little.
  const Rigid3d truth_pose = TruePose(scene, 3, 4);
  EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(truth_pose.rotation) * 180 / M_PI,
            0.1);
  EXPECT_NEAR(geometry.cam2_from_cam1.translation.norm(), 1.0, 1e-9);
  EXPECT_LT(AngleDeg(geometry.cam2_from_cam1.translation, truth_pose.translation), 0.5);
  // F = K2^-T E K1^-1, with E OpenCV's USAC estimate: it holds every true match within a pixel of
  // its epipolar line (the inlier bound is 4 px).
  for (const FeatureMatch& match : scene.database.two_view_geometries.at(pair_id).inlier_matches) {
    EXPECT_LT(EpipolarDistancePx(scene, geometry, 3, 4, match), 1.0);
  }
}

TEST(FeatureMatching, TrueMatchesAloneGiveTheTruePose) {
  const SyntheticScene scene = Line();
  const TwoViewGeometry& truth = scene.database.two_view_geometries.at(ImagePairToPairId(3, 4));
  const TwoViewGeometry geometry = Verify(scene, 3, 4, truth.inlier_matches);
  EXPECT_EQ(geometry.inlier_matches.size(), truth.inlier_matches.size());
  // ramap's estimator on exact matches (float32 keypoints, ~1e-5 px): the mapper's exact-recovery
  // bound for rotations, and a hundredth of a degree for the direction of a forward motion.
  const Rigid3d truth_pose = TruePose(scene, 3, 4);
  EXPECT_LT(geometry.cam2_from_cam1.rotation.angularDistance(truth_pose.rotation) * 180 / M_PI,
            1e-3);
  EXPECT_LT(AngleDeg(geometry.cam2_from_cam1.translation, truth_pose.translation), 1e-2);
}

TEST(FeatureMatching, UnknownFocalLengthsGiveAFundamentalMatrixOnly) {
  const SyntheticScene scene = Line(/*focal_known=*/false);
  const uint64_t pair_id = ImagePairToPairId(3, 4);
  const TwoViewGeometry geometry = Verify(scene, 3, 4, scene.database.matches.at(pair_id));
  EXPECT_EQ(geometry.config, TwoViewConfig::kUncalibrated);
  EXPECT_EQ(geometry.E, Eigen::Matrix3d::Zero());
  EXPECT_GE(geometry.inlier_matches.size(),
            scene.database.two_view_geometries.at(pair_id).inlier_matches.size());
  for (const FeatureMatch& match : scene.database.two_view_geometries.at(pair_id).inlier_matches) {
    // F estimated on the pixels by OpenCV's USAC within its 4 px bound: within a pixel.
    EXPECT_LT(EpipolarDistancePx(scene, geometry, 3, 4, match), 1.0);
  }
}

TEST(FeatureMatching, TooFewInliersGiveADegeneratePairWithoutInliers) {
  const SyntheticScene scene = Line();
  std::vector<FeatureMatch> few =
      scene.database.two_view_geometries.at(ImagePairToPairId(3, 4)).inlier_matches;
  few.resize(14);
  FeatureMatchingOptions options;
  options.min_num_inliers = 15;
  const TwoViewGeometry geometry = Verify(scene, 3, 4, few, options);
  EXPECT_EQ(geometry.config, TwoViewConfig::kDegenerate);
  EXPECT_TRUE(geometry.inlier_matches.empty());
  few.push_back(scene.database.two_view_geometries.at(ImagePairToPairId(3, 4)).inlier_matches[14]);
  EXPECT_EQ(Verify(scene, 3, 4, few, options).config, TwoViewConfig::kCalibrated);
}

TEST(FeatureMatching, DescriptorRatiosFollowTheirInliers) {
  const SyntheticScene scene = Line();
  const std::vector<FeatureMatch>& raw = scene.database.matches.at(ImagePairToPairId(3, 4));
  std::vector<float> ratios;
  std::map<std::pair<uint32_t, uint32_t>, float> ratio_of;
  for (size_t k = 0; k < raw.size(); ++k) {
    ratios.push_back(0.001f * static_cast<float>(k + 1));  // one of its own for each match
    ratio_of[{raw[k].point2D_idx1, raw[k].point2D_idx2}] = ratios.back();
  }
  const TwoViewGeometry geometry = Verify(scene, 3, 4, raw, FeatureMatchingOptions(), ratios);
  ASSERT_EQ(geometry.inlier_ratios.size(), geometry.inlier_matches.size());
  for (size_t k = 0; k < geometry.inlier_matches.size(); ++k) {
    const FeatureMatch& match = geometry.inlier_matches[k];
    EXPECT_EQ(geometry.inlier_ratios[k], (ratio_of[{match.point2D_idx1, match.point2D_idx2}]));
  }
  // Without ratios, none are kept.
  EXPECT_TRUE(Verify(scene, 3, 4, raw).inlier_ratios.empty());
}

// A 12-view orbit with SIFT-like descriptors and no matches yet, as a database fresh from
// extraction. Views 30 degrees apart share many points; views 150 degrees or more apart share none
// (each point is seen from within 72.5 degrees of its normal only).
SyntheticScene Unmatched() {
  SyntheticSceneOptions options =
      test::NoiseFree(SyntheticLayout::kSequential, SyntheticPath::kCircle, 12);
  options.num_points = 800;
  options.camera.has_prior_focal_length = true;
  SyntheticScene scene = BuildSyntheticScene(options);
  AddSyntheticDescriptors(SyntheticDescriptorOptions(), &scene);
  scene.database.matches.clear();
  scene.database.two_view_geometries.clear();
  return scene;
}

// The share of a pair's verified matches that observe the same 3D point.
double TrueShare(const SyntheticScene& scene, const TwoViewGeometry& geometry) {
  const Image& image1 = scene.ground_truth.images.at(geometry.image_id1);
  const Image& image2 = scene.ground_truth.images.at(geometry.image_id2);
  int num_true = 0;
  for (const FeatureMatch& match : geometry.inlier_matches) {
    const uint64_t point = image1.points2D[match.point2D_idx1].point3D_id;
    num_true +=
        point != kInvalidPoint3DId && point == image2.points2D[match.point2D_idx2].point3D_id;
  }
  return static_cast<double>(num_true) / geometry.inlier_matches.size();
}

TEST(FeatureMatching, MatchingReplacesTheGivenPairsOnly) {
  SyntheticScene scene = Unmatched();
  // An earlier result for pair (7, 8), which must stay, and a stale one for (1, 2), replaced.
  TwoViewGeometry kept;
  kept.image_id1 = 7;
  kept.image_id2 = 8;
  kept.config = TwoViewConfig::kCalibrated;
  kept.inlier_matches = {{1, 1}};
  scene.database.two_view_geometries[ImagePairToPairId(7, 8)] = kept;
  scene.database.two_view_geometries[ImagePairToPairId(1, 2)] = kept;
  FeatureMatchingOptions options;
  options.num_threads = 2;
  const MatchingSummary summary =
      MatchImagePairs(&scene.database, {{1, 2}, {2, 3}, {1, 7}}, options);
  EXPECT_EQ(summary.num_pairs, 3);
  EXPECT_EQ(summary.num_verified_pairs, 2);  // (1, 7) share no point
  ASSERT_EQ(scene.database.two_view_geometries.size(), 3u);
  EXPECT_EQ(scene.database.two_view_geometries.at(ImagePairToPairId(7, 8)).inlier_matches.size(),
            1u);
  for (const auto& [id1, id2] : {std::pair<uint32_t, uint32_t>{1, 2}, {2, 3}}) {
    const TwoViewGeometry& geometry =
        scene.database.two_view_geometries.at(ImagePairToPairId(id1, id2));
    EXPECT_GT(geometry.inlier_matches.size(), 50u);
    EXPECT_EQ(geometry.inlier_ratios.size(), geometry.inlier_matches.size());
    // The descriptors' noise lets the odd wrong match through the ratio test and the epipolar
    // bound; 95% must be true.
    EXPECT_GT(TrueShare(scene, geometry), 0.95) << id1 << " " << id2;
    EXPECT_TRUE(scene.database.matches.count(ImagePairToPairId(id1, id2)));
  }
  EXPECT_FALSE(scene.database.two_view_geometries.count(ImagePairToPairId(1, 7)));
}

TEST(FeatureMatching, MatchingNamesImagesItCannotMatch) {
  SyntheticScene scene = Unmatched();
  scene.database.source_path = "project.db";
  test::ExpectInputError(
      [&] {
        MatchImagePairs(&scene.database, {{1, 99}}, FeatureMatchingOptions());
      },
      {"project.db", "no image 99 to match"});
  scene.database.descriptors.erase(2);
  test::ExpectInputError(
      [&] {
        MatchImagePairs(&scene.database, {{1, 2}}, FeatureMatchingOptions());
      },
      {"project.db", scene.database.images.at(2).name, "run feature_extractor"});
}

TEST(FeatureMatching, ScreeningKeepsThePairsThatShareFeatures) {
  const SyntheticScene scene = Unmatched();
  const std::vector<std::pair<uint32_t, uint32_t>> pairs = {{1, 2}, {1, 7}, {5, 6}, {2, 8}};
  EXPECT_EQ(ScreenPairsPreemptively(scene.database, pairs, FeatureMatchingOptions()),
            (std::vector<std::pair<uint32_t, uint32_t>>{{1, 2}, {5, 6}}));
}

// Bug: FeatureMatchingOptions says preemptive_num_features 0 matches every pair in full, but
// ScreenPairsPreemptively then compares empty feature sets and drops every pair. matching_plan.cc
// skips the screening at 0; jobs/loop_closure.cc does not, so with
// --Matching.preemptive_num_features 0 loop closure screens out every bridge pair between models.
TEST(FeatureMatching, DISABLED_ZeroPreemptiveFeaturesScreenNoPairOut) {
  const SyntheticScene scene = Unmatched();
  FeatureMatchingOptions options;
  options.preemptive_num_features = 0;
  const std::vector<std::pair<uint32_t, uint32_t>> pairs = {{1, 2}, {1, 7}};
  EXPECT_EQ(ScreenPairsPreemptively(scene.database, pairs, options), pairs);
}

TEST(FeatureMatching, ModeNames) {
  for (const MatchingMode mode : {MatchingMode::kAuto, MatchingMode::kSequential,
                                  MatchingMode::kExhaustive, MatchingMode::kRetrieval}) {
    EXPECT_EQ(MatchingModeFromName(MatchingModeName(mode)), mode);
  }
  EXPECT_EQ(MatchingModeName(MatchingMode::kRetrieval), "retrieval");
  test::ExpectInputError([] { MatchingModeFromName("vocab_tree"); },
                         {"--Matching.mode", "'vocab_tree'"});
}

}  // namespace
}  // namespace ramap
