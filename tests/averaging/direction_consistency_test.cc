// Pair directions checked against their triangles (averaging/direction_consistency.h), and
// translation averaging's rejection of the rows its solution marks as outliers.
#include "ramap/averaging/direction_consistency.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <random>
#include <set>

#include "translation_scenes.h"

namespace ramap {
namespace {

using namespace translation_test;

constexpr double kDeg = M_PI / 180.0;

TEST(AngleToCone, InsideOnTheEdgesAndOutside) {
  const Eigen::Vector3d u = Eigen::Vector3d::UnitX();
  const Eigen::Vector3d v = Eigen::Vector3d::UnitY();
  EXPECT_NEAR(AngleToCone(Eigen::Vector3d(1, 1, 0).normalized(), u, v), 0.0, 1e-12);
  EXPECT_NEAR(AngleToCone(u, u, v), 0.0, 1e-12);
  // Above the wedge: the angle to its projection onto the plane.
  EXPECT_NEAR(AngleToCone(Eigen::Vector3d(1, 1, std::sqrt(2.0)).normalized(), u, v), M_PI / 4,
              1e-12);
  // In the plane, behind the wedge: the angle to the nearer edge.
  EXPECT_NEAR(AngleToCone(Eigen::Vector3d(-1, -0.2, 0).normalized(), u, v),
              M_PI / 2 + std::atan(0.2), 1e-12);
  // Forward motion: parallel edges make a ray, and the opposite direction is 180 deg off.
  EXPECT_NEAR(AngleToCone(-u, u, u), M_PI, 1e-12);
}

// Cameras along a 90 deg arc of a 60 m circle, 1 m apart, looking along it: a stretch of a drive
// in one window. Points on both sides.
Scene Arc(int num_cameras, int num_points, std::mt19937& rng) {
  Scene scene;
  const double radius = 60.0;
  for (int i = 0; i < num_cameras; ++i) {
    const double a = 1.0 * i / radius;
    const Eigen::Vector3d center(radius * (1 - std::cos(a)), 0.0, radius * std::sin(a));
    const Eigen::Vector3d forward(std::sin(a), 0.0, std::cos(a));
    const Eigen::Vector3d right = Eigen::Vector3d::UnitY().cross(forward).normalized();
    Eigen::Matrix3d world_from_cam;
    world_from_cam << right, forward.cross(right), forward;
    scene.rotations[i + 1] = Eigen::Quaterniond(world_from_cam.transpose());
    scene.centers[i + 1] = center;
  }
  std::uniform_real_distribution<double> along(0.0, num_cameras + 30.0), side(4.0, 10.0),
      height(-2.0, 4.0);
  std::bernoulli_distribution left(0.5);
  for (int p = 0; p < num_points; ++p) {
    const double a = along(rng) / radius;
    const double r = radius + (left(rng) ? -1 : 1) * side(rng);
    scene.points.emplace_back(radius - r * std::cos(a), height(rng), r * std::sin(a));
  }
  return scene;
}

// Every direction turned by a small random angle (noise), and the `every`-th one by `min_deg` to
// `max_deg` about a random axis (aliased); returns the aliased ones' pair keys.
std::set<std::pair<uint32_t, uint32_t>> Corrupt(std::vector<PairDirection>* directions, int every,
                                                double min_deg, double max_deg, std::mt19937* rng) {
  std::normal_distribution<double> noise(0.0, 0.05 * kDeg);
  std::uniform_real_distribution<double> off(min_deg * kDeg, max_deg * kDeg);
  std::set<std::pair<uint32_t, uint32_t>> aliased;
  for (size_t k = 0; k < directions->size(); ++k) {
    PairDirection& pair = (*directions)[k];
    const Eigen::Vector3d axis = Eigen::Vector3d::Random().cross(pair.direction).normalized();
    const double angle = k % every == 3 ? off(*rng) : noise(*rng);
    pair.direction = Eigen::AngleAxisd(angle, axis) * pair.direction;
    if (k % every == 3) aliased.insert({pair.image_id1, pair.image_id2});
  }
  return aliased;
}

std::set<std::pair<uint32_t, uint32_t>> RejectedPairs(const DirectionConsistencyResult& result) {
  std::set<std::pair<uint32_t, uint32_t>> rejected;
  for (const RejectedDirection& r : result.rejected) rejected.insert({r.image_id1, r.image_id2});
  return rejected;
}

TranslationAveragingOptions WithoutRowRejection() {
  TranslationAveragingOptions options;
  options.max_rejection_rounds = 0;
  return options;
}

// A window of 30 frames with 10% of its pairs aliased by 3-8 deg: the cycle check finds those that
// close cycles, and the window is then solved as well as without any.
TEST(DirectionConsistency, AWindowWithTenPercentAliasedPairsIsSolvedWithinNoise) {
  std::mt19937 rng(5);
  Scene arc = Arc(30, 1500, rng);
  auto [scene, tracks, directions] = ObserveScene(std::move(arc), 0.05 * kDeg, &rng);
  std::vector<PairDirection> clean = directions;
  Corrupt(&clean, 1000000, 0, 0, &rng);  // noise only
  const std::set<std::pair<uint32_t, uint32_t>> aliased = Corrupt(&directions, 10, 3, 8, &rng);
  ASSERT_GE(aliased.size(), 20u);

  const DirectionConsistencyResult checked =
      CheckDirectionCycles(directions, DirectionConsistencyOptions());
  const std::set<std::pair<uint32_t, uint32_t>> rejected = RejectedPairs(checked);
  // Neighbouring frames close no cycle whose legs point the same way (no frame between them):
  // those are left to translation averaging's own rejection.
  size_t found = 0;
  for (const auto& pair : aliased) found += rejected.count(pair);
  EXPECT_GE(found, aliased.size() * 85 / 100);
  EXPECT_LE(rejected.size(), found + directions.size() / 50);

  const double clean_error =
      RelativeCenterError(scene, AverageTranslations(scene.rotations, clean, tracks.tracks,
                                                     tracks.bearings, WithoutRowRejection()));
  const double checked_error = RelativeCenterError(
      scene, AverageTranslations(scene.rotations, checked.kept, tracks.tracks, tracks.bearings));
  EXPECT_LT(checked_error, 1.5 * clean_error + 1e-3);
}

// A direction pointing back along its pair (its tracks and neighbours say forward) is rejected,
// with its reason: 180 deg off its triangles.
TEST(DirectionConsistency, APairDirectionOppositeToItsTracksIsRejected) {
  std::mt19937 rng(6);
  Scene arc = Arc(20, 1000, rng);
  auto [scene, tracks, directions] = ObserveScene(std::move(arc), 0.0, &rng);
  const auto flipped = std::find_if(directions.begin(), directions.end(), [](const auto& d) {
    return d.image_id1 == 8 && d.image_id2 == 12;
  });
  ASSERT_NE(flipped, directions.end());
  flipped->direction = -flipped->direction;
  const DirectionConsistencyResult checked =
      CheckDirectionCycles(directions, DirectionConsistencyOptions());
  ASSERT_EQ(checked.rejected.size(), 1u);
  EXPECT_EQ(checked.rejected[0].image_id1, 8u);
  EXPECT_EQ(checked.rejected[0].image_id2, 12u);
  EXPECT_GT(checked.rejected[0].consistency_deg, 170.0);
  EXPECT_EQ(checked.kept.size(), directions.size() - 1);
  // Switched off, nothing is rejected.
  DirectionConsistencyOptions off;
  off.mode = DirectionCheckMode::kOff;
  EXPECT_EQ(CheckDirectionCycles(directions, off).kept.size(), directions.size());
}

// A ring closes its loop between its last and first cameras; a loop pair's direction turned by
// 20 deg breaks the cycles it closes and is rejected with its residual, threshold and cycles.
TEST(DirectionConsistency, ALoopEdgeThatBreaksItsCyclesIsRejectedWithItsReason) {
  std::mt19937 rng(7);
  Scene ring = Ring(30, 600, rng);
  auto [scene, tracks, directions] = ObserveScene(std::move(ring), 0.0, &rng);
  // Cameras 27 and 3 are six apart across the closure: five cameras between them close cycles.
  const auto loop = std::find_if(directions.begin(), directions.end(), [](const auto& d) {
    return d.image_id1 == 3 && d.image_id2 == 27;
  });
  ASSERT_NE(loop, directions.end());
  // Out of the ring's plane, where every cycle's legs lie.
  const Eigen::Vector3d axis = loop->direction.cross(Eigen::Vector3d::UnitY()).normalized();
  loop->direction = Eigen::AngleAxisd(20 * kDeg, axis) * loop->direction;
  const DirectionConsistencyResult checked =
      CheckDirectionCycles(directions, DirectionConsistencyOptions());
  ASSERT_EQ(checked.rejected.size(), 1u);
  const RejectedDirection& rejected = checked.rejected[0];
  EXPECT_EQ(rejected.image_id1, loop->image_id1);
  EXPECT_EQ(rejected.image_id2, loop->image_id2);
  EXPECT_GT(rejected.consistency_deg, 10.0);
  EXPECT_LT(rejected.consistency_deg, 20.0 + 1e-9);
  EXPECT_GT(rejected.consistency_deg, rejected.threshold_deg);
  EXPECT_GE(rejected.num_cycles, 3);
  EXPECT_EQ(rejected.round, 1);
}

// The threshold follows the noise: the same perturbations ten times larger give a threshold about
// ten times higher (above its floor), so that noise alone is not rejected.
TEST(DirectionConsistency, TheAdaptiveThresholdFollowsTheNoise) {
  std::mt19937 rng(8);
  Scene arc = Arc(30, 1500, rng);
  const ObservedScene observed = ObserveScene(std::move(arc), 0.0, &rng);
  DirectionConsistencyOptions options;
  options.min_threshold_deg = 0.0;
  std::vector<double> thresholds;
  for (const double noise_deg : {0.2, 2.0}) {
    std::mt19937 same(9);
    std::normal_distribution<double> noise(0.0, noise_deg * kDeg);
    std::vector<PairDirection> directions = observed.directions;
    for (PairDirection& pair : directions) {
      const Eigen::Vector3d axis = pair.direction.unitOrthogonal();
      const double angle = noise(same);
      const double turn = 2 * M_PI * std::uniform_real_distribution<double>(0, 1)(same);
      pair.direction =
          Eigen::AngleAxisd(angle, Eigen::AngleAxisd(turn, pair.direction) * axis) * pair.direction;
    }
    const DirectionConsistencyResult checked = CheckDirectionCycles(directions, options);
    thresholds.push_back(checked.threshold_deg);
    EXPECT_LT(checked.rejected.size(), directions.size() / 20) << noise_deg << " deg";
  }
  // Not exactly ten: noise that stays inside a cycle's cone costs nothing at either level.
  EXPECT_GT(thresholds[1] / thresholds[0], 7.0);
  EXPECT_LT(thresholds[1] / thresholds[0], 14.0);
}

// Translation averaging's own rejection: wrong directions that no triangle check removed (every
// fifth pair of a ring, random) are dropped after the first solve, and the second solve is as
// accurate as with the right ones alone.
TEST(TranslationRowRejection, RemovesWrongDirectionsTheSolutionDoesNotFit) {
  std::mt19937 rng(9);
  auto [scene, tracks, directions] = NoisyRing(&rng);
  std::vector<PairDirection> right;
  std::uniform_real_distribution<double> uniform(-1, 1);
  for (size_t k = 0; k < directions.size(); ++k) {
    if (k % 5 == 0) {
      directions[k].direction =
          Eigen::Vector3d(uniform(rng), uniform(rng), uniform(rng)).normalized();
    } else {
      right.push_back(directions[k]);
    }
  }
  const TranslationAveragingResult with =
      AverageTranslations(scene.rotations, directions, tracks.tracks, tracks.bearings);
  const TranslationAveragingResult without = AverageTranslations(
      scene.rotations, directions, tracks.tracks, tracks.bearings, WithoutRowRejection());
  const TranslationAveragingResult truth_only =
      AverageTranslations(scene.rotations, right, tracks.tracks, tracks.bearings);
  EXPECT_GE(with.num_rejected_rows, static_cast<int>(directions.size() / 5) * 9 / 10);
  EXPECT_EQ(without.num_rejected_rows, 0);
  // The pair rows dropped are named, each a wrong one, missed by more than its threshold.
  std::set<std::pair<uint32_t, uint32_t>> wrong;
  for (size_t k = 0; k < directions.size(); k += 5) {
    wrong.insert({directions[k].image_id1, directions[k].image_id2});
  }
  EXPECT_GE(with.rejected_pair_rows.size(), wrong.size() * 8 / 10);
  for (const RejectedPairRow& row : with.rejected_pair_rows) {
    EXPECT_TRUE(wrong.count({row.image_id1, row.image_id2}))
        << row.image_id1 << " " << row.image_id2;
    EXPECT_GT(row.miss_deg, row.threshold_deg);
  }
  EXPECT_LT(RelativeCenterError(scene, with), 1.5 * RelativeCenterError(scene, truth_only) + 1e-3);
  EXPECT_LT(RelativeCenterError(scene, with), RelativeCenterError(scene, without));
}

}  // namespace
}  // namespace ramap
