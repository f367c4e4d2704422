// EstimateAbsolutePose and AbsolutePoseInliers on hand-made bearings of known points: the exact
// pose without noise, its inliers, and no pose when too few points agree.
#include "ramap/geometry/absolute_pose.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>

namespace ramap {
namespace {

// A camera turned about an oblique axis, 6 units from the world's origin, and `num_points` points
// in its view at depths 3 to 12, with their exact unit bearings.
struct Observed {
  Rigid3d cam_from_world;
  std::vector<Eigen::Vector3d> bearings, points;
};

Observed Observe(int num_points, uint32_t seed = 2) {
  Observed observed;
  const Eigen::Quaterniond rotation(Eigen::AngleAxisd(0.6, Eigen::Vector3d(1, -1, 2).normalized()));
  observed.cam_from_world = Rigid3d(rotation, Eigen::Vector3d(0.5, -1.0, 6.0));
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> lateral(-0.5, 0.5), depth(3.0, 12.0);
  const Rigid3d world_from_cam = observed.cam_from_world.Inverse();
  for (int k = 0; k < num_points; ++k) {
    const double z = depth(rng);
    const Eigen::Vector3d in_camera(lateral(rng) * z, lateral(rng) * z, z);
    observed.points.push_back(world_from_cam * in_camera);
    observed.bearings.push_back(in_camera.normalized());
  }
  return observed;
}

// `bearing` turned by `angle_rad` about an axis perpendicular to it.
Eigen::Vector3d TurnedBy(const Eigen::Vector3d& bearing, double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, bearing.unitOrthogonal()) * bearing;
}

TEST(AbsolutePose, ExactPoseAndEveryInlierWithoutNoise) {
  const Observed observed = Observe(60);
  const std::optional<AbsolutePose> pose =
      EstimateAbsolutePose(observed.bearings, observed.points, AbsolutePoseOptions());
  ASSERT_TRUE(pose.has_value());
  // P3P and OpenGV's refinement on exact rays: the refinement stops at its own tolerance, about
  // 1e-8 units on a camera 6 units away; 1e-7 leaves a margin.
  EXPECT_LT(pose->cam_from_world.rotation.angularDistance(observed.cam_from_world.rotation), 1e-8);
  EXPECT_LT((pose->cam_from_world.translation - observed.cam_from_world.translation).norm(), 1e-7);
  EXPECT_EQ(pose->inliers.size(), 60u);
}

TEST(AbsolutePose, WrongBearingsAreLeftOutOfTheInliers) {
  Observed observed = Observe(80);
  std::vector<int> correct;
  for (int k = 0; k < 80; ++k) {
    if (k % 4 == 0) {
      observed.bearings[k] = TurnedBy(observed.bearings[k], 0.2);  // 50 times the bound
    } else {
      correct.push_back(k);
    }
  }
  const std::optional<AbsolutePose> pose =
      EstimateAbsolutePose(observed.bearings, observed.points, AbsolutePoseOptions());
  ASSERT_TRUE(pose.has_value());
  EXPECT_EQ(pose->inliers, correct);
  // The refinement runs on the correct bearings alone: the pose is still exact (as above).
  EXPECT_LT(pose->cam_from_world.rotation.angularDistance(observed.cam_from_world.rotation), 1e-8);
}

TEST(AbsolutePose, FewerAgreeingPointsThanTheMinimumGiveNoPose) {
  AbsolutePoseOptions options;
  options.min_num_inliers = 30;
  const Observed enough = Observe(30);
  EXPECT_TRUE(EstimateAbsolutePose(enough.bearings, enough.points, options).has_value());
  const Observed too_few = Observe(29);
  EXPECT_FALSE(EstimateAbsolutePose(too_few.bearings, too_few.points, options).has_value());
  // 40 points of which 20 are wrong: 20 agree, fewer than 30.
  Observed half_wrong = Observe(40);
  for (int k = 0; k < 40; k += 2) half_wrong.bearings[k] = TurnedBy(half_wrong.bearings[k], 0.3);
  EXPECT_FALSE(EstimateAbsolutePose(half_wrong.bearings, half_wrong.points, options).has_value());
}

TEST(AbsolutePose, InliersAreTheBearingsWithinTheAngleOfTheirPoints) {
  Observed observed = Observe(6);
  const double bound = 4e-3;
  // Angles of each bearing from its point's direction: within, at 99% of, and beyond the bound.
  const std::vector<double> angles = {0.0,          0.5 * bound, 0.99 * bound,
                                      1.01 * bound, 2 * bound,   M_PI / 2};
  for (int k = 0; k < 6; ++k) observed.bearings[k] = TurnedBy(observed.bearings[k], angles[k]);
  EXPECT_EQ(AbsolutePoseInliers(observed.cam_from_world, observed.bearings, observed.points, bound),
            (std::vector<int>{0, 1, 2}));
  // Bearings need not be unit: only their directions count.
  for (Eigen::Vector3d& bearing : observed.bearings) bearing *= 3.0;
  EXPECT_EQ(AbsolutePoseInliers(observed.cam_from_world, observed.bearings, observed.points, bound),
            (std::vector<int>{0, 1, 2}));
}

TEST(AbsolutePose, PointsBehindTheCameraAreNotInliers) {
  Observed observed = Observe(3);
  // The bearing opposite to the direction to its point: 180 degrees off.
  observed.bearings[1] = -observed.bearings[1];
  EXPECT_EQ(AbsolutePoseInliers(observed.cam_from_world, observed.bearings, observed.points, 0.01),
            (std::vector<int>{0, 2}));
}

}  // namespace
}  // namespace ramap
