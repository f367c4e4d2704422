// EstimatePairDirection's contract beyond the recovery tests in translation_averaging_test.cc: the
// world frame and sign of the result, the matches it needs, and the far points it ignores.
#include "ramap/averaging/pair_directions.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace ramap {
namespace {

// Noise-free bearings of `num_points` points at depths [min_depth, max_depth] in front of camera 1
// (the world origin, looking along +z), seen from two cameras with the given cam_from_world
// rotations and centres.
struct ExactPair {
  Eigen::Quaterniond rotation1, rotation2;
  Eigen::Vector3d center1, center2;
  std::vector<Eigen::Vector3d> bearings1, bearings2;
};

ExactPair MakePair(const Eigen::Quaterniond& rotation1, const Eigen::Quaterniond& rotation2,
                   const Eigen::Vector3d& center1, const Eigen::Vector3d& center2, int num_points,
                   double min_depth, double max_depth, uint32_t seed = 3) {
  ExactPair pair{rotation1, rotation2, center1, center2, {}, {}};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lateral(-0.4, 0.4), depth(min_depth, max_depth);
  for (int k = 0; k < num_points; ++k) {
    // A point in camera 1's view, so that both cameras (which look roughly the same way) see it.
    const double z = depth(rng);
    const Eigen::Vector3d in_camera1(lateral(rng) * z, lateral(rng) * z, z);
    const Eigen::Vector3d world = rotation1.conjugate() * in_camera1 + center1;
    pair.bearings1.push_back((rotation1 * (world - center1)).normalized());
    pair.bearings2.push_back((rotation2 * (world - center2)).normalized());
  }
  return pair;
}

ExactPair TurnedPair(int num_points = 200) {
  const Eigen::Quaterniond r1(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()));
  const Eigen::Quaterniond r2 =
      Eigen::Quaterniond(Eigen::AngleAxisd(0.2, Eigen::Vector3d(0, 1, 0.3).normalized())) * r1;
  return MakePair(r1, r2, Eigen::Vector3d(4, -2, 1), Eigen::Vector3d(5.5, -1.2, 1.6), num_points,
                  3.0, 15.0);
}

double AngleRad(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

// Noise-free rays leave only the rounding of a 3x3 eigensolver: far below 1e-9 rad.
constexpr double kExactRad = 1e-9;

TEST(PairDirections, WorldDirectionOfTheBaselineWhateverBothRotations) {
  const ExactPair pair = TurnedPair();
  const auto direction =
      EstimatePairDirection(pair.rotation1, pair.rotation2, pair.bearings1, pair.bearings2);
  ASSERT_TRUE(direction.has_value());
  EXPECT_NEAR(direction->norm(), 1.0, 1e-12);
  EXPECT_LT(AngleRad(*direction, pair.center2 - pair.center1), kExactRad);
}

TEST(PairDirections, SwappingTheCamerasReversesTheDirection) {
  const ExactPair pair = TurnedPair();
  const auto forward =
      EstimatePairDirection(pair.rotation1, pair.rotation2, pair.bearings1, pair.bearings2);
  const auto backward =
      EstimatePairDirection(pair.rotation2, pair.rotation1, pair.bearings2, pair.bearings1);
  ASSERT_TRUE(forward.has_value());
  ASSERT_TRUE(backward.has_value());
  EXPECT_LT(AngleRad(*backward, -*forward), kExactRad);
}

TEST(PairDirections, TurningTheWorldTurnsTheDirection) {
  // The same cameras in a world turned by G: cam_from_world' = R G^-1, c' = G c; the bearings are
  // unchanged, and the direction must turn with the world.
  const ExactPair pair = TurnedPair();
  const Eigen::Quaterniond world(Eigen::AngleAxisd(1.1, Eigen::Vector3d(-2, 1, 0.5).normalized()));
  const auto original =
      EstimatePairDirection(pair.rotation1, pair.rotation2, pair.bearings1, pair.bearings2);
  const auto turned =
      EstimatePairDirection(pair.rotation1 * world.conjugate(), pair.rotation2 * world.conjugate(),
                            pair.bearings1, pair.bearings2);
  ASSERT_TRUE(original.has_value());
  ASSERT_TRUE(turned.has_value());
  EXPECT_LT(AngleRad(*turned, world * *original), kExactRad);
}

TEST(PairDirections, FewerUsableMatchesThanTheMinimumGiveNoDirection) {
  PairDirectionOptions options;
  options.min_num_matches = 15;
  const ExactPair enough = TurnedPair(15);
  EXPECT_TRUE(EstimatePairDirection(enough.rotation1, enough.rotation2, enough.bearings1,
                                    enough.bearings2, options)
                  .has_value());
  const ExactPair too_few = TurnedPair(14);
  EXPECT_FALSE(EstimatePairDirection(too_few.rotation1, too_few.rotation2, too_few.bearings1,
                                     too_few.bearings2, options)
                   .has_value());
}

TEST(PairDirections, FarPointsCarryNoDirectionUnlessTheRayAngleBoundAllowsThem) {
  // A baseline of 1 and points 300 to 400 away: every pair of rays meets at under
  // 1 / 300 rad = 0.19 deg, below the default bound of 0.5 deg.
  const Eigen::Quaterniond identity = Eigen::Quaterniond::Identity();
  const ExactPair far = MakePair(identity, identity, Eigen::Vector3d::Zero(),
                                 Eigen::Vector3d(1, 0, 0), 200, 300.0, 400.0);
  EXPECT_FALSE(EstimatePairDirection(far.rotation1, far.rotation2, far.bearings1, far.bearings2)
                   .has_value());
  // Below their angle (0.14 to 0.19 deg), the same rays give the baseline; they are noise-free, so
  // their small angles cost only a little precision (1e-7 rad).
  PairDirectionOptions options;
  options.min_ray_angle_deg = 0.05;
  const auto direction =
      EstimatePairDirection(far.rotation1, far.rotation2, far.bearings1, far.bearings2, options);
  ASSERT_TRUE(direction.has_value());
  EXPECT_LT(AngleRad(*direction, Eigen::Vector3d::UnitX()), 1e-7);
}

}  // namespace
}  // namespace ramap
