#include "ramap/refine/reprojection_costs.h"

#include <ceres/gradient_checker.h>
#include <ceres/manifold.h>
#include <gtest/gtest.h>

#include <memory>
#include <random>
#include <vector>

namespace ramap {
namespace {

// The written-out Jacobians against Ceres' numeric differentiation of the same residual, at
// random poses and points in front of the camera (a wrong term is off by far more than the
// tolerance, which numeric differences of the smallest distortion terms need).
void ExpectJacobiansMatchNumericDifferentiation(const ceres::CostFunction& cost,
                                                std::vector<double> intrinsics, std::mt19937* rng) {
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    Eigen::Quaterniond q(uniform(*rng), uniform(*rng), uniform(*rng), uniform(*rng));
    q.normalize();
    Eigen::Vector3d X(uniform(*rng), uniform(*rng), uniform(*rng));
    // A translation that puts the point 4-6 units in front of the camera.
    const Eigen::Vector3d t =
        -(q * X) + Eigen::Vector3d(uniform(*rng), uniform(*rng), 5 + uniform(*rng));
    PoseBlock pose;
    pose << q.coeffs(), t;
    std::vector<double*> parameters = {pose.data(), X.data()};
    if (!intrinsics.empty()) parameters.push_back(intrinsics.data());
    ceres::NumericDiffOptions numeric;
    const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
    ceres::GradientChecker checker(&cost, no_manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(parameters.data(), 1e-5, &results)) << results.error_log;
  }
}

TEST(ReprojectionCosts, NormalizedPlaneJacobiansMatchNumericDifferentiation) {
  std::mt19937 rng(3);
  const std::unique_ptr<ceres::CostFunction> cost(
      NewNormalizedPlaneCost(Eigen::Vector3d(0.1, -0.2, 1.0).normalized(), 700.0));
  ExpectJacobiansMatchNumericDifferentiation(*cost, {}, &rng);
}

TEST(ReprojectionCosts, PixelJacobiansMatchNumericDifferentiationForEveryModel) {
  std::mt19937 rng(4);
  const Eigen::Vector2d keypoint(310.0, 250.0);
  const std::vector<std::pair<CameraModel, std::vector<double>>> cameras = {
      {CameraModel::kSimplePinhole, {500, 320, 240}},
      {CameraModel::kPinhole, {500, 510, 320, 240}},
      {CameraModel::kSimpleRadial, {500, 320, 240, -0.1}},
      {CameraModel::kRadial, {500, 320, 240, -0.1, 0.02}},
      {CameraModel::kOpenCV, {500, 510, 320, 240, -0.1, 0.02, 0.001, -0.002}},
      {CameraModel::kFullOpenCV,
       {500, 510, 320, 240, -0.1, 0.02, 0.001, -0.002, 0.001, 0.01, 0.002, 0.001}}};
  for (const auto& [model, params] : cameras) {
    SCOPED_TRACE(NumCameraParams(model));
    const std::unique_ptr<ceres::CostFunction> cost(NewPixelCost(model, keypoint));
    ASSERT_NE(cost, nullptr);
    ExpectJacobiansMatchNumericDifferentiation(*cost, params, &rng);
  }
}

TEST(ReprojectionCosts, RotatedPointJacobianIsTheDerivativeOfEigensRotation) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.9, 0.1, -0.3, 0.2).normalized();
  const Eigen::Vector3d X(0.5, -1.0, 2.0);
  const Eigen::Matrix<double, 3, 4> jacobian = RotatedPointJacobian(q, X);
  const double h = 1e-6;
  for (int k = 0; k < 4; ++k) {
    Eigen::Quaterniond plus = q, minus = q;
    plus.coeffs()[k] += h;
    minus.coeffs()[k] -= h;
    // Eigen's formula, not the normalised rotation: the residuals use q * X as it stands.
    const Eigen::Vector3d numeric = ((plus * X) - (minus * X)) / (2 * h);
    EXPECT_LT((jacobian.col(k) - numeric).norm(), 1e-6) << "coefficient " << k;
  }
}

}  // namespace
}  // namespace ramap
