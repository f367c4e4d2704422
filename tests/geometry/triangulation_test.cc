#include "ramap/geometry/triangulation.h"

#include <gtest/gtest.h>

namespace ramap {
namespace {

Rigid3d CameraAt(const Eigen::Vector3d& center, double yaw) {
  const Eigen::Quaterniond rotation(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitY()));
  return Rigid3d(rotation, -(rotation * center));
}

RayObservation Observe(const Rigid3d& pose, const Eigen::Vector3d& X) {
  return {pose, (pose * X).normalized()};
}

TEST(Triangulation, ExactFromManyViews) {
  const Eigen::Vector3d X(0.3, -0.2, 5.0);
  std::vector<RayObservation> observations;
  for (int i = 0; i < 5; ++i)
    observations.push_back(Observe(CameraAt({0.5 * i, 0.1 * i, 0}, 0.05 * i), X));
  const auto point = TriangulatePoint(observations);
  ASSERT_TRUE(point.has_value());
  EXPECT_LT((point->xyz - X).norm(), 1e-9);
  EXPECT_EQ(point->inliers.size(), 5u);
  EXPECT_GT(point->max_triangulation_angle_deg, 1.5);
}

TEST(Triangulation, DropsTheWrongObservation) {
  const Eigen::Vector3d X(0.3, -0.2, 5.0);
  std::vector<RayObservation> observations;
  for (int i = 0; i < 4; ++i) observations.push_back(Observe(CameraAt({0.5 * i, 0, 0}, 0), X));
  observations[2].bearing = (observations[2].bearing + Eigen::Vector3d(0.1, 0, 0)).normalized();
  const auto point = TriangulatePoint(observations);
  ASSERT_TRUE(point.has_value());
  EXPECT_EQ(point->inliers, (std::vector<int>{0, 1, 3}));
  EXPECT_LT((point->xyz - X).norm(), 1e-9);
}

TEST(Triangulation, RejectsSmallAngleAndPointsBehind) {
  const Eigen::Vector3d far(0, 0, 1000.0);
  std::vector<RayObservation> observations = {Observe(CameraAt({0, 0, 0}, 0), far),
                                              Observe(CameraAt({0.1, 0, 0}, 0), far)};
  EXPECT_FALSE(TriangulatePoint(observations).has_value());
  // Rays that meet behind both cameras.
  const Eigen::Vector3d behind(0, 0, -5.0);
  observations = {{CameraAt({0, 0, 0}, 0), -(CameraAt({0, 0, 0}, 0) * behind).normalized()},
                  {CameraAt({1, 0, 0}, 0), -(CameraAt({1, 0, 0}, 0) * behind).normalized()}};
  EXPECT_FALSE(TriangulatePoint(observations).has_value());
  // Not enough observations, or NaN.
  EXPECT_FALSE(TriangulatePoint({Observe(CameraAt({0, 0, 0}, 0), far)}).has_value());
  observations = {Observe(CameraAt({0, 0, 0}, 0), Eigen::Vector3d(0, 0, 5)),
                  {CameraAt({1, 0, 0}, 0), Eigen::Vector3d::Constant(std::nan(""))}};
  EXPECT_FALSE(TriangulatePoint(observations).has_value());
}

TEST(Triangulation, TwoRayDepthsMeetTheOffsetAndParallelRaysHaveNone) {
  // A point at (1, 2, 6) seen from the origin and from (2, 0, 0): l1 ray1 - l2 ray2 = (2, 0, 0).
  const Eigen::Vector3d X(1, 2, 6), c2(2, 0, 0);
  const Eigen::Vector3d ray1 = X.normalized(), ray2 = (X - c2).normalized();
  const std::optional<Eigen::Vector2d> depths = TwoRayDepths(ray1, ray2, c2);
  ASSERT_TRUE(depths.has_value());
  EXPECT_NEAR((*depths)(0), X.norm(), 1e-12);
  EXPECT_NEAR((*depths)(1), (X - c2).norm(), 1e-12);
  // The opposite offset puts the point behind both cameras.
  const std::optional<Eigen::Vector2d> behind = TwoRayDepths(ray1, ray2, -c2);
  ASSERT_TRUE(behind.has_value());
  EXPECT_LT((*behind)(0), 0);
  EXPECT_LT((*behind)(1), 0);
  EXPECT_FALSE(TwoRayDepths(ray1, ray1, c2).has_value());
}

}  // namespace
}  // namespace ramap
