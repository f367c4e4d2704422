// Matching plans and the matcher: the GEMM matcher against the plain distance loop, the video plan
// on frame names only, and image retrieval finding a loop of a synthetic drive from descriptors.
#include "ramap/features/matching_plan.h"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <random>
#include <set>

#include "ramap/features/descriptor_matching.h"
#include "ramap/synthetic/synthetic_descriptors.h"
#include "ramap/synthetic/synthetic_scene.h"

namespace ramap {
namespace {

// A synthetic scene with SIFT-like descriptors on every keypoint.
SyntheticScene SceneWithDescriptors(SyntheticSceneOptions options) {
  SyntheticScene scene = BuildSyntheticScene(options);
  SyntheticDescriptorOptions descriptors;
  descriptors.seed = options.seed;
  AddSyntheticDescriptors(descriptors, &scene);
  return scene;
}

SyntheticSceneOptions Drive(int num_images, uint64_t seed) {
  SyntheticSceneOptions options;
  options.num_images = num_images;
  options.num_points = 40 * num_images;
  options.loop_max_distance = 0.0;
  options.seed = seed;
  return options;
}

// Points the two images of every pair see in common, from the ground truth's tracks.
std::map<std::pair<uint32_t, uint32_t>, int> SharedPoints(const Reconstruction& truth) {
  std::map<std::pair<uint32_t, uint32_t>, int> shared;
  for (const auto& [id, point] : truth.points3D) {
    std::set<uint32_t> images;
    for (const TrackElement& element : point.track) images.insert(element.image_id);
    for (auto a = images.begin(); a != images.end(); ++a) {
      for (auto b = std::next(a); b != images.end(); ++b) ++shared[{*a, *b}];
    }
  }
  return shared;
}

TEST(DescriptorMatching, MatrixProductEqualsTheDistanceLoop) {
  SyntheticSceneOptions options = Drive(2, 3);
  options.num_points = 1500;
  options.overlap = 1;
  const SyntheticScene scene = SceneWithDescriptors(options);
  const Descriptors& one = scene.database.descriptors.at(1);
  const Descriptors& two = scene.database.descriptors.at(2);
  ASSERT_GT(one.size(), 512u);  // more than one block of rows
  for (const bool cross_check : {true, false}) {
    DescriptorMatchingOptions matching;
    matching.cross_check = cross_check;
    std::vector<float> fast_ratios, loop_ratios;
    const std::vector<FeatureMatch> fast = MatchDescriptors(one, two, matching, &fast_ratios);
    const std::vector<FeatureMatch> loop = MatchDescriptorsByLoop(one, two, matching, &loop_ratios);
    ASSERT_GT(loop.size(), 200u);
    ASSERT_EQ(fast.size(), loop.size());
    for (size_t k = 0; k < loop.size(); ++k) {
      EXPECT_EQ(fast[k].point2D_idx1, loop[k].point2D_idx1);
      EXPECT_EQ(fast[k].point2D_idx2, loop[k].point2D_idx2);
      EXPECT_NEAR(fast_ratios[k], loop_ratios[k], 1e-6);
    }
  }
}

// Preemptive matching's features are the largest in scale however the keypoints store it: a
// scale column, or an affine shape whose a11 is negative when the feature points left.
TEST(DescriptorMatching, PreemptiveFeaturesAreTheLargestWhateverTheKeypointColumns) {
  Descriptors descriptors;
  descriptors.num_cols = 128;
  for (int k = 0; k < 4; ++k) descriptors.data.insert(descriptors.data.end(), 128, k);
  const std::vector<float> scales = {2, 9, 1, 5};  // rows 1 and 3 are the largest
  Keypoints with_scale, affine, plain;
  with_scale.num_cols = 4, affine.num_cols = 6, plain.num_cols = 2;
  for (const float scale : scales) {
    with_scale.data.insert(with_scale.data.end(), {0, 0, scale, 0.3f});
    affine.data.insert(affine.data.end(), {0, 0, -scale, 0, 0, -scale});  // turned by 180 deg
    plain.data.insert(plain.data.end(), {0, 0});
  }
  for (const Keypoints* keypoints : {&with_scale, &affine}) {
    const Descriptors top = LargestScaleDescriptors(*keypoints, descriptors, 2);
    ASSERT_EQ(top.size(), 2u);
    EXPECT_EQ(top.data[0], 1);
    EXPECT_EQ(top.data[128], 3);
  }
  EXPECT_EQ(LargestScaleDescriptors(plain, descriptors, 2).size(), 2u);  // an even subset
}

TEST(MatchingPlan, FrameNumberedVideoTakesTheSequentialPlan) {
  const SyntheticScene scene = SceneWithDescriptors(Drive(80, 1));
  FeatureMatchingOptions options;
  const MatchingPlan plan = PlanMatching(options, scene.database);
  EXPECT_EQ(plan.mode, MatchingMode::kSequential) << plan.reason;
  // Frame k with frames k+1 .. k+overlap.
  EXPECT_EQ(plan.unscreened_pairs.size(), 80u * 10 - 55);
  for (const auto& [a, b] : plan.unscreened_pairs) EXPECT_LE(b - a, 10u);
  ASSERT_FALSE(plan.pairs_to_screen.empty());
  for (const auto& [a, b] : plan.pairs_to_screen) {
    EXPECT_GT(b - a, static_cast<uint32_t>(options.loop_min_frame_gap));
  }
  // Up to the exhaustive limit, every pair.
  const SyntheticScene short_clip =
      SceneWithDescriptors(Drive(options.auto_exhaustive_max_images, 1));
  const MatchingPlan exhaustive = PlanMatching(options, short_clip.database);
  EXPECT_EQ(exhaustive.mode, MatchingMode::kExhaustive);
  EXPECT_EQ(exhaustive.pairs_to_screen.size(), 50u * 49 / 2);
}

TEST(MatchingPlan, NamesThatAreNotFrameNumbersNeverTakeTheVideoPlan) {
  SyntheticScene scene = SceneWithDescriptors(Drive(80, 2));
  const std::vector<std::function<std::string(uint32_t)>> namings = {
      [](uint32_t id) {
        return "view_" + std::string(1, 'a' + id % 26) + std::to_string(id / 26) + "x.jpg";
      },
      [](uint32_t id) {
        return std::string(id % 2 ? "left_" : "right_") + std::to_string(id) + ".png";
      },
      [](uint32_t id) {
        return std::to_string(id * 7919 % 1000) + "f" + std::to_string(id) + ".jpg";
      },
      [](uint32_t id) { return "DSC_" + std::to_string(id) + (id % 3 ? ".jpg" : "_edit.jpg"); },
  };
  FeatureMatchingOptions options;
  options.retrieval.max_features_per_image = 200;  // the choice is tested, not the retrieval
  for (const auto& naming : namings) {
    for (auto& [id, image] : scene.database.images) image.name = naming(id);
    const MatchingPlan plan = PlanMatching(options, scene.database);
    EXPECT_EQ(plan.mode, MatchingMode::kRetrieval) << naming(1) << ": " << plan.reason;
    EXPECT_TRUE(plan.pairs_to_screen.empty());  // no loop candidates, no exhaustive pairs
    EXPECT_FALSE(plan.unscreened_pairs.empty());
  }
  // Asked for, the video plan is still there.
  FeatureMatchingOptions sequential = options;
  sequential.mode = MatchingMode::kSequential;
  EXPECT_EQ(PlanMatching(sequential, scene.database).mode, MatchingMode::kSequential);
}

// A closed drive: the last frames see what the first ones saw. Retrieval, from descriptors alone,
// must propose the revisit as a loop candidate for nearly every frame that has one.
TEST(ImageRetrieval, FindsAKnownLoopInASyntheticSequence) {
  for (const uint64_t seed : {1, 2, 3}) {
    SyntheticSceneOptions options = Drive(100, seed);
    options.path = SyntheticPath::kLoop;
    const SyntheticScene scene = SceneWithDescriptors(options);
    FeatureMatchingOptions matching;
    matching.mode = MatchingMode::kSequential;
    const MatchingPlan plan = PlanMatching(matching, scene.database);
    const auto shared = SharedPoints(scene.ground_truth);
    std::set<uint32_t> with_loop, loop_found;
    for (const auto& [pair, count] : shared) {
      if (pair.second - pair.first > static_cast<uint32_t>(matching.loop_min_frame_gap) &&
          count >= 30) {
        with_loop.insert({pair.first, pair.second});
      }
    }
    for (const auto& pair : plan.pairs_to_screen) {
      const auto found = shared.find(pair);
      if (found != shared.end() && found->second >= 15)
        loop_found.insert({pair.first, pair.second});
    }
    ASSERT_GE(with_loop.size(), 10u) << "seed " << seed;
    int found = 0;
    for (const uint32_t id : with_loop) found += loop_found.count(id);
    EXPECT_GE(found, 0.9 * with_loop.size()) << "seed " << seed;
  }
}

}  // namespace
}  // namespace ramap
