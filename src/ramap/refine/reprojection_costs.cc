#include "ramap/refine/reprojection_costs.h"

#include <ceres/jet.h>
#include <ceres/sized_cost_function.h>

#include "ramap/geometry/camera_distortion.h"

namespace ramap {
namespace {

using RowMajor2x3 = Eigen::Matrix<double, 2, 3, Eigen::RowMajor>;
using RowMajor2x7 = Eigen::Matrix<double, 2, 7, Eigen::RowMajor>;

// The chain rule from d(residual)/d(camera-frame point) to the pose and point blocks.
void WritePoseAndPointJacobians(const Eigen::Matrix<double, 2, 3>& d_x, const Eigen::Quaterniond& q,
                                const Eigen::Vector3d& X, double** jacobians) {
  if (jacobians[0] != nullptr) {
    Eigen::Map<RowMajor2x7> d_pose(jacobians[0]);
    d_pose.leftCols<4>() = d_x * RotatedPointJacobian(q, X);
    d_pose.rightCols<3>() = d_x;
  }
  if (jacobians[1] != nullptr) {
    Eigen::Map<RowMajor2x3> d_point(jacobians[1]);
    d_point = d_x * q.toRotationMatrix();
  }
}

class NormalizedPlaneCost : public ceres::SizedCostFunction<2, 7, 3> {
 public:
  NormalizedPlaneCost(const Eigen::Vector3d& bearing, double focal_px)
      : observed_(bearing.head<2>() / bearing.z()), focal_(focal_px) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> t(parameters[0] + 4);
    const Eigen::Map<const Eigen::Vector3d> X(parameters[1]);
    const Eigen::Vector3d x = q * X + t;
    const double inverse_z = 1.0 / x.z();
    residuals[0] = focal_ * (x.x() * inverse_z - observed_.x());
    residuals[1] = focal_ * (x.y() * inverse_z - observed_.y());
    if (jacobians == nullptr) return true;
    const double f_z = focal_ * inverse_z;
    Eigen::Matrix<double, 2, 3> d_x;
    d_x << f_z, 0.0, -f_z * x.x() * inverse_z, 0.0, f_z, -f_z * x.y() * inverse_z;
    WritePoseAndPointJacobians(d_x, q, X, jacobians);
    return true;
  }

 private:
  Eigen::Vector2d observed_;
  double focal_;
};

template <int kNumParams>
class PixelCost : public ceres::SizedCostFunction<2, 7, 3, kNumParams> {
 public:
  PixelCost(CameraModel model, const Eigen::Vector2d& keypoint)
      : model_(model), observed_(keypoint) {}

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override {
    const Eigen::Map<const Eigen::Quaterniond> q(parameters[0]);
    const Eigen::Map<const Eigen::Vector3d> t(parameters[0] + 4);
    const Eigen::Map<const Eigen::Vector3d> X(parameters[1]);
    const double* params = parameters[2];
    const Eigen::Vector3d x = q * X + t;
    if (jacobians == nullptr) {
      double pixel[2];
      if (!ProjectPerspective(model_, params, x.data(), pixel)) return false;
      residuals[0] = pixel[0] - observed_.x();
      residuals[1] = pixel[1] - observed_.y();
      return true;
    }
    // Dual numbers in the camera-frame point (3) and the intrinsics only.
    using Dual = ceres::Jet<double, 3 + kNumParams>;
    Dual point[3];
    for (int k = 0; k < 3; ++k) point[k] = Dual(x[k], k);
    Dual intrinsics[kNumParams];
    for (int k = 0; k < kNumParams; ++k) intrinsics[k] = Dual(params[k], 3 + k);
    Dual pixel[2];
    if (!ProjectPerspective(model_, intrinsics, point, pixel)) return false;
    residuals[0] = pixel[0].a - observed_.x();
    residuals[1] = pixel[1].a - observed_.y();
    Eigen::Matrix<double, 2, 3> d_x;
    for (int row = 0; row < 2; ++row) d_x.row(row) = pixel[row].v.template head<3>().transpose();
    WritePoseAndPointJacobians(d_x, q, X, jacobians);
    if (jacobians[2] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 2, kNumParams, Eigen::RowMajor>> d_params(jacobians[2]);
      for (int row = 0; row < 2; ++row)
        d_params.row(row) = pixel[row].v.template tail<kNumParams>().transpose();
    }
    return true;
  }

 private:
  CameraModel model_;
  Eigen::Vector2d observed_;
};

}  // namespace

Eigen::Matrix<double, 3, 4> RotatedPointJacobian(const Eigen::Quaterniond& q,
                                                 const Eigen::Vector3d& X) {
  // Eigen rotates by X + 2w (v x X) + 2 v x (v x X), with v = (x, y, z) and
  // v x (v x X) = v (v.X) - X (v.v).
  const Eigen::Vector3d v = q.vec();
  const double w = q.w();
  Eigen::Matrix3d cross_X;
  cross_X << 0.0, -X.z(), X.y(), X.z(), 0.0, -X.x(), -X.y(), X.x(), 0.0;
  Eigen::Matrix<double, 3, 4> jacobian;
  jacobian.leftCols<3>() = -2.0 * w * cross_X + 2.0 * (v.dot(X) * Eigen::Matrix3d::Identity() +
                                                       v * X.transpose() - 2.0 * X * v.transpose());
  jacobian.col(3) = 2.0 * v.cross(X);
  return jacobian;
}

ceres::CostFunction* NewNormalizedPlaneCost(const Eigen::Vector3d& bearing, double focal_px) {
  return new NormalizedPlaneCost(bearing, focal_px);
}

ceres::CostFunction* NewPixelCost(CameraModel model, const Eigen::Vector2d& keypoint) {
  switch (NumCameraParams(model)) {
    case 3:
      return new PixelCost<3>(model, keypoint);
    case 4:
      return new PixelCost<4>(model, keypoint);
    case 5:
      return new PixelCost<5>(model, keypoint);
    case 8:
      return new PixelCost<8>(model, keypoint);
    case 12:
      return new PixelCost<12>(model, keypoint);
  }
  return nullptr;
}

}  // namespace ramap
