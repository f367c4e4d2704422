// Loop closure on a synthetic drive around a loop, matched sequentially only: the first solve's
// loop candidates join the end to the start, ramap's matcher verifies them from descriptors, and
// the second solve has them as loop edges.
#include "ramap/jobs/loop_closure.h"

#include <gtest/gtest.h>

#include <random>

#include "ramap/eval/pose_metrics.h"
#include "ramap/synthetic/synthetic_scene.h"
#include "test_support.h"

namespace ramap {
namespace {

// ORB-like 256-bit descriptors: one random pattern per 3D point, a few bits flipped in each image
// that sees it; clutter keypoints get patterns of their own. The matcher then finds the true
// matches by Hamming distance, as it would on real images.
void AddDescriptors(SyntheticScene* scene, uint64_t seed) {
  std::mt19937_64 random(seed);
  std::map<uint64_t, std::array<uint8_t, 32>> patterns;
  auto random_pattern = [&] {
    std::array<uint8_t, 32> pattern;
    for (uint8_t& byte : pattern) byte = static_cast<uint8_t>(random());
    return pattern;
  };
  for (const auto& [id, point] : scene->ground_truth.points3D) patterns[id] = random_pattern();
  std::uniform_int_distribution<int> bit(0, 255);
  for (const auto& [image_id, image] : scene->ground_truth.images) {
    Descriptors descriptors;
    descriptors.num_cols = 32;
    for (const Point2D& point : image.points2D) {
      std::array<uint8_t, 32> pattern =
          point.point3D_id == kInvalidPoint3DId ? random_pattern() : patterns.at(point.point3D_id);
      for (int flip = 0; flip < 8; ++flip) {
        const int b = bit(random);
        pattern[b / 8] ^= static_cast<uint8_t>(1u << (b % 8));
      }
      descriptors.data.insert(descriptors.data.end(), pattern.begin(), pattern.end());
    }
    scene->database.descriptors[image_id] = std::move(descriptors);
  }
}

SyntheticScene SequentialLoop() {
  SyntheticSceneOptions options;
  options.path = SyntheticPath::kLoop;
  options.num_images = 80;
  options.num_points = 3000;
  options.pixel_noise_sigma = 1.0;
  options.overlap = 5;
  options.loop_max_distance = 0.0;  // sequential matching only: the loop is for ramap to find
  options.seed = 21;
  SyntheticScene scene = BuildSyntheticScene(options);
  AddDescriptors(&scene, 5);
  return scene;
}

std::set<uint64_t> MatchedPairs(const FeatureDatabase& database) {
  std::set<uint64_t> pairs;
  for (const auto& [pair_id, geometry] : database.two_view_geometries) pairs.insert(pair_id);
  return pairs;
}

std::vector<uint32_t> Order(const Reconstruction& reconstruction) {
  std::vector<uint32_t> order;
  for (const auto& [id, image] : reconstruction.images) order.push_back(id);
  return order;
}

TEST(LoopCandidates, RevisitsAreFoundAndNeighboursAreNot) {
  const SyntheticScene scene = SequentialLoop();
  const std::vector<LoopCandidate> candidates =
      FindLoopCandidates(scene.ground_truth, Order(scene.ground_truth),
                         MatchedPairs(scene.database), LoopCandidateOptions());
  ASSERT_FALSE(candidates.empty());
  for (const LoopCandidate& candidate : candidates) {
    // The loop's end meets its start: one image among the first frames, one among the last.
    EXPECT_GE(candidate.image_id2 - candidate.image_id1, 20u);
    EXPECT_TRUE(candidate.image_id1 <= 10 && candidate.image_id2 >= 70)
        << candidate.image_id1 << " " << candidate.image_id2;
    EXPECT_LE(candidate.distance_baselines, 5.0);
    EXPECT_LE(candidate.view_angle_deg, 30.0);
  }
  // A straight drive revisits nothing.
  SyntheticSceneOptions line;
  line.num_images = 60;
  line.num_points = 500;
  const SyntheticScene straight = BuildSyntheticScene(line);
  EXPECT_TRUE(FindLoopCandidates(straight.ground_truth, Order(straight.ground_truth),
                                 MatchedPairs(straight.database), LoopCandidateOptions())
                  .empty());
}

TEST(LoopClosure, VerifiedLoopsEnterTheSecondSolve) {
  SyntheticScene scene = SequentialLoop();
  auto evaluate = [&](const MapperResult& result) {
    return test::EvaluateAgainstTruth(result.reconstructions.front(), scene);
  };
  const MapperResult first = RunMapper(scene.database, test::AveragingOnly(), "synthetic");
  ASSERT_EQ(first.summary.num_registered_images, 80);
  const LoopClosedMapperResult closed =
      RunMapperWithLoopClosure(&scene.database, test::AveragingOnly(), true, LoopClosureOptions(),
                               FeatureMatchingOptions(), "synthetic", nullptr, PosePriors());
  const LoopClosureSummary& closure = closed.closure;
  EXPECT_GT(closure.num_candidates, 0);
  EXPECT_GE(closure.num_verified, 3);
  EXPECT_EQ(closure.loops.size(), static_cast<size_t>(closure.num_verified));
  EXPECT_TRUE(closed.database_changed);
  const MapperResult& second = closed.result;
  // The view graph's loop edges (between keyframe windows) gain the revisits.
  EXPECT_GE(second.summary.num_loop_edges, first.summary.num_loop_edges + closure.num_verified);
  const PoseEvaluation before = evaluate(first), after = evaluate(second);
  std::printf(
      "loop closure: %d of %d candidates verified; ATE %.4f -> %.4f, rotation error "
      "max %.3f -> %.3f deg\n",
      closure.num_verified, closure.num_candidates, before.ate_rmse, after.ate_rmse,
      before.rotation_error_max_deg, after.rotation_error_max_deg);
  EXPECT_EQ(after.num_registered, 80);
  EXPECT_LT(after.ate_rmse, before.ate_rmse);
}

// A sequence whose first solve splits in two (every pair across frames 40 / 41 removed, as a
// stretch of blur would): the pairs between the two models are screened, matched from
// descriptors and verified, and the second solve joins them into one.
TEST(LoopClosure, PairsBetweenModelsJoinThem) {
  SyntheticScene scene = SequentialLoop();
  for (auto it = scene.database.two_view_geometries.begin();
       it != scene.database.two_view_geometries.end();) {
    const bool across = it->second.image_id1 <= 40 && it->second.image_id2 > 40;
    if (across) scene.database.matches.erase(it->first);
    it = across ? scene.database.two_view_geometries.erase(it) : std::next(it);
  }
  const MapperResult first = RunMapper(scene.database, test::AveragingOnly(), "synthetic");
  ASSERT_EQ(first.reconstructions.size(), 2u);
  FeatureDatabase unjoined = scene.database;
  const LoopClosedMapperResult closed =
      RunMapperWithLoopClosure(&scene.database, test::AveragingOnly(), true, LoopClosureOptions(),
                               FeatureMatchingOptions(), "synthetic", nullptr, PosePriors());
  const LoopClosureSummary& closure = closed.closure;
  // 40 x 40 images, sampled to every second of each: 400 pairs at most.
  EXPECT_GT(closure.num_bridge_pairs, 100);
  EXPECT_LE(closure.num_bridge_pairs, 400);
  EXPECT_GE(closure.num_bridge_pairs_verified, 2);
  const MapperResult& second = closed.result;
  EXPECT_EQ(second.reconstructions.size(), 1u);
  EXPECT_EQ(second.summary.num_registered_images, 80);
  LoopClosureOptions off;
  off.max_bridge_pairs = 0;
  EXPECT_EQ(MatchLoopCandidates(first, off, FeatureMatchingOptions(), &unjoined).num_bridge_pairs,
            0);
}

}  // namespace
}  // namespace ramap
